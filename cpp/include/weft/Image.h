#pragma once
// Images in memory: 8-bit (PNG file IO) and float (OpenEXR and Radiance .hdr file IO).
#include <cstdint>
#include <string>
#include <vector>

namespace weft {

/// Interleaved 8-bit image, rows top to bottom, `channels` in {1, 2, 3, 4}.
struct ImageU8 {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<uint8_t> pixels; // width * height * channels bytes

    ImageU8() = default;
    /// Throws InvalidArgument unless w, h > 0 and c in [1, 4].
    ImageU8(int w, int h, int c);
    uint8_t* at(int x, int y) { return pixels.data() + (size_t(y) * width + x) * channels; }
    const uint8_t* at(int x, int y) const {
        return pixels.data() + (size_t(y) * width + x) * channels;
    }
    /// Throws InvalidArgument unless sizes are positive and pixels.size() matches.
    void validate() const;
    /// The same image with 4 channels (grey -> rgb, missing alpha -> 255).
    ImageU8 toRgba() const;
};

/// Largest decoded PNG loadPng accepts: width x height x channels (8-bit) bytes, 1 GiB (a
/// 16384^2 RGBA image). Checked from the header, before anything is allocated.
constexpr uint64_t kMaxPngDecodedBytes = uint64_t(1) << 30;

/// Reads a PNG (8 or 16 bit, any colour type; 16-bit is reduced to 8). Throws IoError naming
/// the file when it is missing, truncated or not a PNG, or when its header claims more than
/// kMaxPngDecodedBytes, or more pixels than its compressed bytes could hold.
/// Channels after expansion: grey 1, grey+alpha 2, rgb 3, rgba 4; palettes become rgb, and a
/// tRNS chunk adds an alpha channel.
ImageU8 loadPng(const std::string& path);

/// Writes a PNG; creates no directories. Throws InvalidArgument when image.validate() fails
/// and IoError when the file cannot be written (a partly written file is removed).
void savePng(const std::string& path, const ImageU8& image);

/// Interleaved float image (linear values, HDR), rows top to bottom, `channels` in {1, 2, 3, 4}.
struct ImageF {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels; // width * height * channels floats

    ImageF() = default;
    /// Throws InvalidArgument unless w, h in [1, 65536] and c in [1, 4]; pixels are zero.
    ImageF(int w, int h, int c);
    float* at(int x, int y) { return pixels.data() + (size_t(y) * width + x) * channels; }
    const float* at(int x, int y) const {
        return pixels.data() + (size_t(y) * width + x) * channels;
    }
    /// Throws InvalidArgument unless sizes are positive and pixels.size() matches.
    void validate() const;
    /// Throws InvalidArgument naming `what` when any value is NaN or infinite.
    void requireFinite(const std::string& what) const;
};

/// Largest decoded EXR loadExr accepts: data-window width x height x channels read x 4 bytes,
/// 4 GiB (a 16384^2 RGBA float image, or a 32768 x 16384 RGB one would need 6 GiB: refused).
/// Checked from the header, before anything is allocated.
constexpr uint64_t kMaxExrDecodedBytes = uint64_t(4) << 30;

/// Reads an OpenEXR file (scanline or tiled, any compression, half/float/uint channels).
/// Channels: R, G, B, A when present (grey files: Y [+ A]); others are ignored. Throws IoError
/// naming the file when it is missing, truncated or corrupt, when its data window would decode
/// to more than kMaxExrDecodedBytes, or (compressions with a known best ratio: none, RLE, ZIP,
/// PXR24, B44) to more than its bytes could hold.
ImageF loadExr(const std::string& path);
/// Writes 32-bit float channels (1: Y, 2: Y A, 3: R G B, 4: R G B A), ZIP compression.
void saveExr(const std::string& path, const ImageF& image);

/// Reads a Radiance RGBE .hdr/.pic file through stb_image (a FORMAT=32-bit_rle_rgbe header line;
/// flat or run-length encoded scanlines, -Y +X order; other orientations are rejected; a pixel
/// decodes as mantissa * 2^(exponent - 136), stb_image's convention). Returns 3 channels.
/// Throws IoError naming the file when it is missing, not a regular file, over
/// kMaxInputFileBytes, larger than 65536 pixels a side, shorter than its stated size needs,
/// cut short or corrupt.
ImageF loadHdr(const std::string& path);
/// Writes a Radiance RGBE file through stb_image_write, run-length encoded scanlines (flat when
/// the width is outside [8, 32767]). Only channels 1 (grey) and 3/4 (alpha dropped) are
/// accepted; values must be finite, >= 0 and below 2^127 (the largest RGBE holds).
void saveHdr(const std::string& path, const ImageF& image);

/// Loads .exr, .hdr or .png by extension (PNG values are divided by 255, no decoding).
ImageF loadImageF(const std::string& path);

} // namespace weft
