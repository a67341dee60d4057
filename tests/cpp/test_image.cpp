// ImageU8 helpers and PNG IO: round trips, colour conversions and corrupt files.
#include <weft/Error.h>
#include <weft/Image.h>

#include <gtest/gtest.h>

#include "TempDir.h"

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

namespace fs = std::filesystem;

namespace {

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    ASSERT_TRUE(out.good()) << path;
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

weft::ImageU8 randomImage(int width, int height, int channels, uint32_t seed) {
    weft::ImageU8 image(width, height, channels);
    std::mt19937 random(seed);
    for (uint8_t& value : image.pixels) value = uint8_t(random());
    return image;
}

// ---- A minimal PNG encoder (uncompressed deflate) to build files libpng-independently ----

uint32_t crc32(const std::string& bytes) {
    uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char byte : bytes) {
        crc ^= byte;
        for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

void put32(std::string& out, uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(char((value >> shift) & 0xFF));
}

std::string chunk(const std::string& type, const std::string& data) {
    std::string out;
    put32(out, uint32_t(data.size()));
    out += type + data;
    put32(out, crc32(type + data));
    return out;
}

// A zlib stream of stored (uncompressed) deflate blocks.
std::string zlibStored(const std::string& raw) {
    std::string out = "\x78\x01";
    size_t offset = 0;
    do {
        const size_t length = std::min<size_t>(raw.size() - offset, 65535);
        const bool last = offset + length == raw.size();
        out.push_back(last ? 1 : 0);
        out.push_back(char(length & 0xFF));
        out.push_back(char(length >> 8));
        out.push_back(char(~length & 0xFF));
        out.push_back(char((~length >> 8) & 0xFF));
        out += raw.substr(offset, length);
        offset += length;
    } while (offset < raw.size());
    uint32_t a = 1, b = 0;
    for (unsigned char byte : raw) {
        a = (a + byte) % 65521;
        b = (b + a) % 65521;
    }
    put32(out, (b << 16) | a);
    return out;
}

// `scanlines` holds the filtered image data (each row starts with its filter byte).
std::string makePng(uint32_t width, uint32_t height, int bitDepth, int colorType,
                    const std::string& scanlines, const std::string& extraChunks = "",
                    int interlace = 0) {
    std::string header;
    put32(header, width);
    put32(header, height);
    header += {char(bitDepth), char(colorType), 0, 0, char(interlace)};
    return "\x89PNG\r\n\x1a\n" + chunk("IHDR", header) + extraChunks +
           chunk("IDAT", zlibStored(scanlines)) + chunk("IEND", "");
}

std::string bytes(std::initializer_list<int> values) {
    std::string out;
    for (int v : values) out.push_back(char(v));
    return out;
}

} // namespace

TEST(ImageTest, RoundTripIsBitExactForEveryChannelCount) {
    TempDir dir;
    for (int channels = 1; channels <= 4; ++channels) {
        SCOPED_TRACE("channels " + std::to_string(channels));
        const weft::ImageU8 image = randomImage(37, 23, channels, 100u + channels);
        const std::string path = dir.file("round" + std::to_string(channels) + ".png");
        weft::savePng(path, image);
        const weft::ImageU8 loaded = weft::loadPng(path);
        EXPECT_EQ(loaded.width, 37);
        EXPECT_EQ(loaded.height, 23);
        EXPECT_EQ(loaded.channels, channels);
        EXPECT_EQ(loaded.pixels, image.pixels);
    }
}

TEST(ImageTest, RowsAreStoredTopToBottom) {
    TempDir dir;
    weft::ImageU8 image(2, 3, 1);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 2; ++x) *image.at(x, y) = uint8_t(10 * y + x);
    const std::string path = dir.file("rows.png");
    weft::savePng(path, image);
    const weft::ImageU8 loaded = weft::loadPng(path);
    EXPECT_EQ(*loaded.at(0, 0), 0);
    EXPECT_EQ(*loaded.at(1, 2), 21);
    // A file whose first scanline is (0, 1) loads as the same image: row 0 is the top row.
    const std::string handMade = makePng(2, 3, 8, 0, bytes({0, 0, 1, 0, 10, 11, 0, 20, 21}));
    const std::string handPath = dir.file("hand.png");
    writeBytes(handPath, handMade);
    EXPECT_EQ(weft::loadPng(handPath).pixels, image.pixels);
}

TEST(ImageTest, ValidateRejectsInconsistentImages) {
    EXPECT_NO_THROW(weft::ImageU8(3, 2, 4).validate());
    EXPECT_THROW(weft::ImageU8().validate(), weft::InvalidArgument);
    EXPECT_THROW(weft::ImageU8(0, 2, 3).validate(), weft::InvalidArgument);
    weft::ImageU8 negative;
    negative.width = 2;
    negative.height = -1;
    negative.channels = 3;
    EXPECT_THROW(negative.validate(), weft::InvalidArgument);
    weft::ImageU8 fiveChannels(2, 2, 4);
    fiveChannels.channels = 5;
    fiveChannels.pixels.resize(20);
    EXPECT_THROW(fiveChannels.validate(), weft::InvalidArgument);
    weft::ImageU8 truncated(4, 4, 3);
    truncated.pixels.pop_back();
    EXPECT_THROW(truncated.validate(), weft::InvalidArgument);
    // InvalidArgument is a weft::Error.
    EXPECT_THROW(truncated.validate(), weft::Error);
}

TEST(ImageTest, ToRgbaExpandsEveryChannelCount) {
    weft::ImageU8 grey(2, 1, 1);
    grey.pixels = {7, 200};
    EXPECT_EQ(grey.toRgba().pixels, (std::vector<uint8_t>{7, 7, 7, 255, 200, 200, 200, 255}));

    weft::ImageU8 greyAlpha(1, 1, 2);
    greyAlpha.pixels = {9, 33};
    EXPECT_EQ(greyAlpha.toRgba().pixels, (std::vector<uint8_t>{9, 9, 9, 33}));

    weft::ImageU8 rgb(1, 2, 3);
    rgb.pixels = {1, 2, 3, 4, 5, 6};
    const weft::ImageU8 rgba = rgb.toRgba();
    EXPECT_EQ(rgba.width, 1);
    EXPECT_EQ(rgba.height, 2);
    EXPECT_EQ(rgba.channels, 4);
    EXPECT_EQ(rgba.pixels, (std::vector<uint8_t>{1, 2, 3, 255, 4, 5, 6, 255}));

    const weft::ImageU8 already = randomImage(3, 3, 4, 7);
    EXPECT_EQ(already.toRgba().pixels, already.pixels);

    weft::ImageU8 broken(2, 2, 3);
    broken.pixels.clear();
    EXPECT_THROW(broken.toRgba(), weft::InvalidArgument);
}

TEST(ImageTest, SavingAnInvalidImageThrowsInvalidArgument) {
    TempDir dir;
    const std::string path = dir.file("invalid.png");
    weft::ImageU8 image(4, 4, 3);
    image.pixels.resize(10);
    EXPECT_THROW(weft::savePng(path, image), weft::InvalidArgument);
    EXPECT_THROW(weft::savePng(path, weft::ImageU8()), weft::InvalidArgument);
    EXPECT_FALSE(fs::exists(path));
}

TEST(ImageTest, SavingIntoAMissingDirectoryThrowsIoError) {
    TempDir dir;
    const std::string path = dir.file("no/such/dir/out.png");
    EXPECT_THROW(weft::savePng(path, randomImage(2, 2, 3, 1)), weft::IoError);
    EXPECT_FALSE(fs::exists(dir.file("no")));
}

TEST(ImageTest, MissingFileThrowsIoErrorNamingThePath) {
    TempDir dir;
    const std::string path = dir.file("does-not-exist.png");
    try {
        weft::loadPng(path);
        FAIL() << "expected IoError";
    } catch (const weft::IoError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
}

TEST(ImageTest, EveryTruncationOfAValidFileThrowsIoError) {
    TempDir dir;
    const std::string good = dir.file("good.png");
    weft::savePng(good, randomImage(16, 16, 4, 42));
    const std::string full = readBytes(good);
    ASSERT_GT(full.size(), 100u);
    const std::string cut = dir.file("cut.png");
    for (size_t length = 0; length < full.size(); ++length) {
        writeBytes(cut, full.substr(0, length));
        try {
            weft::loadPng(cut);
            ADD_FAILURE() << "no error for a file cut to " << length << " bytes";
        } catch (const weft::IoError& e) {
            EXPECT_NE(std::string(e.what()).find(cut), std::string::npos) << e.what();
        }
    }
}

TEST(ImageTest, RandomBytesThrowIoError) {
    TempDir dir;
    const std::string path = dir.file("random.png");
    std::mt19937 random(5);
    for (int trial = 0; trial < 50; ++trial) {
        std::string data(size_t(random() % 3000), '\0');
        for (char& c : data) c = char(random());
        // Half the trials start with a valid signature, so libpng itself must reject them.
        if (trial % 2 == 1) data = "\x89PNG\r\n\x1a\n" + data;
        writeBytes(path, data);
        EXPECT_THROW(weft::loadPng(path), weft::IoError) << "trial " << trial;
    }
}

TEST(ImageTest, CorruptedBytesGiveAnImageOrIoErrorButNeverCrash) {
    TempDir dir;
    const std::string good = dir.file("good.png");
    weft::savePng(good, randomImage(24, 12, 3, 9));
    const std::string full = readBytes(good);
    const std::string path = dir.file("corrupt.png");
    std::mt19937 random(11);
    for (int trial = 0; trial < 300; ++trial) {
        std::string data = full;
        const int flips = 1 + int(random() % 4);
        for (int i = 0; i < flips; ++i) data[random() % data.size()] ^= char(1 + random() % 255);
        writeBytes(path, data);
        try {
            const weft::ImageU8 image = weft::loadPng(path);
            EXPECT_NO_THROW(image.validate());
        } catch (const weft::IoError&) {
            // expected for nearly every corruption
        } catch (const std::exception& e) {
            ADD_FAILURE() << "trial " << trial << ": unexpected exception " << e.what();
        }
    }
}

TEST(ImageTest, BadChunkCrcThrowsIoError) {
    TempDir dir;
    std::string png = makePng(1, 1, 8, 0, bytes({0, 128}));
    const std::string path = dir.file("crc.png");
    writeBytes(path, png);
    EXPECT_EQ(weft::loadPng(path).pixels, std::vector<uint8_t>{128});
    png[png.size() - 13] ^= 0x40; // last byte of the IDAT chunk's CRC
    writeBytes(path, png);
    EXPECT_THROW(weft::loadPng(path), weft::IoError);
}

TEST(ImageTest, HeaderClaimingAHugeImageThrowsIoErrorWithoutAllocatingIt) {
    TempDir dir;
    const std::string path = dir.file("huge.png");
    writeBytes(path, makePng(60000, 60000, 8, 6, bytes({0, 1, 2, 3, 4})));
    // Allocating and clearing the 14 GB the header asks for would take many seconds.
    const auto start = std::chrono::steady_clock::now();
    EXPECT_THROW(weft::loadPng(path), weft::IoError);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
    writeBytes(path, makePng(5000000, 1, 8, 0, bytes({0, 1})));
    EXPECT_THROW(weft::loadPng(path), weft::IoError);
}

TEST(ImageTest, PaletteWithTransparencyBecomesRgba) {
    TempDir dir;
    // 3x2 pixels, 2 bits per palette index; tRNS gives entries 0 and 1 an alpha.
    const std::string palette =
        chunk("PLTE", bytes({10, 20, 30, 40, 50, 60, 70, 80, 90, 255, 0, 0}));
    const std::string alpha = chunk("tRNS", bytes({0, 128}));
    // Row 0: indices 0 1 2 -> 00 01 10 00 = 0x18; row 1: 3 2 1 -> 11 10 01 00 = 0xE4.
    const std::string path = dir.file("palette.png");
    writeBytes(path, makePng(3, 2, 2, 3, bytes({0, 0x18, 0, 0xE4}), palette + alpha));
    const weft::ImageU8 image = weft::loadPng(path);
    ASSERT_EQ(image.channels, 4);
    ASSERT_EQ(image.width, 3);
    ASSERT_EQ(image.height, 2);
    EXPECT_EQ(image.pixels,
              (std::vector<uint8_t>{10,  20, 30, 0,   40, 50, 60, 128, 70, 80, 90, 255,
                                    255, 0,  0,  255, 70, 80, 90, 255, 40, 50, 60, 128}));
}

TEST(ImageTest, PaletteWithoutTransparencyBecomesRgb) {
    TempDir dir;
    const std::string palette = chunk("PLTE", bytes({1, 2, 3, 4, 5, 6}));
    const std::string path = dir.file("palette.png");
    writeBytes(path, makePng(2, 1, 8, 3, bytes({0, 1, 0}), palette));
    const weft::ImageU8 image = weft::loadPng(path);
    EXPECT_EQ(image.channels, 3);
    EXPECT_EQ(image.pixels, (std::vector<uint8_t>{4, 5, 6, 1, 2, 3}));
}

TEST(ImageTest, SixteenBitSamplesAreReducedToEightBits) {
    TempDir dir;
    const std::string path = dir.file("grey16.png");
    // k * 257 maps exactly to k.
    writeBytes(path, makePng(3, 1, 16, 0, bytes({0, 0x00, 0x00, 0x80, 0x80, 0xFF, 0xFF})));
    weft::ImageU8 image = weft::loadPng(path);
    EXPECT_EQ(image.channels, 1);
    EXPECT_EQ(image.pixels, (std::vector<uint8_t>{0, 128, 255}));

    // 16-bit RGBA, one pixel.
    writeBytes(path,
               makePng(1, 1, 16, 6, bytes({0, 0x11, 0x11, 0x22, 0x22, 0x33, 0x33, 0xFF, 0xFF})));
    image = weft::loadPng(path);
    EXPECT_EQ(image.channels, 4);
    EXPECT_EQ(image.pixels, (std::vector<uint8_t>{0x11, 0x22, 0x33, 0xFF}));
}

TEST(ImageTest, LowBitDepthGreyIsScaledToFullRange) {
    TempDir dir;
    const std::string path = dir.file("grey1.png");
    // 1 bit: 1 0 1 1 -> 0xB0.
    writeBytes(path, makePng(4, 1, 1, 0, bytes({0, 0xB0})));
    weft::ImageU8 image = weft::loadPng(path);
    EXPECT_EQ(image.channels, 1);
    EXPECT_EQ(image.pixels, (std::vector<uint8_t>{255, 0, 255, 255}));
    // 4 bit: 0x3 and 0xF -> 0x33 and 0xFF.
    writeBytes(path, makePng(2, 1, 4, 0, bytes({0, 0x3F})));
    image = weft::loadPng(path);
    EXPECT_EQ(image.pixels, (std::vector<uint8_t>{0x33, 0xFF}));
}

TEST(ImageTest, GreyWithTransparentValueGetsAlphaChannel) {
    TempDir dir;
    const std::string path = dir.file("greytrns.png");
    writeBytes(path, makePng(3, 1, 8, 0, bytes({0, 5, 7, 9}), chunk("tRNS", bytes({0, 7}))));
    const weft::ImageU8 image = weft::loadPng(path);
    EXPECT_EQ(image.channels, 2);
    EXPECT_EQ(image.pixels, (std::vector<uint8_t>{5, 255, 7, 0, 9, 255}));
}

TEST(ImageTest, RgbWithTransparentColourBecomesRgba) {
    TempDir dir;
    const std::string path = dir.file("rgbtrns.png");
    const std::string alpha = chunk("tRNS", bytes({0, 1, 0, 2, 0, 3}));
    writeBytes(path, makePng(2, 1, 8, 2, bytes({0, 1, 2, 3, 1, 2, 4}), alpha));
    const weft::ImageU8 image = weft::loadPng(path);
    EXPECT_EQ(image.channels, 4);
    EXPECT_EQ(image.pixels, (std::vector<uint8_t>{1, 2, 3, 0, 1, 2, 4, 255}));
}

TEST(ImageTest, InterlacedImageIsDeinterlaced) {
    TempDir dir;
    const std::string path = dir.file("adam7.png");
    // 2x2 Adam7: pass 1 holds (0,0), pass 6 holds (1,0), pass 7 holds row 1.
    writeBytes(path, makePng(2, 2, 8, 0, bytes({0, 11, 0, 12, 0, 21, 22}), "", 1));
    const weft::ImageU8 image = weft::loadPng(path);
    EXPECT_EQ(image.pixels, (std::vector<uint8_t>{11, 12, 21, 22}));
}
