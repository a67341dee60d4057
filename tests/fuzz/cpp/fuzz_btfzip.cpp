// libFuzzer target: the bytes of a BTF zip (weft::loadBtf of a .zip: libzip, the entry-size
// checks, the Bonn names, JPEG / PNG / EXR decoding of the chosen entries). The input's size
// picks the options (odd: linear gamma; bit 1: every view instead of the frontal one; bit 2:
// the JPEG cells), so that mutations reach every path. Loaded samples must be finite, in
// [0, 1] for 8/16-bit images.
#include <weft/BtfIo.h>

#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = weft::fuzz::scratchFile("in.zip", data, size);
    weft::BtfLoadOptions options;
    options.threads = 1;
    if (size & 1) options.gamma = weft::BtfGamma::Linear;
    if (size & 2) options.views.clear();
    options.jpegCells = (size & 4) != 0;
    weft::fuzz::expectResultOrWeftError([&] {
        const weft::BtfSamples s = weft::loadBtf(path, options);
        if (s.width() <= 0 || s.height() <= 0 || s.count() <= 0 ||
            s.values().size() != s.texels() * 3 * size_t(s.count()))
            weft::fuzz::finding("loaded BTF with inconsistent sizes");
        weft::fuzz::requireFiniteValues(s.values().data(), s.values().size(), "BTF sample", true);
    });
    return 0;
}
