// libFuzzer target: the input is a weft-demo --script file (weft::app::loadScript, the parser
// run_demo and weft.load_demo_script use). Parsed events must keep the parser's promises:
// frames >= 0 and not decreasing, grab/drag pixels finite within kMaxScriptPixel.
#include <cmath>

#include <weft/DemoScript.h>

#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = weft::fuzz::scratchFile("in.script", data, size);
    weft::fuzz::expectResultOrWeftError([&] {
        const std::vector<weft::app::ScriptEvent> events = weft::app::loadScript(path);
        int last = 0;
        for (const weft::app::ScriptEvent& e : events) {
            if (e.frame < last) weft::fuzz::finding("script frames decrease or are negative");
            last = e.frame;
            if (!(std::fabs(e.x) <= weft::app::kMaxScriptPixel &&
                  std::fabs(e.y) <= weft::app::kMaxScriptPixel))
                weft::fuzz::finding("script pixel outside +-kMaxScriptPixel or not finite");
        }
    });
    return 0;
}
