// weft-demo: the seed's cloth environment in a window, or rendered headless without a display.
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

#include "CliHelp.h"

#include <weft/Demo.h>
#include <weft/Error.h>
#include <weft/ShaderReload.h>

#ifdef WEFT_DEMO_PANEL
#include "Panel.h"
#endif

namespace {

const char* kDescription =
    R"(Shows the seed's interactive cloth environment: a terrain from a height map, a sphere, a
32x32 cloth held at one edge in the wind that collides with both, and a sun and a moon in a
day-night cycle. A window when a display exists; otherwise renders offscreen to PNG files.
)";

const char* kControls =
    R"(controls (window): left-drag grabs and moves the cloth; arrows orbit the camera; 1/2 weaker/
stronger wind, R turns the wind, L orbits the light, T starts/stops the day-night cycle,
N normal mapping, B the cloth's fitted BTF material, E a reflective sphere (dynamic cube
capture with Fresnel), K the fur's shading model (Kajiya-Kay, Marschner, Sadeghi), S shadows,
P PCF kernel size, H holes,
C resets the cloth, Space pauses the
simulation, Esc or Q quits. The title bar shows fps, simulation steps/s and pass times.
The panel (F1 hides it) shows the time per pass and sets all of the above plus exposure,
tone map, anti-aliasing, ambient occlusion, bounce light and the hair's transparency and
self-shadowing; a --script line "<frame> set <name> <value>" sets the same, e.g.
"30 set exposure 1.5" or "10 set bounce off" (names: exposure, tone-map, msaa, ao,
bounce, hour, day-night, light-azimuth, shadows, pcf, hair-transparency, hair-shadows,
fur, wind, wind-direction, paused, normal-map, btf, holes, reflective, panel).
)";

} // namespace

int main(int argc, char** argv) {
    weft::DemoOptions o;
    bool hotReload = weft::shaderHotReloadAvailable();
    if (const char* env = std::getenv("WEFT_SHADER_DIR")) o.shaderDir = env;
#ifdef WEFT_SOURCE_SHADER_DIR
    else if (std::filesystem::is_directory(WEFT_SOURCE_SHADER_DIR))
        o.shaderDir = WEFT_SOURCE_SHADER_DIR;
#endif
    CLI::App app(kDescription, "weft-demo");
    weft::apps::useHelpLayout(app, kControls);
    app.add_option("--width", o.width, "image/window width in pixels (default 1280)")
        ->option_text("N");
    app.add_option("--height", o.height, "image/window height in pixels (default 720)")
        ->option_text("N");
    app.add_option("--frames", o.frames,
                   "stop after N frames, one fixed 60 Hz simulation step each (reproducible);\n"
                   "default: a window runs in real time until closed, headless renders one\n"
                   "frame after the cloth settled for 1.5 s")
        ->option_text("N");
    app.add_flag("--headless", o.headless, "render offscreen even when a display exists");
    app.add_option("--out", o.out,
                   "headless output: a .png (default out/demo.png; with --frames the last\n"
                   "frame), or with --frames a directory for frame_NNNN.png + stats.json")
        ->option_text("PATH");
    app.add_option("--environment", o.environment,
                   "light the scene with a captured environment instead of the sun and moon:\n"
                   "an equirectangular (2:1) or sphere-map (square) .hdr/.exr/.png; diffuse\n"
                   "from its SH9 irradiance, shadows from a dome of 16 shadow lights")
        ->option_text("PATH");
    app.add_option("--msaa", o.msaa, "anti-aliasing samples per pixel: 1, 2, 4 or 8 (default 4)")
        ->option_text("N");
    app.add_option("--ao", o.ambientOcclusion,
                   "ambient occlusion of the constant ambient (no --environment): dome\n"
                   "lights, 0 (off) or a multiple of 8 up to 64 (default 8)")
        ->option_text("N");
    bool noBounce = false, noVsync = false, noHotReload = false;
    app.add_flag("--no-bounce", noBounce, "no bounce light from the ground onto the objects");
    app.add_option("--exposure", o.exposure,
                   "exposure in stops: the image shows radiance x 2^EV (default 0)")
        ->option_text("EV");
    const std::map<std::string, weft::ToneMap> toneMaps = {{"clamp", weft::ToneMap::Clamp},
                                                           {"aces", weft::ToneMap::Aces},
                                                           {"agx", weft::ToneMap::AgX},
                                                           {"neutral", weft::ToneMap::Neutral}};
    std::string toneMap;
    app.add_option("--tone-map", toneMap,
                   "clamp (the seed's look), aces, agx or neutral (default clamp)")
        ->option_text("OP")
        ->check(CLI::Validator(
            [&](std::string& v) -> std::string {
                return toneMaps.count(v) ? ""
                                         : "must be clamp, aces, agx or neutral, got '" + v + "'";
            },
            ""));
    app.add_option("--time", o.hour,
                   "time of day, 0..24 (6 sunrise, 12 noon, 18 sunset; default 8.4): the\n"
                   "analytic sky (Preetham 1999) and its sun, or the moon at night")
        ->option_text("HOURS")
        ->check(CLI::Validator(
            [](std::string& v) -> std::string {
                float hours = -1.0f;
                std::istringstream in(v);
                // NaN fails both comparisons and is refused with the rest.
                return in >> hours && in.eof() && hours >= 0.0f && hours <= 24.0f
                           ? ""
                           : "needs hours in [0, 24], got '" + v + "'";
            },
            ""));
    app.add_option("--script", o.script,
                   "scripted input, one event per line: \"<frame> key <K>\",\n"
                   "\"<frame> grab <x> <y>\", \"<frame> drag <x> <y>\", \"<frame> release\",\n"
                   "\"<frame> set <name> <value>\" (pixels from the top left; keys as below,\n"
                   "or SPACE/LEFT/RIGHT/UP/DOWN; settings as the panel's, below)")
        ->option_text("PATH");
    app.add_option("--screenshot", o.screenshot, "window: save the last presented frame to PATH")
        ->option_text("PATH");
    app.add_option("--stats", o.statsJson,
                   "write the last frame's statistics (passes, CPU/GPU ms) as JSON")
        ->option_text("PATH");
    app.add_flag("--no-vsync", noVsync, "present without waiting for vertical sync");
    app.add_option("--shader-dir", o.shaderDir,
                   "hot reload: watch PATH (laid out like glsl/); an edited shader is recompiled\n"
                   "and used from the next frame on, a broken one reported and ignored\n"
                   "(default: $WEFT_SHADER_DIR, else the source tree's glsl/ when present)")
        ->option_text("PATH");
    app.add_flag("--no-hot-reload", noHotReload, "do not watch any shader directory");
    bool noPanel = false;
    app.add_flag("--no-panel", noPanel,
                 "window: no panel over the picture (it shows what a\n"
                 "headless render shows)");
    app.add_flag("--quiet", o.quiet, "no progress lines on stderr");
    weft::apps::addHelp(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        std::cout << app.help();
        return 0;
    } catch (const CLI::ParseError& e) {
        std::cerr << "weft-demo: error: " << e.what() << " (see --help)" << std::endl;
        return 2;
    }
    if (!toneMap.empty()) o.toneMap = toneMaps.at(toneMap);
    if (noBounce) o.bounce = false;
    if (noVsync) o.vsync = false;
    if (noHotReload || !hotReload) o.shaderDir.clear();
    try {
#ifdef WEFT_DEMO_PANEL
        weft::demo::Panel panel(o.environment);
        return weft::runDemo(o, noPanel ? nullptr : &panel);
#else
        (void)noPanel; // built without Dear ImGui: there is no panel to leave out
        return weft::runDemo(o);
#endif
    } catch (const std::exception& e) {
        std::cerr << "weft-demo: error: " << e.what() << std::endl;
        return 1;
    }
}
