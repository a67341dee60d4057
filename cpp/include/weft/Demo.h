#pragma once
// The demo application (weft-demo and `python -m weft demo`).
#include <string>
#include <weft/Error.h>

#include <weft/Renderer.h>

namespace weft {

struct DemoOptions {
    int width = 1280;
    int height = 720;
    /// Stop after this many frames, each one fixed 60 Hz simulation step (reproducible);
    /// 0: a window runs until closed in real time, headless renders one settled frame.
    int frames = 0;
    bool headless = false; // force the offscreen path even when a display exists
    bool vsync = true;
    /// Headless output: a .png path (the last frame), or with frames > 0 a directory that gets
    /// frame_NNNN.png for every frame and stats.json.
    std::string out = "out/demo.png";
    std::string environment; // light with this .hdr/.exr/.png (equirect or sphere map)
    float hour = -1.0f;      // time of day in hours [0, 24] (6 sunrise, 18 sunset); < 0: default
    std::string shaderDir;   // hot reload: watch this glsl/-like directory ("" = off)
    std::string script;      // scripted input: "<frame> key K | grab x y | drag x y | release"
    std::string screenshot;  // windowed: save the last presented frame here
    std::string statsJson;   // optional: write the last frame's statistics as JSON
    uint32_t msaa = 4;       // RenderSettings::msaa
    uint32_t ambientOcclusion = 8; // RenderSettings::ambientOcclusion
    bool bounce = true;            // RenderSettings::bounce
    float exposure = 0.0f;         // RenderSettings::exposure (stops)
    ToneMap toneMap = ToneMap::Clamp;
    bool quiet = false; // no progress lines on stderr (results still go to stdout)
};

namespace app {
class DemoPanel; // app/DemoPanel.h: weft-demo's ImGui panel
}

/// Runs the seed's cloth environment (terrain, sphere, cloth held at one edge in the wind,
/// sun and moon): a window when a display exists (and !headless), otherwise offscreen to `out`.
/// Returns a process exit code (3 when validation is enabled and the layers reported anything);
/// prints what it wrote.
int runDemo(const DemoOptions& options);
/// The same with `panel` drawn over the window and fed its input (null: none; unused headless).
int runDemo(const DemoOptions& options, app::DemoPanel* panel);

} // namespace weft
