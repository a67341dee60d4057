// libFuzzer target: the input is a Radiance RGBE file read by weft::loadHdr (weft.load_hdr,
// environment maps). A loaded image must be valid with 3 channels, and RGBE can only hold
// finite values >= 0.
#include <weft/Image.h>

#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = weft::fuzz::scratchFile("in.hdr", data, size);
    weft::fuzz::expectResultOrWeftError([&] {
        const weft::ImageF img = weft::loadHdr(path);
        try {
            img.validate();
        } catch (const weft::Error& e) {
            weft::fuzz::finding(std::string("loaded HDR fails validate(): ") + e.what());
        }
        if (img.channels != 3) weft::fuzz::finding("loadHdr returned other than 3 channels");
        weft::fuzz::requireFiniteValues(img.pixels.data(), img.pixels.size(), "HDR pixel", true);
    });
    return 0;
}
