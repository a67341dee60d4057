#pragma once
// The demo application (weft-demo and `python -m weft demo`).
#include <weft/Error.h>
#include <string>

namespace weft {

struct DemoOptions {
    int width = 1280;
    int height = 720;
    int frames = 0;             // windowed: stop after this many frames (0 = until closed)
    bool headless = false;      // force the offscreen path even when a display exists
    bool vsync = true;
    std::string out = "out/demo.png"; // headless output image
    std::string screenshot;     // windowed: save the last presented frame here
    std::string statsJson;      // optional: write the last frame's statistics as JSON
};

/// Runs the demo: a window when a display exists (and !headless), otherwise one offscreen
/// frame written to `out`. Returns a process exit code (3 when validation is enabled and the
/// layers reported anything); prints what it wrote.
int runDemo(const DemoOptions& options);

} // namespace weft
