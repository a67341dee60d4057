// ImageU8 helpers and PNG file IO through libpng.
//
// libpng reports errors by longjmp. Every libpng call that can fail runs inside a small
// "guarded" function whose frame holds only the jmp_buf; C++ objects it fills (pixels, row
// pointers) live in the caller, so a longjmp never skips a destructor and never leaves a
// modified local of the setjmp frame in an indeterminate state.
#include <weft/Error.h>
#include <weft/Image.h>

#include <png.h>

#include "core/FileRead.h"
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

namespace weft {

ImageU8::ImageU8(int w, int h, int c) : width(w), height(h), channels(c) {
    if (w <= 0 || h <= 0 || c < 1 || c > 4 || w > 65536 || h > 65536)
        throw InvalidArgument("image must be 1..65536 pixels per side with 1-4 channels (got " +
                              std::to_string(w) + "x" + std::to_string(h) + "x" +
                              std::to_string(c) + ")");
    pixels.resize(size_t(w) * size_t(h) * size_t(c));
}

void ImageU8::validate() const {
    if (width <= 0 || height <= 0) {
        throw InvalidArgument("image size must be positive, got " + std::to_string(width) + "x" +
                              std::to_string(height));
    }
    if (channels < 1 || channels > 4) {
        throw InvalidArgument("image channels must be 1..4, got " + std::to_string(channels));
    }
    const size_t expected = size_t(width) * size_t(height) * size_t(channels);
    if (pixels.size() != expected) {
        throw InvalidArgument("image of " + std::to_string(width) + "x" + std::to_string(height) +
                              "x" + std::to_string(channels) + " needs " +
                              std::to_string(expected) + " bytes, has " +
                              std::to_string(pixels.size()));
    }
}

ImageU8 ImageU8::toRgba() const {
    validate();
    if (channels == 4) return *this;
    ImageU8 out(width, height, 4);
    const size_t count = size_t(width) * size_t(height);
    const uint8_t* src = pixels.data();
    uint8_t* dst = out.pixels.data();
    for (size_t i = 0; i < count; ++i, src += channels, dst += 4) {
        const bool grey = channels <= 2;
        dst[0] = src[0];
        dst[1] = grey ? src[0] : src[1];
        dst[2] = grey ? src[0] : src[2];
        dst[3] = channels == 2 ? src[1] : 255;
    }
    return out;
}

namespace {

// Largest width or height accepted when reading; far beyond any texture a GPU can sample.
constexpr png_uint_32 kMaxReadDimension = 1u << 16;
// Deflate cannot compress better than about 1032:1, so a file that claims more decompressed
// data than this ratio allows is corrupt; checking it avoids huge allocations for tiny files.
constexpr uint64_t kMaxDeflateRatio = 1100;

struct PngErrorState {
    char message[256] = "unknown libpng error";
};

void onPngError(png_structp png, png_const_charp message) {
    auto* state = static_cast<PngErrorState*>(png_get_error_ptr(png));
    std::snprintf(state->message, sizeof state->message, "%s", message ? message : "?");
    png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

struct PngReader {
    png_structp png = nullptr;
    png_infop info = nullptr;
    explicit PngReader(PngErrorState& error) {
        png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, onPngError, onPngWarning);
        if (png) info = png_create_info_struct(png);
    }
    ~PngReader() { png_destroy_read_struct(&png, &info, nullptr); }
    PngReader(const PngReader&) = delete;
    PngReader& operator=(const PngReader&) = delete;
};

struct PngWriter {
    png_structp png = nullptr;
    png_infop info = nullptr;
    explicit PngWriter(PngErrorState& error) {
        png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, onPngError, onPngWarning);
        if (png) info = png_create_info_struct(png);
    }
    ~PngWriter() { png_destroy_write_struct(&png, &info); }
    PngWriter(const PngWriter&) = delete;
    PngWriter& operator=(const PngWriter&) = delete;
};

struct ReadContext {
    std::FILE* file = nullptr;
    uint64_t fileSize = 0; // 0 when unknown (not seekable)
    ImageU8 image;
    std::vector<png_bytep> rows;
};

// Holds no objects with destructors: libpng may longjmp out of any call here.
void readPngBody(png_structp png, png_infop info, ReadContext& ctx) {
    png_init_io(png, ctx.file);
    png_set_sig_bytes(png, 8);
    png_set_user_limits(png, kMaxReadDimension, kMaxReadDimension);
    png_read_info(png, info);

    png_uint_32 width = 0, height = 0;
    int bitDepth = 0, colorType = 0;
    png_get_IHDR(png, info, &width, &height, &bitDepth, &colorType, nullptr, nullptr, nullptr);
    const uint64_t rawRowBytes = (uint64_t(width) * bitDepth * png_get_channels(png, info) + 7) / 8;
    if (ctx.fileSize > 0 &&
        uint64_t(height) * (rawRowBytes + 1) > kMaxDeflateRatio * ctx.fileSize + 4096) {
        png_error(png, "image size in header is impossible for the file size (corrupt)");
    }

    if (colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (colorType == PNG_COLOR_TYPE_GRAY && bitDepth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    if (bitDepth == 16) png_set_scale_16(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);

    const int channels = png_get_channels(png, info);
    const size_t rowBytes = png_get_rowbytes(png, info);
    if (uint64_t(rowBytes) * height > kMaxPngDecodedBytes)
        png_error(png, "decoded image would exceed the 1 GiB a PNG may have (kMaxPngDecodedBytes)");
    if (channels < 1 || channels > 4 || png_get_bit_depth(png, info) != 8 ||
        rowBytes != size_t(width) * size_t(channels)) {
        png_error(png, "unsupported pixel layout after conversion");
    }

    ctx.image.width = int(width);
    ctx.image.height = int(height);
    ctx.image.channels = channels;
    ctx.image.pixels.resize(rowBytes * height);
    ctx.rows.resize(height);
    for (png_uint_32 y = 0; y < height; ++y) ctx.rows[y] = ctx.image.pixels.data() + y * rowBytes;
    png_read_image(png, ctx.rows.data());
    png_read_end(png, nullptr);
}

bool readPngGuarded(png_structp png, png_infop info, ReadContext& ctx) {
    if (setjmp(png_jmpbuf(png))) return false;
    readPngBody(png, info, ctx);
    return true;
}

// Holds no objects with destructors: libpng may longjmp out of any call here.
void writePngBody(png_structp png, png_infop info, std::FILE* file, const ImageU8& image) {
    static const int colorTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                     PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
    png_init_io(png, file);
    png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8,
                 colorTypes[image.channels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y) png_write_row(png, image.at(0, y));
    png_write_end(png, nullptr);
}

bool writePngGuarded(png_structp png, png_infop info, std::FILE* file, const ImageU8& image) {
    if (setjmp(png_jmpbuf(png))) return false;
    writePngBody(png, info, file, image);
    return true;
}

std::string quoted(const std::string& path) { return "'" + path + "'"; }

} // namespace

ImageU8 loadPng(const std::string& path) {
    checkInputFile(path, "PNG");
    FilePtr file(std::fopen(path.c_str(), "rb"));
    if (!file) { throw IoError("cannot open PNG " + quoted(path) + ": " + std::strerror(errno)); }
    ReadContext ctx;
    ctx.file = file.get();
    if (std::fseek(ctx.file, 0, SEEK_END) == 0) {
        const long size = std::ftell(ctx.file);
        ctx.fileSize = size > 0 ? uint64_t(size) : 0;
    }
    std::rewind(ctx.file);

    png_byte signature[8];
    if (std::fread(signature, 1, sizeof signature, ctx.file) != sizeof signature ||
        png_sig_cmp(signature, 0, sizeof signature) != 0) {
        throw IoError(quoted(path) + " is not a PNG file");
    }

    PngErrorState error;
    PngReader reader(error);
    if (!reader.info) {
        throw IoError("cannot read PNG " + quoted(path) + ": libpng initialisation failed");
    }
    if (!readPngGuarded(reader.png, reader.info, ctx)) {
        throw IoError("cannot read PNG " + quoted(path) +
                      " (truncated or corrupt): " + error.message);
    }
    return std::move(ctx.image);
}

void savePng(const std::string& path, const ImageU8& image) {
    image.validate();
    FilePtr file(std::fopen(path.c_str(), "wb"));
    if (!file) { throw IoError("cannot create PNG " + quoted(path) + ": " + std::strerror(errno)); }

    PngErrorState error;
    bool written = false;
    {
        PngWriter writer(error);
        written = writer.info && writePngGuarded(writer.png, writer.info, file.get(), image);
    }

    const bool flushed = written && std::fflush(file.get()) == 0 && !std::ferror(file.get());
    const int savedErrno = errno;
    const bool closed = std::fclose(file.release()) == 0;
    if (!written || !flushed || !closed) {
        std::remove(path.c_str());
        const std::string reason = written ? std::strerror(savedErrno) : error.message;
        throw IoError("cannot write PNG " + quoted(path) + ": " + reason);
    }
}

} // namespace weft
