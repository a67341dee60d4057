#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <vector>

#include <weft/Cloth.h>

namespace {

weft::ClothParams hanging(int n, int threads) {
    weft::ClothParams p;
    p.nx = p.ny = n;
    p.origin = glm::vec3(-0.5f, 1.5f, 0.0f);
    p.axisU = glm::vec3(1, 0, 0);
    p.axisV = glm::vec3(0, -1, 0);
    p.substeps = 3;
    p.iterations = 2;
    p.tethers = true;
    p.threads = threads;
    return p;
}

} // namespace

TEST(Cloth, ResultDoesNotDependOnThreadCount) {
    weft::Cloth one(hanging(96, 1)), two(hanging(96, 2));
    weft::Wind wind;
    wind.direction = glm::vec3(0.3f, 0.0f, 1.0f);
    wind.strength = 4.0f;
    for (weft::Cloth* c : {&one, &two}) {
        c->pin({0, 95});
        c->setWind(wind);
        weft::Collider sphere;
        sphere.center = glm::vec3(0.0f, 0.8f, 0.1f);
        sphere.radius = 0.2f;
        c->addCollider(sphere);
        for (int s = 0; s < 20; ++s) c->step(1.0f / 60.0f);
    }
    const size_t bytes = size_t(one.particleCount()) * 16;
    EXPECT_EQ(std::memcmp(one.particleData(), two.particleData(), bytes), 0);
}

TEST(Cloth, HolesTearsAndComplianceDoNotDependOnThreadCount) {
    // A 131 x 97 grid: batches large enough to run in parallel, lengths no multiple of the SIMD
    // width, a hole (inactive constraints), tearing enabled, a grab and XPBD compliance (the
    // multipliers are read and written).
    std::vector<std::vector<uint8_t>> results;
    for (int threads : {1, 2, 3}) {
        weft::ClothParams p = hanging(131, threads);
        p.ny = 97;
        p.complianceShear = 1e-4f;
        p.complianceBend = 1e-2f;
        p.tearStrain = 0.05f;
        weft::Cloth c(p);
        c.pin({0, 130});
        std::vector<uint8_t> mask(size_t(131 * 97), 0);
        for (int j = 40; j < 50; ++j)
            for (int i = 60; i < 75; ++i) mask[size_t(j * 131 + i)] = 1;
        c.setHoles(mask);
        c.grab({65}, {glm::vec3(0.3f, 1.2f, 0.4f)});
        for (int s = 0; s < 15; ++s) c.step(1.0f / 60.0f);
        const auto* bytes = reinterpret_cast<const uint8_t*>(c.particleData());
        results.emplace_back(bytes, bytes + size_t(c.particleCount()) * 16);
        std::vector<int> a, b;
        std::vector<float> rest;
        std::vector<uint8_t> family, active;
        c.constraints(a, b, rest, family, active);
        results.back().insert(results.back().end(), active.begin(), active.end());
        EXPECT_LT(std::count(active.begin(), active.end(), 1), int(active.size()));
    }
    EXPECT_EQ(results[0], results[1]);
    EXPECT_EQ(results[0], results[2]);
}

TEST(Cloth, PinnedParticlesStayAndStrainIsSmallWithTethers) {
    weft::Cloth c(hanging(32, 0));
    c.pin({0, 31});
    const glm::vec3 corner(c.particleData()[0], c.particleData()[1], c.particleData()[2]);
    for (int s = 0; s < 120; ++s) c.step(1.0f / 60.0f);
    EXPECT_EQ(glm::vec3(c.particleData()[0], c.particleData()[1], c.particleData()[2]), corner);
    const weft::ClothStats st = c.stats();
    EXPECT_LT(st.meanStrain, 0.01f);
    EXPECT_GT(st.activeConstraints, 0);
    for (int k = 0; k < c.particleCount() * 4; ++k) ASSERT_TRUE(std::isfinite(c.particleData()[k]));
}

TEST(Cloth, RejectsImpossibleParameters) {
    weft::ClothParams p;
    p.nx = 0;
    EXPECT_THROW(weft::Cloth{p}, weft::InvalidArgument);
    p = {};
    p.size.x = std::nanf("");
    EXPECT_THROW(weft::Cloth{p}, weft::InvalidArgument);
    p = {};
    p.axisV = p.axisU;
    EXPECT_THROW(weft::Cloth{p}, weft::InvalidArgument);
    weft::Cloth c;
    EXPECT_THROW(c.step(0.0f), weft::InvalidArgument);
    EXPECT_THROW(c.step(INFINITY), weft::InvalidArgument);
    EXPECT_THROW(c.pin({-1}), weft::InvalidArgument);
    EXPECT_THROW(c.setPositions(std::vector<glm::vec3>(3)), weft::InvalidArgument);
}
