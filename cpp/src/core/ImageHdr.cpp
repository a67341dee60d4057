// Radiance RGBE .hdr files through stb_image / stb_image_write (Debian's libstb-dev headers).
// This is the one file of weft that compiles stb's implementation: static (STB_IMAGE_STATIC,
// STB_IMAGE_WRITE_STATIC), so no stbi_* symbol leaves it and nothing clashes with the libstb
// that libtinygltf or weft-demo's Dear ImGui link; the reader holds only the HDR decoder.
#include <weft/Error.h>
#include <weft/Image.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/FileRead.h"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_HDR
#define STBI_NO_STDIO // weft reads the bytes (regular files, size cap) and hands them over
#define STBI_MAX_DIMENSIONS 65536 // ImageF's limit
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
// (not STBI_WRITE_NO_STDIO: this stb_image_write leaves its HDR writer out with it)
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function" // the static API stb has but weft does not call
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb_image.h>
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace weft {

namespace {

// The file's bytes handed to stb_image through its callbacks, which tell when stb_image needed
// bytes past the end. While it decodes pixels they hand over padding past the end instead of
// nothing: at the end of its input stb_image reads zeros, and this stb_image's run-length
// decoder loops forever on a zero count, so a cut or corrupt file would hang it. The padding (a
// run of one, 0x81 0x81, in a run-length scanline; a pixel in a flat one) makes progress until
// the image is full (at most its pixels' worth of work), and the file is refused as cut short.
// Not while the header is read: its lines end only at the end of the input.
class HdrSource {
public:
    explicit HdrSource(const std::vector<uint8_t>& bytes) : mBytes(bytes) {
        mCallbacks.read = read;
        mCallbacks.skip = skip;
        mCallbacks.eof = eof;
    }
    const stbi_io_callbacks* callbacks() const { return &mCallbacks; }
    /// Back to the start; with `pad`, padding past the end (only once the header is known whole).
    void rewind(bool pad) {
        mPos = 0;
        mPastEnd = false;
        mPad = pad;
    }
    bool pastEnd() const { return mPastEnd; }

private:
    static constexpr unsigned char kPadding = 0x81;
    // stb_image asks for a whole buffer (its 128 bytes) when it needs at least one more byte, and
    // for exactly the bytes it needs otherwise (stbi__getn: the rest of a 4-byte pixel).
    static constexpr int kStbBuffer = 128;
    static int read(void* user, char* out, int size) {
        HdrSource& s = *static_cast<HdrSource*>(user);
        const size_t wanted = size_t(std::max(size, 0));
        const size_t available = s.mBytes.size() - s.mPos;
        const size_t n = std::min(available, wanted);
        if (n > 0) std::memcpy(out, s.mBytes.data() + s.mPos, n);
        s.mPos += n;
        if (available >= (size == kStbBuffer ? 1 : wanted)) return int(n);
        s.mPastEnd = true;
        if (!s.mPad) return int(n);
        std::memset(out + n, kPadding, wanted - n);
        return int(wanted);
    }
    static void skip(void* user, int n) {
        HdrSource& s = *static_cast<HdrSource*>(user);
        const size_t available = s.mBytes.size() - s.mPos;
        if (n > 0 && size_t(n) > available) s.mPastEnd = true;
        s.mPos += std::min(available, size_t(std::max(n, 0)));
    }
    static int eof(void* user) {
        const HdrSource& s = *static_cast<const HdrSource*>(user);
        return s.mPos >= s.mBytes.size();
    }

    const std::vector<uint8_t>& mBytes;
    size_t mPos = 0;
    bool mPastEnd = false;
    bool mPad = false;
    stbi_io_callbacks mCallbacks{};
};

// stb_image's short failure reasons (stbi_failure_reason) for a Radiance file, said in full.
std::string hdrFailure(const char* reason) {
    const std::string r = reason ? reason : "unknown";
    std::string said;
    if (r == "not HDR" || r == "unknown image type")
        said = "missing the '#?RADIANCE' or '#?RGBE' signature";
    else if (r == "unsupported format")
        said = "the header has no FORMAT=32-bit_rle_rgbe line (the only format read)";
    else if (r == "unsupported data layout")
        said = "the resolution line is not '-Y <height> +X <width>'";
    else if (r == "too large")
        said = "the size is larger than 65536 pixels a side";
    else if (r == "corrupt")
        said = "a run-length scanline overflows the image width";
    else if (r == "invalid decoded scanline length")
        said = "a run-length scanline's width does not match the image width";
    else if (r == "outofmem")
        said = "out of memory";
    else
        said = "not a Radiance file stb_image reads";
    return said + " (stb_image: " + r + ")";
}

} // namespace

ImageF loadHdr(const std::string& path) {
    const std::vector<uint8_t> bytes = readInputFile(path, "HDR");
    const auto fail = [&](const std::string& why) {
        throw IoError("cannot read HDR '" + path + "' (truncated or corrupt): " + why);
    };
    HdrSource source(bytes);
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_callbacks(source.callbacks(), &source, &width, &height, &channels)) {
        // The header is not one stb_image reads; decoding it again says why, before any pixel.
        source.rewind(false);
        float* data =
            stbi_loadf_from_callbacks(source.callbacks(), &source, &width, &height, &channels, 3);
        stbi_image_free(data);
        fail(hdrFailure(data ? "unknown" : stbi_failure_reason()));
    }
    if (width <= 0 || height <= 0 || width > 65536 || height > 65536)
        fail("impossible size " + std::to_string(width) + "x" + std::to_string(height));
    // Before anything is allocated: every scanline takes at least 4 bytes plus one per 128
    // pixels per channel (run-length encoded; flat ones take 4 per pixel).
    const uint64_t minBytes = uint64_t(height) * (4 + 4 * ((uint64_t(width) + 127) / 128));
    if (bytes.size() < minBytes)
        fail("file too short for the stated size " + std::to_string(width) + "x" +
             std::to_string(height));
    source.rewind(true);
    std::unique_ptr<float, void (*)(void*)> data(
        stbi_loadf_from_callbacks(source.callbacks(), &source, &width, &height, &channels, 3),
        stbi_image_free);
    if (!data) fail(hdrFailure(stbi_failure_reason()));
    if (source.pastEnd()) fail("pixel data ends early");
    ImageF image(width, height, 3);
    std::memcpy(image.pixels.data(), data.get(), image.pixels.size() * sizeof(float));
    return image;
}

void saveHdr(const std::string& path, const ImageF& image) {
    image.validate();
    if (image.channels == 2)
        throw InvalidArgument(
            "saveHdr: a grey+alpha image has no RGBE form; pass 1, 3 or 4 channels");
    // RGBE's largest exponent byte, 255, holds values below 2^127; larger ones would wrap.
    const float largest = std::ldexp(1.0f, 127);
    for (float v : image.pixels)
        if (!std::isfinite(v) || v < 0.0f || v >= largest)
            throw InvalidArgument("saveHdr: values must be finite and >= 0 (and below 2^127, the "
                                  "largest RGBE holds)");
    std::vector<unsigned char> out;
    const auto append = [](void* context, void* data, int size) {
        auto& bytes = *static_cast<std::vector<unsigned char>*>(context);
        const auto* p = static_cast<const unsigned char*>(data);
        bytes.insert(bytes.end(), p, p + size);
    };
    if (!stbi_write_hdr_to_func(append, &out, image.width, image.height, image.channels,
                                image.pixels.data()))
        throw IoError("cannot encode HDR '" + path + "'");
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw IoError("cannot create HDR '" + path + "': " + std::strerror(errno));
    const bool ok = std::fwrite(out.data(), 1, out.size(), f) == out.size();
    const bool closed = std::fclose(f) == 0;
    if (!ok || !closed) {
        std::remove(path.c_str());
        throw IoError("cannot write HDR '" + path + "'");
    }
}

} // namespace weft
