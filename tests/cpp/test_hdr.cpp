// Radiance .hdr through stb_image (compiled into weft, cpp/src/core/ImageHdr.cpp), here so that the
// sanitizer lane runs stb's decoder under ASan/UBSan: round trips, every truncation, zero
// run-length counts (this stb_image looped forever on them) and corrupted bytes give an image or
// IoError.
#include <weft/Error.h>
#include <weft/Image.h>

#include <gtest/gtest.h>

#include "TempDir.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

namespace {

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& data) {
    std::ofstream(path, std::ios::binary) << data;
}

weft::ImageF testImage(int w, int h) {
    weft::ImageF image(w, h, 3);
    std::mt19937 random(3);
    std::uniform_real_distribution<float> exponent(-8.0f, 8.0f);
    for (float& v : image.pixels) v = std::exp2(exponent(random));
    for (int x = 0; x < w; ++x) image.at(x, 1)[0] = image.at(x, 1)[1] = image.at(x, 1)[2] = 2.0f;
    return image;
}

// Decodes or refuses with IoError naming the file, within a second, never anything else.
void expectImageOrIoError(const std::string& path, const std::string& what) {
    const auto start = std::chrono::steady_clock::now();
    try {
        const weft::ImageF image = weft::loadHdr(path);
        EXPECT_NO_THROW(image.validate()) << what;
        for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << what;
    } catch (const weft::IoError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << what << ": " << e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << what << ": unexpected exception " << e.what();
    }
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1)) << what;
}

} // namespace

TEST(HdrTest, RoundTripIsWithinOneMantissaStepBelow) {
    TempDir dir;
    for (int width : {5, 40}) { // flat and run-length encoded scanlines
        const weft::ImageF image = testImage(width, 6);
        const std::string path = dir.file("a.hdr");
        weft::saveHdr(path, image);
        const weft::ImageF back = weft::loadHdr(path);
        ASSERT_EQ(back.width, width);
        ASSERT_EQ(back.height, 6);
        ASSERT_EQ(back.channels, 3);
        for (int y = 0; y < 6; ++y) {
            for (int x = 0; x < width; ++x) {
                const float* in = image.at(x, y);
                const float* out = back.at(x, y);
                int e = 0;
                std::frexp(std::max(in[0], std::max(in[1], in[2])), &e);
                const float step = std::ldexp(1.0f, e - 8);
                for (int c = 0; c < 3; ++c) {
                    EXPECT_LE(out[c], in[c]);
                    EXPECT_LT(in[c] - out[c], step) << x << "," << y << "," << c;
                }
            }
        }
    }
}

TEST(HdrTest, EveryTruncationThrowsIoError) {
    TempDir dir;
    const std::string good = dir.file("good.hdr");
    weft::saveHdr(good, testImage(20, 4));
    const std::string full = readBytes(good);
    const std::string cut = dir.file("cut.hdr");
    for (size_t length = 0; length < full.size(); ++length) {
        writeBytes(cut, full.substr(0, length));
        try {
            weft::loadHdr(cut);
            ADD_FAILURE() << "no error for a file cut to " << length << " of " << full.size();
        } catch (const weft::IoError& e) {
            EXPECT_NE(std::string(e.what()).find(cut), std::string::npos) << e.what();
        }
    }
}

TEST(HdrTest, ZeroRunLengthCountsAreRefusedQuickly) {
    TempDir dir;
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 3 +X 16\n";
    const std::string path = dir.file("zero.hdr");
    writeBytes(path, header + std::string("\x02\x02\x00\x10", 4) + std::string(64, '\0'));
    expectImageOrIoError(path, "zero counts");
    EXPECT_THROW(weft::loadHdr(path), weft::IoError);
}

TEST(HdrTest, CorruptedBytesGiveAnImageOrIoError) {
    TempDir dir;
    const std::string good = dir.file("good.hdr");
    weft::saveHdr(good, testImage(24, 5));
    const std::string full = readBytes(good);
    const std::string path = dir.file("corrupt.hdr");
    std::mt19937 random(17);
    for (int trial = 0; trial < 400; ++trial) {
        std::string data = full;
        const int flips = 1 + int(random() % 4);
        for (int i = 0; i < flips; ++i) data[random() % data.size()] ^= char(1 + random() % 255);
        writeBytes(path, data);
        expectImageOrIoError(path, "trial " + std::to_string(trial));
    }
}
