// Regressions of the libFuzzer targets' findings (tests/fuzz/cpp; BENCHMARKS.md, reliability):
// each test is the smallest form of an input a target found, or of the check its fix added.
#include <weft/Error.h>
#include <weft/IblConvert.h>
#include <weft/Image.h>

#include <gtest/gtest.h>

#include "TempDir.h"
#include "core/ExrHeader.h"

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

namespace {

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string le32(int32_t v) {
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i) s[size_t(i)] = char(uint32_t(v) >> (8 * i));
    return s;
}

// An EXR attribute: name, type, declared size, value.
std::string exrAttribute(const std::string& name, const std::string& type, int32_t size,
                         const std::string& value) {
    return name + '\0' + type + '\0' + le32(size) + value;
}

// A valid 4x3 RGB EXR (one ZIP chunk) with `extra` inserted as the first header attribute and
// its chunk offset moved by as many bytes.
std::string exrWithAttribute(const TempDir& dir, const std::string& extra) {
    weft::ImageF img(4, 3, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = 0.1f * float(i);
    const std::string path = dir.file("base.exr");
    weft::saveExr(path, img);
    std::string bytes = readBytes(path);
    // The offset table (one entry) follows the header: the 8 bytes at p that hold p + 8.
    for (size_t p = 8; p + 8 <= bytes.size(); ++p) {
        uint64_t v = 0;
        for (int i = 7; i >= 0; --i) v = v << 8 | uint8_t(bytes[p + size_t(i)]);
        if (v != p + 8) continue;
        v += extra.size();
        for (int i = 0; i < 8; ++i) bytes[p + size_t(i)] = char(v >> (8 * i));
        return bytes.substr(0, 8) + extra + bytes.substr(8); // after the magic and version
    }
    ADD_FAILURE() << "no offset table found";
    return bytes;
}

// A saved 4x3 RGB EXR (ZIP, one chunk) split into its header, its offset table's position and
// the chunk: the table entry at p holds p + 8, where the chunk starts.
struct ExrParts {
    std::string bytes;
    size_t table = 0;
};

ExrParts savedExr(const TempDir& dir, float scale = 0.1f) {
    weft::ImageF img(4, 3, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = scale * float(i);
    const std::string path = dir.file("base.exr");
    weft::saveExr(path, img);
    ExrParts parts{readBytes(path), 0};
    for (size_t p = 8; p + 8 <= parts.bytes.size(); ++p) {
        uint64_t v = 0;
        for (int i = 7; i >= 0; --i) v = v << 8 | uint8_t(parts.bytes[p + size_t(i)]);
        if (v == p + 8) {
            parts.table = p;
            return parts;
        }
    }
    ADD_FAILURE() << "no offset table found";
    return parts;
}

// Replaces the 16 bytes of the dataWindow box (min x, min y, max x, max y).
void setDataWindow(std::string& bytes, int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
    const std::string key = std::string("dataWindow") + '\0' + "box2i" + '\0' + le32(16);
    const size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos);
    bytes.replace(at + key.size(), 16, le32(x0) + le32(y0) + le32(x1) + le32(y1));
}

long maxRssKiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss;
}

} // namespace

// OpenEXR 3.1 allocates an attribute of unknown type at its declared size before reading it;
// the fuzzer's inputs declared up to 2 GiB in files of ~400 bytes (each took ~100 ms under
// AddressSanitizer). Such a header is refused before OpenEXR sees it.
TEST(FuzzFindings, ExrAttributeLargerThanTheFileIsRefusedBeforeOpenExrReadsIt) {
    TempDir dir;
    for (int32_t size : {std::numeric_limits<int32_t>::max(), 1 << 20, -1}) {
        const std::string path =
            dir.write("big.exr", exrWithAttribute(dir, exrAttribute("junk", "opaque", size, "xx")));
        try {
            weft::loadExr(path);
            FAIL() << "attribute of " << size << " bytes accepted";
        } catch (const weft::IoError& e) {
            EXPECT_NE(std::string(e.what()).find("header attribute 'junk' (opaque) declares " +
                                                 std::to_string(size) + " bytes"),
                      std::string::npos)
                << e.what();
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        }
    }
}

// The walk must not refuse what OpenEXR reads: attributes of unknown and known types with
// honest sizes, a float vector, a string.
TEST(FuzzFindings, ExrWithExtraWellFormedAttributesStillLoads) {
    TempDir dir;
    const std::string extra = exrAttribute("junk", "opaque", 3, "abc") +
                              exrAttribute("note", "string", 5, "hello") +
                              exrAttribute("weights", "floatvector", 8, std::string(8, '\0')) +
                              exrAttribute("centre", "v3f", 12, std::string(12, '\0'));
    const std::string path = dir.write("extra.exr", exrWithAttribute(dir, extra));
    const weft::ImageF img = weft::loadExr(path);
    EXPECT_EQ(img.width, 4);
    EXPECT_EQ(img.height, 3);
    EXPECT_FLOAT_EQ(img.pixels[5], 0.5f);
}

// A channel list whose declared size is too small: OpenEXR reads the list to its end anyway,
// and the walk follows it to the attributes after it (here, an oversized one it must see).
TEST(FuzzFindings, ExrWalkFollowsAChannelListWhateverItsDeclaredSize) {
    TempDir dir;
    const std::string channel =
        std::string("Z") + '\0' + le32(2) + std::string(4, '\0') + le32(1) + le32(1);
    const std::string extra = exrAttribute("layers", "chlist", 2, channel + '\0') +
                              exrAttribute("junk", "opaque", 1 << 30, "");
    const std::string path = dir.write("chlist.exr", exrWithAttribute(dir, extra));
    try {
        weft::loadExr(path);
        FAIL() << "accepted";
    } catch (const weft::IoError& e) { // the walk's message, not OpenEXR's end of file
        EXPECT_NE(std::string(e.what()).find("'junk' (opaque) declares 1073741824 bytes"),
                  std::string::npos)
            << e.what();
    }
}

// OpenEXR sizes its line buffers by the data window when it opens a file, before weft looked at
// the window: a 594-byte EXR whose window was 6 225 924 pixels wide reserved over a gigabyte
// (1.6 s under AddressSanitizer) only to be refused afterwards. The header walk reads the
// window, and loadExr refuses it before OpenEXR opens the file.
TEST(FuzzFindings, ExrDataWindowIsCheckedBeforeOpenExrOpensTheFile) {
    TempDir dir;
    const std::string good = exrWithAttribute(dir, "");
    const std::string path = dir.write("good.exr", good);
    const weft::ExrHeaderFacts facts = weft::checkExrHeaderSizes(path, good.size());
    ASSERT_TRUE(facts.haveDataWindow);
    EXPECT_EQ(facts.width, 4);
    EXPECT_EQ(facts.height, 3);
    // the same file with the window's max x at 6225923
    const std::string key = std::string("dataWindow") + '\0' + "box2i" + '\0' + le32(16);
    std::string wide = good;
    const size_t at = wide.find(key);
    ASSERT_NE(at, std::string::npos);
    const std::string maxX = le32(6225923);
    wide.replace(at + key.size() + 8, 4, maxX);
    const std::string widePath = dir.write("wide.exr", wide);
    const weft::ExrHeaderFacts wideFacts = weft::checkExrHeaderSizes(widePath, wide.size());
    EXPECT_EQ(wideFacts.width, 6225924);
    try {
        weft::loadExr(widePath);
        FAIL() << "accepted";
    } catch (const weft::IoError& e) {
        EXPECT_NE(std::string(e.what()).find("impossible data window"), std::string::npos)
            << e.what();
    }
}

// A forged 4.4 KiB PIZ file (PIZ and DWA have no known best ratio, so only the 4 GiB cap
// applied) with a 16384 x 16384 RGB window and an offset table whose 512 entries all point at
// one empty chunk: weft zero-filled a 3 GiB image before OpenEXR found the data missing (17.8 s,
// 3.1 GB resident). The file is now decoded strip by strip first and fails at the first strip.
TEST(FuzzFindings, ForgedPizExrFailsBeforeTheImageIsAllocated) {
    TempDir dir;
    ExrParts parts = savedExr(dir);
    std::string header = parts.bytes.substr(0, parts.table);
    const std::string key = std::string("compression") + '\0' + "compression" + '\0' + le32(1);
    const size_t at = header.find(key);
    ASSERT_NE(at, std::string::npos);
    header[at + key.size()] = 4; // PIZ_COMPRESSION
    setDataWindow(header, 0, 0, 16383, 16383);
    const size_t chunks = 16384 / 32; // PIZ stores 32 scanlines per chunk
    const uint64_t chunk = header.size() + 8 * chunks;
    std::string file = header;
    for (size_t i = 0; i < chunks; ++i)
        for (int b = 0; b < 8; ++b) file.push_back(char(chunk >> (8 * b)));
    file += le32(0) + le32(8) + std::string(8, '\0'); // y 0, 8 bytes of data
    const std::string path = dir.write("forged.exr", file);
    const long rssBefore = maxRssKiB();
    const auto start = std::chrono::steady_clock::now();
    EXPECT_THROW(weft::loadExr(path), weft::IoError);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 2.0);
    EXPECT_LT(maxRssKiB() - rssBefore, 256 * 1024) << "KiB of peak resident memory added";
}

// A file decoded strip by strip first (more than 64 MiB of floats and 64 times its size) loads
// the same pixels: 3072 x 2048 RGB, constant but for the first row and one pixel of the last.
TEST(FuzzFindings, LargeCompressibleExrLoadsThroughTheStripCheck) {
    TempDir dir;
    weft::ImageF img(3072, 2048, 3);
    for (float& v : img.pixels) v = 0.25f;
    for (int x = 0; x < img.width; ++x) img.at(x, 0)[0] = float(x);
    img.at(3071, 2047)[2] = 7.0f;
    const std::string path = dir.file("big.exr");
    weft::saveExr(path, img);
    ASSERT_GT(img.pixels.size() * 4, 64u * std::filesystem::file_size(path)); // takes the check
    const weft::ImageF back = weft::loadExr(path);
    ASSERT_EQ(back.width, 3072);
    ASSERT_EQ(back.height, 2048);
    EXPECT_TRUE(back.pixels == img.pixels);
}

// A data window far from the origin: OpenEXR addresses the frame buffer from the window's
// origin, a base that weft computed with pointer arithmetic that overflowed (UBSan: "pointer
// index expression ... overflowed") for a window 65536 wide near y = 2^30. The base is an
// integer now; the wide file (no such data) is refused, a 4x3 one far out loads its pixels.
TEST(FuzzFindings, ExrWindowFarFromTheOriginHasNoPointerOverflow) {
    TempDir dir;
    ExrParts wide = savedExr(dir);
    setDataWindow(wide.bytes, 0, (1 << 30) - 10, 65535, (1 << 30) - 9);
    EXPECT_THROW(weft::loadExr(dir.write("wide.exr", wide.bytes)), weft::IoError);

    ExrParts far = savedExr(dir, 0.5f);
    const int32_t y0 = (1 << 30) - 10;
    setDataWindow(far.bytes, -7, y0, -4, y0 + 2);
    far.bytes.replace(far.table + 8, 4, le32(y0)); // the chunk's first scanline
    const weft::ImageF img = weft::loadExr(dir.write("far.exr", far.bytes));
    ASSERT_EQ(img.width, 4);
    ASSERT_EQ(img.height, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) ASSERT_FLOAT_EQ(img.pixels[i], 0.5f * float(i));
}

// weft-demo's --environment loader (now loadEnvironmentCube, so that a fuzz target can call it)
// left an EXR's NaN, inf or negative values and RGBE values near 1.7e38 (whose resampling sums
// overflow to inf) to the converters and Environment, which refused them without naming the
// file. It checks them itself now, naming the file and the pixel.
TEST(FuzzFindings, EnvironmentFileRadianceMustBeFiniteNonNegativeAndBounded) {
    TempDir dir;
    const float bad[] = {std::nanf(""), std::numeric_limits<float>::infinity(), -1.0f, 1e35f};
    for (float value : bad) {
        weft::ImageF img(8, 4, 3);
        for (float& v : img.pixels) v = 0.5f;
        img.at(3, 2)[1] = value;
        const std::string path = dir.file("env.exr");
        weft::saveExr(path, img);
        try {
            weft::loadEnvironmentCube(path, 4);
            FAIL() << value << " accepted";
        } catch (const weft::InvalidArgument& e) {
            EXPECT_NE(std::string(e.what()).find("at pixel (3, 2)"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        }
    }
    weft::ImageF rgbe(8, 4, 3);
    for (float& v : rgbe.pixels) v = 1.5e38f; // RGBE holds it; four taps of it sum to inf
    weft::saveHdr(dir.file("env.hdr"), rgbe);
    EXPECT_THROW(weft::loadEnvironmentCube(dir.file("env.hdr"), 4), weft::InvalidArgument);
}

TEST(FuzzFindings, EnvironmentFileShapesAndChannels) {
    TempDir dir;
    weft::ImageF equirect(8, 4, 4); // RGBA: alpha ignored
    for (float& v : equirect.pixels) v = 2.0f;
    weft::saveExr(dir.file("pano.exr"), equirect);
    const weft::CubeMap cube = weft::loadEnvironmentCube(dir.file("pano.exr"), 4);
    ASSERT_EQ(cube.size(), 4);
    for (size_t i = 0; i < cube.floatCount(); ++i) ASSERT_NEAR(cube.data()[i], 2.0f, 1e-5f);
    weft::ImageF sphere(6, 6, 3);
    for (float& v : sphere.pixels) v = 1.0f;
    weft::saveExr(dir.file("ball.exr"), sphere);
    const weft::CubeMap ball = weft::loadEnvironmentCube(dir.file("ball.exr"), 4);
    for (size_t i = 0; i < ball.floatCount(); ++i) ASSERT_NEAR(ball.data()[i], 1.0f, 1e-4f);
    weft::saveExr(dir.file("grey.exr"), weft::ImageF(8, 4, 1));
    EXPECT_THROW(weft::loadEnvironmentCube(dir.file("grey.exr"), 4), weft::InvalidArgument);
    weft::saveExr(dir.file("odd.exr"), weft::ImageF(8, 6, 3));
    EXPECT_THROW(weft::loadEnvironmentCube(dir.file("odd.exr"), 4), weft::InvalidArgument);
    EXPECT_THROW(weft::loadEnvironmentCube(dir.file("pano.exr"), 0), weft::InvalidArgument);
    EXPECT_THROW(weft::loadEnvironmentCube(dir.file("missing.exr"), 4), weft::IoError);
}
