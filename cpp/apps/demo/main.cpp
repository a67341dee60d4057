// weft-demo: the seed's cloth environment in a window, or rendered headless without a display.
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>

#include <weft/Demo.h>
#include <weft/Error.h>
#include <weft/ShaderReload.h>

namespace {

const char* kUsage = R"(usage: weft-demo [options]

Shows the seed's interactive cloth environment: a terrain from a height map, a sphere, a
32x32 cloth held at one edge in the wind that collides with both, and a sun and a moon in a
day-night cycle. A window when a display exists; otherwise renders offscreen to PNG files.

options:
  --width N          image/window width in pixels (default 1280)
  --height N         image/window height in pixels (default 720)
  --frames N         stop after N frames, one fixed 60 Hz simulation step each (reproducible);
                     default: a window runs in real time until closed, headless renders one
                     frame after the cloth settled for 1.5 s
  --headless         render offscreen even when a display exists
  --out PATH         headless output: a .png (default out/demo.png; with --frames the last
                     frame), or with --frames a directory for frame_NNNN.png + stats.json
  --environment PATH light the scene with a captured environment instead of the sun and moon:
                     an equirectangular (2:1) or sphere-map (square) .hdr/.exr/.png; diffuse
                     from its SH9 irradiance, shadows from a dome of 16 shadow lights
  --msaa N           anti-aliasing samples per pixel: 1, 2, 4 or 8 (default 4)
  --ao N             ambient occlusion of the constant ambient (no --environment): dome
                     lights, 0 (off) or a multiple of 8 up to 64 (default 8)
  --no-bounce        no bounce light from the ground onto the objects
  --exposure EV      exposure in stops: the image shows radiance x 2^EV (default 0)
  --tone-map OP      clamp (the seed's look), aces, agx or neutral (default clamp)
  --time HOURS       time of day, 0..24 (6 sunrise, 12 noon, 18 sunset; default 8.4): the
                     analytic sky (Preetham 1999) and its sun, or the moon at night
  --script PATH      scripted input, one event per line: "<frame> key <K>",
                     "<frame> grab <x> <y>", "<frame> drag <x> <y>", "<frame> release"
                     (pixels from the top left; keys as below, or SPACE/LEFT/RIGHT/UP/DOWN)
  --screenshot PATH  window: save the last presented frame to PATH
  --stats PATH       write the last frame's statistics (passes, CPU/GPU ms) as JSON
  --no-vsync         present without waiting for vertical sync
  --shader-dir PATH  hot reload: watch PATH (laid out like glsl/); an edited shader is recompiled
                     and used from the next frame on, a broken one reported and ignored
                     (default: $WEFT_SHADER_DIR, else the source tree's glsl/ when present)
  --no-hot-reload    do not watch any shader directory
  -h, --help         show this help

controls (window): left-drag grabs and moves the cloth; arrows orbit the camera; 1/2 weaker/
stronger wind, R turns the wind, L orbits the light, T starts/stops the day-night cycle,
N normal mapping, B the cloth's fitted BTF material, E a reflective sphere (dynamic cube
capture with Fresnel), K the fur's shading model (Kajiya-Kay, Marschner, Sadeghi), S shadows,
P PCF kernel size, H holes,
C resets the cloth, Space pauses the
simulation, Esc or Q quits. The title bar shows fps, simulation steps/s and pass times.
)";

int parseInt(const char* flag, const char* value) {
    char* end = nullptr;
    const long v = std::strtol(value, &end, 10);
    if (!*value || *end) throw weft::InvalidArgument(std::string(flag) + " needs an integer, got '" + value + "'");
    return int(v);
}

float parseFloat(const char* flag, const char* value) {
    char* end = nullptr;
    const float v = std::strtof(value, &end);
    if (!*value || *end) throw weft::InvalidArgument(std::string(flag) + " needs a number, got '" + value + "'");
    return v;
}

} // namespace

int main(int argc, char** argv) {
    weft::DemoOptions o;
    bool hotReload = weft::shaderHotReloadAvailable();
    if (const char* env = std::getenv("WEFT_SHADER_DIR")) o.shaderDir = env;
#ifdef WEFT_SOURCE_SHADER_DIR
    else if (std::filesystem::is_directory(WEFT_SOURCE_SHADER_DIR)) o.shaderDir = WEFT_SOURCE_SHADER_DIR;
#endif
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            auto next = [&]() -> const char* {
                if (i + 1 >= argc) throw weft::InvalidArgument(a + " needs a value");
                return argv[++i];
            };
            if (a == "-h" || a == "--help") {
                std::cout << kUsage;
                return 0;
            } else if (a == "--width") o.width = parseInt("--width", next());
            else if (a == "--height") o.height = parseInt("--height", next());
            else if (a == "--frames") o.frames = parseInt("--frames", next());
            else if (a == "--headless") o.headless = true;
            else if (a == "--no-vsync") o.vsync = false;
            else if (a == "--out") o.out = next();
            else if (a == "--screenshot") o.screenshot = next();
            else if (a == "--stats") o.statsJson = next();
            else if (a == "--script") o.script = next();
            else if (a == "--shader-dir") o.shaderDir = next();
            else if (a == "--environment") o.environment = next();
            else if (a == "--msaa") o.msaa = uint32_t(parseInt("--msaa", next()));
            else if (a == "--ao") o.ambientOcclusion = uint32_t(parseInt("--ao", next()));
            else if (a == "--no-bounce") o.bounce = false;
            else if (a == "--exposure") o.exposure = parseFloat("--exposure", next());
            else if (a == "--tone-map") {
                const std::string op = next();
                const char* names[] = {"clamp", "aces", "agx", "neutral"};
                int found = -1;
                for (int k = 0; k < 4; ++k)
                    if (op == names[k]) found = k;
                if (found < 0)
                    throw weft::InvalidArgument("--tone-map must be clamp, aces, agx or neutral, got '" + op + "'");
                o.toneMap = weft::ToneMap(found);
            }
            else if (a == "--time") {
                const char* v = next();
                char* end = nullptr;
                o.hour = std::strtof(v, &end);
                if (!*v || *end || !(o.hour >= 0.0f && o.hour <= 24.0f))
                    throw weft::InvalidArgument(std::string("--time needs hours in [0, 24], got '") + v + "'");
            }
            else if (a == "--no-hot-reload") hotReload = false;
            else throw weft::InvalidArgument("unknown option '" + a + "' (see --help)");
        }
        if (!hotReload) o.shaderDir.clear();
        return weft::runDemo(o);
    } catch (const std::exception& e) {
        std::cerr << "weft-demo: error: " << e.what() << std::endl;
        return 1;
    }
}
