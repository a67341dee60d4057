// The SIMD projections (SSE, AVX where the CPU has it) against the scalar definition on random
// data: pinned particles, broken constraints, coincident ends, XPBD multipliers, lengths that
// are no multiple of the SIMD width.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

#include "sim/cloth/ClothKernels.h"

namespace {

using weft::cloth::BatchJob;
using weft::cloth::Isa;
using weft::cloth::Particle;

bool anyMoved(const std::vector<Particle>& p, const std::vector<Particle>& q) {
    for (size_t k = 0; k < p.size(); ++k)
        if (p[k].x != q[k].x) return true;
    return false;
}

struct RowCase {
    std::vector<Particle> particles;
    std::vector<int> a;
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
    // Constraint q joins column a[q] of row 0 and column a[q] + dx of row 1 (no two share a
    // particle, as in a batch).
    for (int q = 0; q < count; ++q) rc.a.push_back(q * (dx + 1));
    for (int q = 0; q < count; ++q) {
        rc.rest.push_back(0.01f + unit(rng));
        rc.lambda.push_back(pos(rng) * 1e-3f);
        rc.on.push_back(unit(rng) < 0.15f ? 0 : 1);
        if (unit(rng) < 0.1f) // coincident ends
            rc.particles[size_t(rc.a[size_t(q)] + nx + dx)].x =
                rc.particles[size_t(rc.a[size_t(q)])].x;
    }
    return rc;
}

} // namespace

TEST(ClothKernels, SimdEqualsScalar) {
    std::vector<Isa> simd = {Isa::Sse};
    if (weft::cloth::bestIsa() == Isa::Avx) simd.push_back(Isa::Avx);
    if (weft::cloth::bestIsa() == Isa::Scalar) GTEST_SKIP() << "no SIMD in this build";
    std::mt19937 rng(7);
    int moved = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const int dx = trial % 3, count = 1 + trial % 37, nx = count * (dx + 1) + dx;
        for (float alphaTilde : {0.0f, 0.5f, 3600.0f}) {
            const RowCase start = randomRow(rng, nx, dx, count);
            auto project = [&](Isa isa) {
                RowCase rc = start;
                weft::cloth::projectBatch(rc.particles.data(),
                                          BatchJob{rc.a.data(), count, nx + dx, rc.rest.data(),
                                                   rc.on.data(), rc.lambda.data(), alphaTilde,
                                                   glm::vec3(0.01f, -0.02f, 0.0f)},
                                          isa);
                return rc;
            };
            const RowCase scalar = project(Isa::Scalar);
            for (Isa isa : simd) {
                const RowCase got = project(isa);
                for (size_t k = 0; k < got.particles.size(); ++k) {
                    ASSERT_EQ(got.particles[k].x, scalar.particles[k].x) << trial << " " << k;
                    ASSERT_EQ(got.particles[k].w, scalar.particles[k].w);
                }
                ASSERT_EQ(got.lambda, scalar.lambda) << trial;
            }
            moved += anyMoved(scalar.particles, start.particles);
        }
    }
    EXPECT_GT(moved, 800); // the cases do project something
}

TEST(ClothKernels, ProjectionSatisfiesTheConstraintAndKeepsPinnedParticles) {
    std::vector<Particle> ps(8);
    for (int k = 0; k < 8; ++k)
        ps[size_t(k)] = {glm::vec3(float(k), 0.0f, 0.0f), k == 0 ? 0.0f : 1.0f};
    // Four constraints (0,4) (1,5) (2,6) (3,7) of rest length 2: one SSE group.
    const std::vector<int> a = {0, 1, 2, 3};
    const std::vector<float> rest(4, 2.0f);
    const std::vector<uint8_t> on = {1, 1, 1, 0};
    std::vector<float> lambda(4, 0.0f);
    weft::cloth::projectBatch(
        ps.data(),
        BatchJob{a.data(), 4, 4, rest.data(), on.data(), lambda.data(), 0.0f, glm::vec3(4, 0, 0)},
        weft::cloth::bestIsa());
    EXPECT_EQ(ps[0].x, glm::vec3(0, 0, 0)); // pinned: the other end moves all the way
    EXPECT_FLOAT_EQ(ps[4].x.x, 2.0f);
    EXPECT_FLOAT_EQ(ps[1].x.x, 2.0f); // equal masses share the correction
    EXPECT_FLOAT_EQ(ps[5].x.x, 4.0f);
    EXPECT_EQ(ps[3].x.x, 3.0f); // broken constraint untouched
    EXPECT_EQ(ps[7].x.x, 7.0f);
}

TEST(ClothKernels, SimdTethersEqualScalar) {
    if (weft::cloth::bestIsa() == Isa::Scalar) GTEST_SKIP() << "no SIMD in this build";
    std::vector<Isa> simd = {Isa::Sse};
    if (weft::cloth::bestIsa() == Isa::Avx) simd.push_back(Isa::Avx);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> pos(-1.0f, 1.0f), unit(0.0f, 1.0f);
    int pulled = 0;
    for (int trial = 0; trial < 100; ++trial) {
        const int n = 3 + trial % 41, slots = 1 + trial % 4;
        std::vector<Particle> start(static_cast<size_t>(n));
        std::vector<int> anchors;
        for (int k = 0; k < n; ++k) {
            const bool anchor = k == 0 || unit(rng) < 0.1f;
            start[size_t(k)] = {glm::vec3(pos(rng), pos(rng), pos(rng)), anchor ? 0.0f : 1.0f};
            if (anchor) anchors.push_back(k);
        }
        std::vector<int> anchor(size_t(slots * n));
        std::vector<float> length(size_t(slots * n));
        for (size_t t = 0; t < anchor.size(); ++t) {
            anchor[t] = anchors[size_t(rng() % anchors.size())];
            length[t] =
                unit(rng) < 0.2f ? std::numeric_limits<float>::infinity() : 0.2f + unit(rng);
        }
        const int begin = trial % 3, end = n - trial % 2;
        auto project = [&](Isa isa) {
            std::vector<Particle> ps = start;
            weft::cloth::projectTethers(ps.data(),
                                        {begin, end, slots, n, anchor.data(), length.data()}, isa);
            return ps;
        };
        const std::vector<Particle> scalar = project(Isa::Scalar);
        pulled += anyMoved(scalar, start);
        for (Isa isa : simd) {
            const std::vector<Particle> got = project(isa);
            for (size_t k = 0; k < got.size(); ++k) {
                ASSERT_EQ(got[k].x, scalar[k].x) << trial << " " << k;
                ASSERT_EQ(got[k].w, scalar[k].w);
            }
        }
        for (int k : anchors) ASSERT_EQ(scalar[size_t(k)].x, start[size_t(k)].x); // anchors stay
        for (int k = 0; k < begin; ++k) ASSERT_EQ(scalar[size_t(k)].x, start[size_t(k)].x);
    }
    EXPECT_GT(pulled, 80);
}

TEST(ClothKernels, SimdIntegrationEqualsScalar) {
    if (weft::cloth::bestIsa() == Isa::Scalar) GTEST_SKIP() << "no SIMD in this build";
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> pos(-1.0f, 1.0f), unit(0.0f, 1.0f);
    const int n = 37;
    for (bool windy : {false, true}) {
        std::vector<Particle> x(static_cast<size_t>(n)), prev(static_cast<size_t>(n));
        std::vector<uint8_t> pinned(static_cast<size_t>(n)), hole(static_cast<size_t>(n));
        std::vector<glm::vec4> normals(static_cast<size_t>(n));
        for (int k = 0; k < n; ++k) {
            const float r = unit(rng);
            pinned[size_t(k)] = r < 0.2f;
            hole[size_t(k)] = r > 0.1f && r < 0.3f;
            const bool grabbed = r > 0.9f;
            const float w =
                pinned[size_t(k)] || hole[size_t(k)] || grabbed ? 0.0f : 1.0f + unit(rng);
            x[size_t(k)] = {glm::vec3(pos(rng), pos(rng), pos(rng)), w};
            prev[size_t(k)] = {glm::vec3(pos(rng), pos(rng), pos(rng)), 0.0f};
            normals[size_t(k)] =
                glm::vec4(glm::normalize(glm::vec3(pos(rng), pos(rng), 1.0f)), 0.0f);
        }
        const weft::cloth::IntegrateJob job{2,
                                            n - 1,
                                            pinned.data(),
                                            hole.data(),
                                            glm::vec3(0.1f, -9.81f, 0.2f),
                                            1.0f / 60.0f,
                                            0.99f,
                                            windy ? normals.data() : nullptr,
                                            glm::normalize(glm::vec3(1.0f, 0.2f, 0.5f)),
                                            7.0f};
        auto run = [&](Isa isa, std::vector<Particle>& px, std::vector<Particle>& pp) {
            px = x;
            pp = prev;
            weft::cloth::integrate(px.data(), pp.data(), job, isa);
        };
        std::vector<Particle> sx, sp, vx, vp;
        run(Isa::Scalar, sx, sp);
        run(weft::cloth::bestIsa(), vx, vp);
        for (size_t k = 0; k < size_t(n); ++k) {
            ASSERT_EQ(vx[k].x, sx[k].x) << windy << " " << k;
            ASSERT_EQ(vx[k].w, sx[k].w);
            ASSERT_EQ(vp[k].x, sp[k].x) << windy << " " << k;
        }
        EXPECT_TRUE(anyMoved(sx, x));
        EXPECT_EQ(sx[0].x, x[0].x); // outside [begin, end)
        EXPECT_EQ(sx[size_t(n) - 1].x, x[size_t(n) - 1].x);
    }
}
