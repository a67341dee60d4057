#pragma once
// In-memory image codecs for BTF files: JPEG (libjpeg) and PNG (libpng) decoding and encoding
// of 8-bit grey/RGB images. Errors throw IoError naming `name`.
#include <cstdint>
#include <string>
#include <vector>

namespace weft {

struct DecodedImage {
    int width = 0, height = 0, channels = 0; ///< channels 1 (grey) or 3 (RGB)
    std::vector<uint8_t> pixels;
};

/// Decodes JPEG or PNG by signature; alpha is dropped, 16-bit PNG reduced to 8 bits.
DecodedImage decodeBtfImage(const std::vector<uint8_t>& bytes, const std::string& name);

/// Encodes interleaved RGB as JPEG (quality 1..100) or PNG.
std::vector<uint8_t> encodeJpeg(const uint8_t* rgb, int width, int height, int quality);
std::vector<uint8_t> encodePng(const uint8_t* rgb, int width, int height);

} // namespace weft
