// The SIMD row projection against the scalar definition on random data: pinned particles,
// broken constraints, coincident ends, XPBD multipliers, rows whose length is no multiple of 4.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "sim/cloth/ClothKernels.h"

namespace {

using weft::cloth::Particle;
using weft::cloth::RowJob;

struct RowCase {
    std::vector<Particle> particles;
    std::vector<int> cols;
    std::vector<float> rest, lambda;
    std::vector<uint8_t> on;
};

RowCase randomRow(std::mt19937& rng, int nx, int dx, int count) {
    std::uniform_real_distribution<float> pos(-1.0f, 1.0f), unit(0.0f, 1.0f);
    RowCase rc;
    rc.particles.resize(size_t(nx) * 3);
    for (Particle& p : rc.particles) {
        p.x = glm::vec3(pos(rng), pos(rng), pos(rng));
        p.w = unit(rng) < 0.2f ? 0.0f : 1.0f + 100.0f * unit(rng);
    }
    // Constraint q joins column cols[q] of row 0 and column cols[q] + dx of row 1 (no two share
    // a particle, as in a batch).
    for (int q = 0; q < count; ++q) rc.cols.push_back(q * (dx + 1));
    for (int q = 0; q < count; ++q) {
        rc.rest.push_back(0.01f + unit(rng));
        rc.lambda.push_back(pos(rng) * 1e-3f);
        rc.on.push_back(unit(rng) < 0.15f ? 0 : 1);
        if (unit(rng) < 0.1f) // coincident ends
            rc.particles[size_t(rc.cols[size_t(q)] + nx + dx)].x = rc.particles[size_t(rc.cols[size_t(q)])].x;
    }
    return rc;
}

} // namespace

TEST(ClothKernels, SimdRowEqualsScalarRow) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 200; ++trial) {
        const int dx = trial % 3, count = 1 + trial % 23, nx = count * (dx + 1) + dx;
        for (float alphaTilde : {0.0f, 0.5f, 3600.0f}) {
            RowCase simd = randomRow(rng, nx, dx, count);
            RowCase scalar = simd;
            auto job = [&](RowCase& rc) {
                return RowJob{rc.cols.data(), count, nx + dx, rc.rest.data(), rc.on.data(),
                              rc.lambda.data(), alphaTilde, glm::vec3(0.01f, -0.02f, 0.0f)};
            };
            weft::cloth::projectRow(simd.particles.data(), job(simd));
            weft::cloth::projectRowScalar(scalar.particles.data(), job(scalar));
            for (size_t k = 0; k < simd.particles.size(); ++k) {
                ASSERT_EQ(simd.particles[k].x, scalar.particles[k].x) << trial << " " << k;
                ASSERT_EQ(simd.particles[k].w, scalar.particles[k].w);
            }
            ASSERT_EQ(simd.lambda, scalar.lambda) << trial;
        }
    }
}

TEST(ClothKernels, ProjectionSatisfiesTheConstraintAndKeepsPinnedParticles) {
    std::vector<Particle> ps(8);
    for (int k = 0; k < 8; ++k) ps[size_t(k)] = {glm::vec3(float(k), 0.0f, 0.0f), k == 0 ? 0.0f : 1.0f};
    // Four constraints (0,4) (1,5) (2,6) (3,7) of rest length 2: one SIMD group.
    const std::vector<int> cols = {0, 1, 2, 3};
    const std::vector<float> rest(4, 2.0f);
    const std::vector<uint8_t> on = {1, 1, 1, 0};
    std::vector<float> lambda(4, 0.0f);
    weft::cloth::projectRow(ps.data(), RowJob{cols.data(), 4, 4, rest.data(), on.data(),
                                              lambda.data(), 0.0f, glm::vec3(4, 0, 0)});
    EXPECT_EQ(ps[0].x, glm::vec3(0, 0, 0)); // pinned: the other end moves all the way
    EXPECT_FLOAT_EQ(ps[4].x.x, 2.0f);
    EXPECT_FLOAT_EQ(ps[1].x.x, 2.0f); // equal masses share the correction
    EXPECT_FLOAT_EQ(ps[5].x.x, 4.0f);
    EXPECT_EQ(ps[3].x.x, 3.0f); // broken constraint untouched
    EXPECT_EQ(ps[7].x.x, 7.0f);
}
