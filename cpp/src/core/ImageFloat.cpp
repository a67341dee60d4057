// ImageF helpers and float image file IO: OpenEXR (through the OpenEXR library); Radiance .hdr
// is in ImageHdr.cpp (stb_image).
#include <weft/Error.h>
#include <weft/Image.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPixelType.h>
#include <OpenEXR/ImfThreading.h>

#include "core/ExrHeader.h"
#include "core/FileRead.h"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace weft {

ImageF::ImageF(int w, int h, int c) : width(w), height(h), channels(c) {
    if (w <= 0 || h <= 0 || c < 1 || c > 4 || w > 65536 || h > 65536)
        throw InvalidArgument("float image must be 1..65536 pixels per side with 1-4 channels "
                              "(got " +
                              std::to_string(w) + "x" + std::to_string(h) + "x" +
                              std::to_string(c) + ")");
    pixels.assign(size_t(w) * size_t(h) * size_t(c), 0.0f);
}

void ImageF::validate() const {
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4)
        throw InvalidArgument("float image must have a positive size and 1-4 channels (got " +
                              std::to_string(width) + "x" + std::to_string(height) + "x" +
                              std::to_string(channels) + ")");
    const size_t expected = size_t(width) * size_t(height) * size_t(channels);
    if (pixels.size() != expected)
        throw InvalidArgument("float image of " + std::to_string(width) + "x" +
                              std::to_string(height) + "x" + std::to_string(channels) + " needs " +
                              std::to_string(expected) + " values, has " +
                              std::to_string(pixels.size()));
}

void ImageF::requireFinite(const std::string& what) const {
    for (size_t i = 0; i < pixels.size(); ++i)
        if (!std::isfinite(pixels[i]))
            throw InvalidArgument(what + " contains a non-finite value (NaN or inf) at pixel " +
                                  std::to_string(i / size_t(channels)));
}

namespace {

std::string quoted(const std::string& path) { return "'" + path + "'"; }

std::string lowerExtension(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    const size_t slash = path.find_last_of("/\\");
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

// ---- OpenEXR -----------------------------------------------------------------------------------

// OpenEXR's own thread pool would compete with weft's; decode on the calling thread.
void exrSingleThreaded() {
    static const bool once = [] {
        Imf::setGlobalThreadCount(0);
        return true;
    }();
    (void)once;
}

} // namespace

namespace {

// Best compression ratio of an EXR codec over the samples it stores (0: no useful bound).
// Deflate (ZIP, ZIPS, PXR24) cannot beat about 1032:1; EXR's RLE stores a run of up to 128
// bytes in 2; B44A stores a flat 4x4 block of halves (32 bytes) in 3. PIZ (Huffman with run
// codes) and DWA (lossy, then deflate) have no small bound: only the absolute cap applies.
uint64_t exrBestRatio(Imf::Compression c) {
    switch (c) {
    case Imf::NO_COMPRESSION: return 1;
    case Imf::RLE_COMPRESSION: return 64;
    case Imf::ZIPS_COMPRESSION:
    case Imf::ZIP_COMPRESSION:
    case Imf::PXR24_COMPRESSION: return 1100;
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION: return 11;
    default: return 0;
    }
}

// loadExr decodes a file whose image would be larger than kExrVerifyBytes and kExrVerifyRatio
// times the file once into a strip of at most kExrVerifyStripBytes before allocating it.
constexpr uint64_t kExrVerifyBytes = uint64_t(64) << 20;
constexpr uint64_t kExrVerifyRatio = 64;
constexpr uint64_t kExrVerifyStripBytes = uint64_t(16) << 20;

// `values` floats would be decoded: refuse more than the documented cap, and more than the
// file's bytes could hold (half samples, 2 bytes each, are the smallest stored).
void checkExrDecodedSize(const std::string& path, uint64_t values, Imf::Compression c,
                         uint64_t fileSize) {
    const uint64_t bytes = values * sizeof(float);
    if (bytes > kMaxExrDecodedBytes)
        throw IoError("EXR " + quoted(path) + " would decode to " + std::to_string(bytes) +
                      " bytes, more than the " + std::to_string(kMaxExrDecodedBytes) +
                      " an EXR may have (kMaxExrDecodedBytes)");
    const uint64_t ratio = exrBestRatio(c);
    if (ratio > 0 && values * 2 > ratio * fileSize + (uint64_t(1) << 20))
        throw IoError("EXR " + quoted(path) + " claims " + std::to_string(values) +
                      " samples, impossible for its " + std::to_string(fileSize) +
                      " bytes (corrupt)");
}

} // namespace

ImageF loadExr(const std::string& path) {
    exrSingleThreaded();
    uint64_t fileSize = 0;
    { fileSize = checkInputFile(path, "EXR"); }
    auto impossibleWindow = [](int64_t w, int64_t h) {
        return w <= 0 || h <= 0 || w > 65536 || h > 65536;
    };
    // Before OpenEXR allocates what the header declares: attributes, and line buffers as wide as
    // the data window (gigabytes of address space for a window of millions of pixels a side).
    const ExrHeaderFacts facts = checkExrHeaderSizes(path, fileSize);
    if (facts.haveDataWindow && impossibleWindow(facts.width, facts.height))
        throw IoError("EXR " + quoted(path) + " has an impossible data window");
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const int64_t w64 = int64_t(dw.max.x) - dw.min.x + 1;
        const int64_t h64 = int64_t(dw.max.y) - dw.min.y + 1;
        if (impossibleWindow(w64, h64))
            throw IoError("EXR " + quoted(path) + " has an impossible data window");
        const Imf::ChannelList& list = file.header().channels();
        const bool rgb = list.findChannel("R") && list.findChannel("G") && list.findChannel("B");
        const bool grey = !rgb && list.findChannel("Y");
        const bool alpha = list.findChannel("A") != nullptr;
        if (!rgb && !grey)
            throw IoError("EXR " + quoted(path) + " has neither R, G, B nor Y channels");
        std::vector<const char*> names;
        if (rgb)
            names = {"R", "G", "B"};
        else
            names = {"Y"};
        if (alpha) names.push_back("A");
        const uint64_t values = uint64_t(w64) * uint64_t(h64) * names.size();
        checkExrDecodedSize(path, values, file.header().compression(), fileSize);
        const size_t channels = names.size();
        const size_t xs = sizeof(float) * channels;
        const size_t ys = xs * size_t(w64);
        // Reads rows y0..y1 of the data window into `rows` (the image's layout). OpenEXR
        // addresses a slice from the window's origin, so the base lies before `rows`, possibly
        // far before the address space: computed as an integer, where wrapping is defined.
        auto readRows = [&](float* rows, int y0, int y1) {
            const uintptr_t origin = reinterpret_cast<uintptr_t>(rows) -
                                     uintptr_t(intptr_t(dw.min.x)) * xs -
                                     uintptr_t(intptr_t(y0)) * ys;
            Imf::FrameBuffer fb;
            for (size_t c = 0; c < channels; ++c) {
                char* base = reinterpret_cast<char*>(origin + c * sizeof(float));
                const double fill = c == 3 || (grey && c == 1) ? 1.0 : 0.0; // alpha: opaque
                fb.insert(names[c], Imf::Slice(Imf::FLOAT, base, xs, ys, 1, 1, fill));
            }
            file.setFrameBuffer(fb);
            file.readPixels(y0, y1);
        };
        // Far more pixels than bytes (past what the ratio check bounds, or a codec without a
        // known ratio: PIZ, DWA): decode the file in strips of at most 16 MiB into one buffer
        // first, so that a file whose data is missing or corrupt fails before the image is
        // allocated (a forged 4 KiB PIZ file otherwise made weft zero-fill 3 GiB first).
        if (values * sizeof(float) > kExrVerifyBytes &&
            values * sizeof(float) > kExrVerifyRatio * fileSize) {
            const int lines =
                int(std::clamp<uint64_t>(kExrVerifyStripBytes / ys, 1, uint64_t(h64)));
            std::vector<float> strip(size_t(lines) * size_t(w64) * channels);
            for (int64_t y = dw.min.y; y <= dw.max.y; y += lines)
                readRows(strip.data(), int(y), int(std::min<int64_t>(y + lines - 1, dw.max.y)));
        }
        ImageF img(static_cast<int>(w64), static_cast<int>(h64), static_cast<int>(channels));
        readRows(img.pixels.data(), dw.min.y, dw.max.y);
        return img;
    } catch (const Error&) { throw; } catch (const std::exception& e) {
        throw IoError("cannot read EXR " + quoted(path) + " (truncated or corrupt): " + e.what());
    }
}

void saveExr(const std::string& path, const ImageF& image) {
    image.validate();
    exrSingleThreaded();
    static const char* const layouts[4][4] = {
        {"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        for (int c = 0; c < image.channels; ++c)
            header.channels().insert(layouts[image.channels - 1][c], Imf::Channel(Imf::FLOAT));
        Imf::OutputFile file(path.c_str(), header);
        const size_t xs = sizeof(float) * size_t(image.channels);
        Imf::FrameBuffer fb;
        char* base = const_cast<char*>(reinterpret_cast<const char*>(image.pixels.data()));
        for (int c = 0; c < image.channels; ++c)
            fb.insert(layouts[image.channels - 1][c],
                      Imf::Slice(Imf::FLOAT, base + size_t(c) * sizeof(float), xs,
                                 xs * size_t(image.width)));
        file.setFrameBuffer(fb);
        file.writePixels(image.height);
    } catch (const std::exception& e) {
        std::remove(path.c_str());
        throw IoError("cannot write EXR " + quoted(path) + ": " + e.what());
    }
}

ImageF loadImageF(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == "exr") return loadExr(path);
    if (ext == "hdr" || ext == "pic") return loadHdr(path);
    if (ext == "png") {
        const ImageU8 u8 = loadPng(path);
        ImageF img(u8.width, u8.height, u8.channels);
        for (size_t i = 0; i < u8.pixels.size(); ++i) img.pixels[i] = float(u8.pixels[i]) / 255.0f;
        return img;
    }
    throw InvalidArgument("loadImageF: unknown image type of " + quoted(path) +
                          " (expected .exr, .hdr or .png)");
}

} // namespace weft
