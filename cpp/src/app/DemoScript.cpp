#include <weft/DemoScript.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <GLFW/glfw3.h>

#include <weft/Error.h>

#include "app/DemoSettings.h"
#include "core/FileRead.h"

namespace weft::app {

int scriptKeyCode(const std::string& name, const std::string& where) {
    static const std::map<std::string, int> named = {
        {"SPACE", GLFW_KEY_SPACE}, {"LEFT", GLFW_KEY_LEFT}, {"RIGHT", GLFW_KEY_RIGHT},
        {"UP", GLFW_KEY_UP},       {"DOWN", GLFW_KEY_DOWN}, {"ESCAPE", GLFW_KEY_ESCAPE}};
    std::string upper = name;
    for (char& c : upper) c = char(std::toupper((unsigned char)c));
    if (auto it = named.find(upper); it != named.end()) return it->second;
    if (upper.size() == 1 &&
        ((upper[0] >= 'A' && upper[0] <= 'Z') || (upper[0] >= '0' && upper[0] <= '9')))
        return upper[0]; // GLFW codes of letters and digits are their ASCII codes
    throw InvalidArgument(where + ": unknown key '" + name + "'");
}

std::vector<ScriptEvent> loadScript(const std::string& path) {
    std::vector<ScriptEvent> events;
    if (path.empty()) return events;
    checkInputFile(path, "script", kMaxScriptBytes);
    std::ifstream in(path);
    if (!in) throw IoError("cannot open script '" + path + "'");
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        line = line.substr(0, line.find('#'));
        std::istringstream words(line);
        ScriptEvent e;
        if (!(words >> e.frame)) {
            if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
            throw IoError(path + ":" + std::to_string(n) + ": expected '<frame> <action> ...'");
        }
        const std::string where = path + ":" + std::to_string(n);
        if (!(words >> e.action)) throw IoError(where + ": missing action");
        if (e.action == "key") {
            std::string k;
            if (!(words >> k)) throw IoError(where + ": key needs a name");
            e.key = scriptKeyCode(k, where);
        } else if (e.action == "grab" || e.action == "drag") {
            if (!(words >> e.x >> e.y)) throw IoError(where + ": " + e.action + " needs x y");
            if (!(std::fabs(e.x) <= kMaxScriptPixel && std::fabs(e.y) <= kMaxScriptPixel))
                throw IoError(where + ": " + e.action + " pixel must be finite, within +-1e6");
        } else if (e.action == "set") {
            std::string extra;
            if (!(words >> e.name >> e.value) || (words >> extra))
                throw IoError(where + ": set needs a setting's name and one value");
            try {
                checkDemoSetting(e.name, e.value);
            } catch (const InvalidArgument& bad) {
                throw InvalidArgument(where + ": " + bad.what());
            }
        } else if (e.action != "release") {
            throw IoError(where + ": unknown action '" + e.action +
                          "' (key, grab, drag, release, set)");
        }
        if (e.frame < 0 || (!events.empty() && e.frame < events.back().frame))
            throw IoError(where + ": frames must be >= 0 and not decrease");
        events.push_back(e);
    }
    return events;
}

} // namespace weft::app
