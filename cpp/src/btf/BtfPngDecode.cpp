// PNG decoding for BTF samples through libpng's low-level (png_read_*) API.
//
// libpng's simplified API cannot be used here: it treats 8-bit data as sRGB and 16-bit data as
// linear, so reading a 16-bit file into 8 bits applies the sRGB curve (a stored 0.25 became
// 0.533), and it composites alpha on a background without saying so. A BTF sample is a
// measurement, so values are returned exactly as stored (gAMA/sRGB/iCCP chunks are ignored, as
// for JPEG), at their stored depth, and transparency is refused.
//
// libpng reports errors by longjmp. As in core/Image.cpp, every libpng call that can fail runs in
// a small guarded function whose frame owns no C++ object; buffers belong to the caller.
#include "btf/BtfImageCodec.h"

#include <weft/Error.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>

#include <png.h>

namespace weft {

namespace {

// Deflate cannot compress better than about 1032:1: a header claiming more decompressed data
// than this ratio allows is corrupt, and checking it first avoids huge allocations.
constexpr uint64_t kMaxDeflateRatio = 1100;

struct MemoryStream {
    const uint8_t* data = nullptr;
    size_t size = 0, pos = 0;
};

struct PngDecoder {
    png_structp png = nullptr;
    png_infop info = nullptr;
    char message[256] = "unknown libpng error";
    MemoryStream stream;
    PngDecoder() {
        png = png_create_read_struct(PNG_LIBPNG_VER_STRING, this, onError, onWarning);
        if (png) info = png_create_info_struct(png);
    }
    ~PngDecoder() { png_destroy_read_struct(&png, &info, nullptr); }
    PngDecoder(const PngDecoder&) = delete;
    PngDecoder& operator=(const PngDecoder&) = delete;

    static void onError(png_structp png, png_const_charp text) {
        auto* self = static_cast<PngDecoder*>(png_get_error_ptr(png));
        std::snprintf(self->message, sizeof self->message, "%s", text ? text : "?");
        png_longjmp(png, 1);
    }
    static void onWarning(png_structp, png_const_charp) {}
};

void readFromMemory(png_structp png, png_bytep out, png_size_t length) {
    auto* s = static_cast<MemoryStream*>(png_get_io_ptr(png));
    if (length > s->size - s->pos) png_error(png, "file ends early");
    std::memcpy(out, s->data + s->pos, length);
    s->pos += length;
}

struct PngLayout {
    png_uint_32 width = 0, height = 0;
    uint64_t storedBytes = 0; // decompressed size of the image data as stored (filter bytes too)
    int channels = 0, bitDepth = 0; // after the transforms
    size_t rowBytes = 0;
};

bool pngReadHeader(PngDecoder& d, PngLayout& out) {
    if (setjmp(png_jmpbuf(d.png))) return false;
    png_set_read_fn(d.png, &d.stream, readFromMemory);
    png_set_user_limits(d.png, 65536, 65536);
    png_read_info(d.png, d.info);
    int bitDepth = 0, colorType = 0;
    png_get_IHDR(d.png, d.info, &out.width, &out.height, &bitDepth, &colorType, nullptr, nullptr,
                 nullptr);
    out.storedBytes =
        uint64_t(out.height) *
        ((uint64_t(out.width) * unsigned(bitDepth) * png_get_channels(d.png, d.info) + 7) / 8 + 1);
    if (colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(d.png);
    if (colorType == PNG_COLOR_TYPE_GRAY && bitDepth < 8) png_set_expand_gray_1_2_4_to_8(d.png);
    if (png_get_valid(d.png, d.info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(d.png);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    if (bitDepth == 16) png_set_swap(d.png); // PNG stores big-endian; we read uint16_t
#endif
    png_set_interlace_handling(d.png);
    png_read_update_info(d.png, d.info);
    out.channels = png_get_channels(d.png, d.info);
    out.bitDepth = png_get_bit_depth(d.png, d.info);
    out.rowBytes = png_get_rowbytes(d.png, d.info);
    return true;
}

bool pngReadRows(PngDecoder& d, png_bytep* rows) {
    if (setjmp(png_jmpbuf(d.png))) return false;
    png_read_image(d.png, rows);
    png_read_end(d.png, nullptr); // reads to IEND: a file cut after the pixels is still caught
    return true;
}

// Drops an opaque alpha channel; refuses any pixel that is not fully opaque.
template <typename T>
void dropAlpha(std::vector<T>& pixels, int width, int height, int& channels, unsigned opaque,
               const std::string& name) {
    if (channels != 2 && channels != 4) return;
    const size_t count = size_t(width) * size_t(height);
    const int colour = channels - 1;
    for (size_t i = 0; i < count; ++i) {
        const unsigned alpha = pixels[i * size_t(channels) + size_t(colour)];
        if (alpha == opaque) continue;
        throw IoError("PNG '" + name + "' is transparent: alpha " + std::to_string(alpha) + "/" +
                      std::to_string(opaque) + " at pixel (" + std::to_string(i % size_t(width)) +
                      ", " + std::to_string(i / size_t(width)) +
                      "); a BTF sample must be opaque (compositing on a background would change "
                      "the measured values), so remove or flatten the alpha channel");
    }
    for (size_t i = 0; i < count; ++i)
        for (int c = 0; c < colour; ++c)
            pixels[i * size_t(colour) + size_t(c)] = pixels[i * size_t(channels) + size_t(c)];
    pixels.resize(count * size_t(colour));
    channels = colour;
}

} // namespace

DecodedImage decodePng(const std::vector<uint8_t>& bytes, const std::string& name) {
    PngDecoder d;
    if (!d.png || !d.info) throw IoError("cannot read PNG '" + name + "': out of memory");
    d.stream.data = bytes.data();
    d.stream.size = bytes.size();
    PngLayout layout;
    if (!pngReadHeader(d, layout))
        throw IoError("cannot read PNG '" + name + "' (corrupt): " + d.message);
    if (layout.storedBytes > kMaxDeflateRatio * bytes.size() + 4096)
        throw IoError("PNG '" + name + "' claims a size impossible for its file size (corrupt)");
    const int bytesPerValue = layout.bitDepth / 8;
    if ((layout.bitDepth != 8 && layout.bitDepth != 16) || layout.channels < 1 ||
        layout.channels > 4 ||
        layout.rowBytes != size_t(layout.width) * size_t(layout.channels) * size_t(bytesPerValue))
        throw IoError("PNG '" + name + "' has an unsupported pixel layout");
    if (uint64_t(layout.rowBytes) * layout.height > kMaxBtfImageBytes)
        throw IoError("PNG '" + name + "' is " + std::to_string(layout.width) + "x" +
                      std::to_string(layout.height) + ", larger than a BTF image can be");

    DecodedImage img;
    img.width = int(layout.width);
    img.height = int(layout.height);
    img.channels = layout.channels;
    uint8_t* base = nullptr;
    if (bytesPerValue == 2) {
        img.pixels16.resize(layout.rowBytes / 2 * layout.height);
        base = reinterpret_cast<uint8_t*>(img.pixels16.data());
    } else {
        img.pixels.resize(layout.rowBytes * layout.height);
        base = img.pixels.data();
    }
    std::vector<png_bytep> rows(layout.height);
    for (png_uint_32 y = 0; y < layout.height; ++y) rows[y] = base + size_t(y) * layout.rowBytes;
    if (!pngReadRows(d, rows.data()))
        throw IoError("cannot read PNG '" + name + "' (truncated or corrupt): " + d.message);
    if (bytesPerValue == 2)
        dropAlpha(img.pixels16, img.width, img.height, img.channels, 65535u, name);
    else
        dropAlpha(img.pixels, img.width, img.height, img.channels, 255u, name);
    return img;
}

} // namespace weft
