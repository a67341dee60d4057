// libFuzzer target: the input is an OpenEXR file read by weft::loadExr (weft.load_exr, BTF EXR
// images, environment maps). A loaded image must be valid; its values are what the file stores
// (NaN and inf included: the callers that need radiance check it).
#include <weft/Image.h>

#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = weft::fuzz::scratchFile("in.exr", data, size);
    weft::fuzz::expectResultOrWeftError([&] {
        const weft::ImageF img = weft::loadExr(path);
        try {
            img.validate();
        } catch (const weft::Error& e) {
            weft::fuzz::finding(std::string("loaded EXR fails validate(): ") + e.what());
        }
    });
    return 0;
}
