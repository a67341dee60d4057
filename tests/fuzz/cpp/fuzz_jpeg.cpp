// libFuzzer target: the input is an image file as the BTF reader decodes it
// (weft::decodeBtfImage: JPEG or PNG by signature, with the JPEG coefficient pass the
// JPEG-cell refinement asks for). A decoded image must have the sizes it claims.
#include "FuzzCommon.h"
#include "btf/BtfImageCodec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::vector<uint8_t> bytes(data, data + size);
    weft::fuzz::expectResultOrWeftError([&] {
        // the last byte chooses whether the coefficients are read too (both paths are used)
        const bool coefficients = size > 0 && (data[size - 1] & 1);
        const weft::DecodedImage img = weft::decodeBtfImage(bytes, "fuzz", coefficients);
        if (img.width <= 0 || img.height <= 0 || (img.channels != 1 && img.channels != 3))
            weft::fuzz::finding("decoded image with impossible sizes");
        const size_t values = size_t(img.width) * size_t(img.height) * size_t(img.channels);
        if (img.pixels.size() + img.pixels16.size() != values)
            weft::fuzz::finding("decoded pixel count differs from width x height x channels");
        for (const auto& c : img.coefficients.components)
            if (c.blocksWide <= 0 || c.blocksHigh <= 0)
                weft::fuzz::finding("JPEG component with no blocks");
    });
    return 0;
}
