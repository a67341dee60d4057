// IBL from C++: the face convention, texel solid angles, SH9 of analytic environments, the exact
// irradiance on the GPU against the CPU, the capture conversions' argument checks and the dome's
// round-robin schedule.
#include <weft/CubeMap.h>
#include <weft/Device.h>
#include <weft/Environment.h>
#include <weft/Error.h>
#include <weft/IblConvert.h>
#include <weft/IblFilter.h>
#include <weft/IblGpu.h>
#include <weft/IblLights.h>
#include <weft/ShadowDome.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

namespace {

constexpr double kPi = 3.14159265358979323846;

weft::CubeMap constantCube(int size, glm::vec3 value) {
    weft::CubeMap cube(size);
    for (size_t k = 0; k < cube.floatCount(); k += 3)
        for (int c = 0; c < 3; ++c) cube.data()[k + c] = value[c];
    return cube;
}

} // namespace

TEST(IblCube, FaceConventionRoundTrips) {
    // major axis picks the face; the texel centre direction maps back to the same texel
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int f = 0; f < 6; ++f) EXPECT_EQ(weft::cubeCoord(axes[f]).face, f);
    const int s = 9;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < s; ++j)
            for (int i = 0; i < s; ++i) {
                const weft::CubeCoord c = weft::cubeCoord(weft::cubeTexelDirection(f, i, j, s));
                EXPECT_EQ(c.face, f);
                EXPECT_NEAR(c.u, 2.0f * (i + 0.5f) / s - 1.0f, 1e-5f);
                EXPECT_NEAR(c.v, 2.0f * (j + 0.5f) / s - 1.0f, 1e-5f);
            }
    // +X face: u grows towards -Z, v towards -Y (Vulkan table)
    const glm::vec3 d = weft::cubeDirection(0, 0.5f, 0.25f);
    EXPECT_GT(d.x, 0.0f);
    EXPECT_LT(d.z, 0.0f);
    EXPECT_LT(d.y, 0.0f);
}

TEST(IblCube, SolidAnglesSumToFourPi) {
    for (int s : {1, 3, 64}) {
        double sum = 0.0;
        for (int j = 0; j < s; ++j)
            for (int i = 0; i < s; ++i) sum += weft::cubeTexelSolidAngle(i, j, s);
        EXPECT_NEAR(6.0 * sum, 4.0 * kPi, 1e-9);
    }
}

TEST(IblCube, SamplingAConstantIsExactEverywhere) {
    weft::CubeMap cube = constantCube(5, {0.25f, 0.5f, 2.0f});
    cube.buildMips();
    EXPECT_EQ(cube.levels(), 3); // 5, 2, 1
    std::mt19937 rng(3);
    std::normal_distribution<float> n;
    for (int k = 0; k < 500; ++k) {
        const glm::vec3 v = cube.sampleLod({n(rng), n(rng), n(rng)}, float(k % 4) * 0.9f);
        EXPECT_NEAR(v.x, 0.25f, 1e-5f);
        EXPECT_NEAR(v.z, 2.0f, 1e-5f);
    }
    EXPECT_THROW(cube.sample({0, 0, 0}), weft::InvalidArgument);
}

TEST(IblFilter, Sh9OfAConstantAndALinearEnvironment) {
    // L = 1: only L00 = sqrt(4 pi); E = pi.
    // L = 1 + y: adds L1-1 = sqrt(4 pi / 3), E(+Y) = pi + 2 pi / 3
    weft::CubeMap cube = constantCube(32, {1, 1, 1});
    const int s = cube.size();
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < s; ++j)
            for (int i = 0; i < s; ++i) {
                const float y = weft::cubeTexelDirection(f, i, j, s).y;
                for (int c = 0; c < 3; ++c) cube.texel(f, i, j)[c] = 1.0f + y;
            }
    const weft::Sh9 sh = weft::projectSh9(cube);
    EXPECT_NEAR(sh.coeffs[0].x, std::sqrt(4.0 * kPi), 1e-3);
    EXPECT_NEAR(sh.coeffs[1].x, std::sqrt(4.0 * kPi / 3.0), 1e-3);
    for (int k = 2; k < 9; ++k) EXPECT_NEAR(sh.coeffs[size_t(k)].y, 0.0, 2e-3) << k;
    EXPECT_NEAR(weft::shIrradiance(sh, {0, 1, 0}).x, kPi + 2.0 * kPi / 3.0, 5e-3);
    EXPECT_NEAR(weft::shIrradiance(sh, {1, 0, 0}).x, kPi, 5e-3);
}

TEST(IblFilter, ExactIrradianceOnTheGpuEqualsTheCpu) {
    // Vulkan compute on the selected device (lavapipe on CI); a 128^2 source takes 3 dispatches.
    weft::clearValidationMessages();
    weft::CubeMap cube(128);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> value(0.5f, 1.5f);
    for (size_t k = 0; k < cube.floatCount(); ++k) cube.data()[k] = value(rng);
    double ms = 0.0;
    const weft::CubeMap gpu = weft::irradianceExactGpu(cube, 2, 128, &ms);
    const weft::CubeMap cpu = weft::irradianceExact(cube, 2, 128);
    EXPECT_GT(ms, 0.0);
    ASSERT_EQ(gpu.size(), 2);
    for (size_t k = 0; k < cpu.floatCount(); ++k)
        EXPECT_NEAR(gpu.data()[k], cpu.data()[k], 1e-4 * cpu.data()[k]) << k;
    EXPECT_THROW(weft::irradianceExactGpu(cube, 0, 64), weft::InvalidArgument);
    EXPECT_THROW(weft::irradianceExactGpu(cube, 1024, 1024), weft::InvalidArgument);
    EXPECT_THROW(weft::irradianceExactGpu(weft::CubeMap(), 8, 64), weft::InvalidArgument);
    for (const auto& m : weft::validationMessages()) ADD_FAILURE() << "validation: " << m;
}

TEST(IblFilter, EnvironmentCachesUntilTheRadianceChanges) {
    weft::Environment env(constantCube(8, {1, 1, 1}));
    env.irradianceSh();
    env.irradianceSh();
    EXPECT_EQ(env.stats().filterRuns, 1);
    EXPECT_FALSE(env.stats().lastRefiltered);
    env.setRadiance(constantCube(8, {2, 2, 2}));
    EXPECT_NEAR(env.irradianceSh().coeffs[0].x, 2.0 * std::sqrt(4.0 * kPi), 1e-3);
    EXPECT_EQ(env.stats().filterRuns, 2);
    EXPECT_EQ(env.version(), 2u);
}

TEST(IblConvert, BadArgumentsThrow) {
    std::vector<float> px(4 * 4 * 3, 1.0f);
    const weft::RgbView img{px.data(), 4, 4};
    EXPECT_THROW(weft::sphereToCube(img, glm::mat4(1.0f), 0.0f, 8), weft::InvalidArgument);
    EXPECT_THROW(weft::sphereToCube(img, glm::mat4(1.0f), 1.0f, 0), weft::InvalidArgument);
    EXPECT_THROW(weft::sphereToCube(img, glm::mat4(0.0f), 1.0f, 8), weft::InvalidArgument);
    EXPECT_THROW(weft::fisheyeToCube(img, glm::mat4(1.0f), -1.0f, 8), weft::InvalidArgument);
    px[5] = NAN;
    EXPECT_THROW(weft::equirectToCube(img, 8), weft::InvalidArgument);
    EXPECT_THROW(weft::equirectToCube(weft::RgbView{nullptr, 4, 4}, 8), weft::InvalidArgument);
    EXPECT_THROW(weft::CubeMap(0), weft::InvalidArgument);
}

TEST(IblLights, DomeRoundRobinVisitsEveryLightOnce) {
    const weft::ShadowDome dome(constantCube(8, {1, 1, 1}), 16, weft::DomeLayout::Rings);
    std::multiset<int> seen;
    for (int frame = 0; frame < 4; ++frame)
        for (int i : dome.refreshSet(frame, 4)) seen.insert(i);
    EXPECT_EQ(seen.size(), 16u);
    EXPECT_EQ(std::set<int>(seen.begin(), seen.end()).size(), 16u);
    EXPECT_THROW(weft::ShadowDome::directions(20, weft::DomeLayout::Fibonacci),
                 weft::InvalidArgument);
}

TEST(IblConvert, RgbViewOfAFloatImage) {
    weft::ImageF img(8, 4, 3);
    img.at(2, 1)[0] = 5.0f;
    const weft::RgbView v = weft::rgbView(img);
    EXPECT_EQ(v.width, 8);
    EXPECT_EQ(v.height, 4);
    EXPECT_EQ(v.pixels[(1 * 8 + 2) * 3], 5.0f);
    EXPECT_EQ(weft::equirectToCube(v, 4).size(), 4);
    EXPECT_THROW(weft::rgbView(weft::ImageF(8, 4, 4)), weft::InvalidArgument);
}
