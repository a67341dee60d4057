#pragma once
// The demo's --script files: scripted input events, one per line (parsed apart from the demo so
// the parser can be tested and fuzzed without a window or a GPU).
#include <string>
#include <vector>

namespace weft::app {

/// At frame `frame`, press a key, grab / drag / release at a pixel, or change a setting.
struct ScriptEvent {
    int frame = 0;
    std::string action;      ///< key, grab, drag, release, set
    int key = 0;             ///< GLFW key code (action "key")
    double x = 0, y = 0;     ///< pixel (grab, drag), finite and within +-kMaxScriptPixel
    std::string name, value; ///< set: one of DemoSettings.h's settings and its value (checked)
};

/// Largest |x| or |y| of a grab or drag (pixels): far off any window, small enough that the
/// ray built from it stays finite in float.
constexpr double kMaxScriptPixel = 1e6;
/// Largest script file read (bytes).
constexpr unsigned long long kMaxScriptBytes = 64ull << 20;

/// GLFW code of a key name (SPACE, LEFT, RIGHT, UP, DOWN, ESCAPE, a letter or a digit); throws
/// InvalidArgument naming `where` otherwise.
int scriptKeyCode(const std::string& name, const std::string& where);

/// Lines "<frame> key <K>", "<frame> grab <x> <y>", "<frame> drag <x> <y>", "<frame> release",
/// "<frame> set <name> <value>" (what weft-demo's panel edits, app/DemoSettings.h);
/// '#' starts a comment; frames must not decrease. An empty path gives no events. Throws IoError
/// with "path:line:" for a malformed line, InvalidArgument for an unknown key or setting.
std::vector<ScriptEvent> loadScript(const std::string& path);

} // namespace weft::app
