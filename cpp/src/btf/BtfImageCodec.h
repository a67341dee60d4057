#pragma once
// In-memory image codecs for BTF files: JPEG (libjpeg) and PNG (libpng) decoding of grey/RGB
// images (8-bit, and 16-bit PNG), encoding of 8-bit RGB. Errors throw IoError naming `name`.
#include <cstdint>
#include <string>
#include <vector>

namespace weft {

/// Largest decoded image (width * height * channels * bytes per value) and largest zip entry a
/// BTF reader accepts: 16x a 4096^2 RGB 8-bit image, far beyond any measured BTF, small enough
/// that a forged header cannot make the reader allocate gigabytes.
constexpr uint64_t kMaxBtfImageBytes = uint64_t(256) << 20;
/// Largest total the chosen entries of a BTF zip may declare uncompressed (each is inflated,
/// decoded and freed in turn, so this bounds time, not memory): 64 GiB, 100x a full 6561-image
/// Bonn BTF of 800x800 JPEGs.
constexpr uint64_t kMaxBtfZipTotalBytes = uint64_t(64) << 30;

/// What a JPEG stores, before the decoder's inverse DCT and colour conversion: per colour
/// component the quantised 8x8 block-DCT coefficients (natural order, libjpeg's
/// jpeg_read_coefficients) and the quantisation table. The stored integer c of a coefficient
/// says the encoder's DCT value lay in [(c - 1/2) q, (c + 1/2) q].
struct JpegCoefficientImage {
    struct Component {
        int blocksWide = 0, blocksHigh = 0; ///< blocks holding image data
        int hSampling = 1, vSampling = 1;   ///< sampling factors (luma 2x2 for 4:2:0)
        uint16_t quant[64] = {};            ///< natural order
    };
    bool ycbcr = false; ///< JFIF YCbCr (3 components); false: one grey component
    std::vector<Component> components;
    std::vector<int16_t> coefficients; ///< [component][blockRow][blockCol][64]
};

struct DecodedImage {
    int width = 0, height = 0, channels = 0; ///< channels 1 (grey) or 3 (RGB)
    std::vector<uint8_t> pixels;             ///< 8-bit values, interleaved (empty for 16-bit PNG)
    std::vector<uint16_t> pixels16;          ///< 16-bit PNG values as stored, interleaved
    /// JPEG only and only when asked for: the stored coefficients; empty (no components) when
    /// the JPEG is neither grey nor YCbCr (then nothing is known of its cells)
    JpegCoefficientImage coefficients;
};

/// Decodes JPEG or PNG by signature. Values are returned as stored (no gamma conversion, 16-bit
/// PNG kept at 16 bits). An alpha channel that is opaque everywhere is dropped; any alpha below
/// full opacity (including a tRNS colour key) is refused with IoError, because compositing on a
/// background would change the measured radiance.
/// `jpegCoefficients`: also read a JPEG's stored coefficients (a second, entropy-only pass).
DecodedImage decodeBtfImage(const std::vector<uint8_t>& bytes, const std::string& name,
                            bool jpegCoefficients = false);

/// PNG only (BtfPngDecode.cpp); same contract as decodeBtfImage.
DecodedImage decodePng(const std::vector<uint8_t>& bytes, const std::string& name);

/// Encodes interleaved RGB as JPEG (quality 1..100) or PNG.
std::vector<uint8_t> encodeJpeg(const uint8_t* rgb, int width, int height, int quality);
std::vector<uint8_t> encodePng(const uint8_t* rgb, int width, int height);

} // namespace weft
