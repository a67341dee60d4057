// Regressions of the libFuzzer targets' findings (tests/fuzz/cpp; BENCHMARKS.md, reliability):
// each test is the smallest form of an input a target found, or of the check its fix added.
#include <weft/Error.h>
#include <weft/IblConvert.h>
#include <weft/Image.h>

#include <gtest/gtest.h>

#include "TempDir.h"

#include <cmath>
#include <limits>
#include <string>

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
