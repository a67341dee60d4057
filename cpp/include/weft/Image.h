#pragma once
// 8-bit images in memory and their PNG file IO.
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

/// Reads a PNG (8 or 16 bit, any colour type; 16-bit is reduced to 8). Throws IoError naming
/// the file when it is missing, truncated or not a PNG.
/// Channels after expansion: grey 1, grey+alpha 2, rgb 3, rgba 4; palettes become rgb, and a
/// tRNS chunk adds an alpha channel.
ImageU8 loadPng(const std::string& path);

/// Writes a PNG; creates no directories. Throws InvalidArgument when image.validate() fails
/// and IoError when the file cannot be written (a partly written file is removed).
void savePng(const std::string& path, const ImageU8& image);

} // namespace weft
