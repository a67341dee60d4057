// libFuzzer target: the input is a PNG file read by weft::loadPng (textures, weft.load_png).
// A loaded image must be valid (sizes positive, pixel count matching).
#include <weft/Image.h>

#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = weft::fuzz::scratchFile("in.png", data, size);
    weft::fuzz::expectResultOrWeftError([&] {
        const weft::ImageU8 img = weft::loadPng(path);
        try {
            img.validate();
        } catch (const weft::Error& e) {
            weft::fuzz::finding(std::string("loaded PNG fails validate(): ") + e.what());
        }
    });
    return 0;
}
