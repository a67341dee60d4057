// weft-demo: the default scene in a window, or rendered headless to a PNG without a display.
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include <weft/Demo.h>
#include <weft/Error.h>

namespace {

const char* kUsage = R"(usage: weft-demo [options]

Shows weft's default scene (textured ground, sphere, box, shadow-casting sun) in a window when a
display exists; otherwise renders it offscreen and writes a PNG.

options:
  --width N          image/window width in pixels (default 1280)
  --height N         image/window height in pixels (default 720)
  --frames N         window: stop after N frames (default: run until closed)
  --headless         render offscreen even when a display exists
  --out PATH         headless output image (default out/demo.png)
  --screenshot PATH  window: save the last presented frame to PATH
  --stats PATH       write the last frame's statistics (passes, CPU/GPU ms) as JSON
  --no-vsync         present without waiting for vertical sync
  -h, --help         show this help

keys (window): arrows orbit the camera, Esc or Q quits.
)";

int parseInt(const char* flag, const char* value) {
    char* end = nullptr;
    const long v = std::strtol(value, &end, 10);
    if (!*value || *end) throw weft::InvalidArgument(std::string(flag) + " needs an integer, got '" + value + "'");
    return int(v);
}

} // namespace

int main(int argc, char** argv) {
    weft::DemoOptions o;
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
            else throw weft::InvalidArgument("unknown option '" + a + "' (see --help)");
        }
        return weft::runDemo(o);
    } catch (const std::exception& e) {
        std::cerr << "weft-demo: error: " << e.what() << std::endl;
        return 1;
    }
}
