// The cloth step (SPEC §2.3, seed alg. 3.1 + beyond): normals (eq. 3.6), gravity and wind
// (eq. 3.5), Position Verlet with damping (eq. 3.12), then relaxation sweeps of XPBD distance
// constraints (eq. 3.3/3.4 when compliance is 0) over conflict-free batches, tethers and
// collider projections (eq. 3.7), self-collision, tearing and sleeping.
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <unordered_map>

#include "sim/cloth/ClothImpl.h"

namespace weft {

using cloth::Particle;

namespace {
// Below this many constraints a batch is projected on the calling thread: a fork-join and the
// cache lines that move between cores cost more than the work.
constexpr int kMinParallelConstraints = 4096;
constexpr int kMinParallelParticles = 4096;
// The SoA path splits every pass of a substep by the same rows (integration, each batch, the
// tethers, the copy back), so each thread keeps its part of the cloth in its own cache; it
// splits all of them or none (a pass that ran on one thread would pull the other's part
// over). Below this many particles one thread is faster than the fork-joins.
int soaMinParallel() {
    static const int v =
        std::getenv("WEFT_CLOTH_SOA_MIN") ? std::atoi(std::getenv("WEFT_CLOTH_SOA_MIN")) : 8192;
    return v;
}

float compliance(const ClothParams& p, ConstraintFamily f) {
    switch (f) {
    case ConstraintFamily::Stretch: return p.complianceStretch;
    case ConstraintFamily::Shear: return p.complianceShear;
    case ConstraintFamily::Bend: return p.complianceBend;
    }
    return 0.0f;
}
} // namespace

void Cloth::Impl::computeNormals() const {
    const int nx = params.nx, ny = params.ny;
    pool->parallelFor(
        ny,
        [&](int j0, int j1) {
            for (int j = j0; j < j1; ++j) {
                const int jm = std::max(j - 1, 0), jp = std::min(j + 1, ny - 1);
                for (int i = 0; i < nx; ++i) {
                    const int im = std::max(i - 1, 0), ip = std::min(i + 1, nx - 1);
                    const glm::vec3 du =
                        particles[size_t(j * nx + ip)].x - particles[size_t(j * nx + im)].x;
                    const glm::vec3 dv =
                        particles[size_t(jp * nx + i)].x - particles[size_t(jm * nx + i)].x;
                    const glm::vec3 c = glm::cross(dv, du);
                    const float len = glm::length(c);
                    glm::vec4& out = normals[size_t(j * nx + i)];
                    if (len > 1e-20f) out = glm::vec4(c / len, 0.0f); // else keep the last normal
                }
            }
        },
        64);
    normalsStale = false;
}

void Cloth::Impl::projectBatch(const cloth::Batch& batch, float alphaTilde) {
    const cloth::Constraint& first = constraints[size_t(batch.begin)];
    const size_t c0 = size_t(batch.begin);
    const cloth::BatchJob job{endA.data() + c0,
                              batch.end - batch.begin,
                              batch.dy * params.nx + batch.dx,
                              restLength.data() + c0,
                              active.data() + c0,
                              lambda.data() + c0,
                              alphaTilde,
                              rest[size_t(first.b)] - rest[size_t(first.a)]};
    pool->parallelFor(
        job.count,
        [&](int q0, int q1) {
            cloth::BatchJob part = job;
            part.a += q0;
            part.rest += q0;
            part.on += q0;
            part.lambda += q0;
            part.count = q1 - q0;
            cloth::projectBatch(particles.data(), part, isa);
        },
        kMinParallelConstraints);
}

void Cloth::Impl::collide(int begin, int end, bool friction) {
    const float thickness = params.thickness;
    for (int k = begin; k < end; ++k) {
        Particle& p = particles[size_t(k)];
        if (p.w == 0.0f) continue;
        for (const Collider& c : localColliders) {
            glm::vec3 n;
            const float s = c.distance(p.x, n);
            if (s >= thickness) continue;
            p.x += (thickness - s) * n;
            if (friction && c.friction > 0.0f) {
                const glm::vec3 v = p.x - previous[size_t(k)].x;
                previous[size_t(k)].x += (v - n * glm::dot(v, n)) * c.friction;
            }
        }
    }
}

void Cloth::Impl::relax(float h) {
    const float h2 = h * h;
    for (const cloth::Batch& b : batches) projectBatch(b, compliance(params, b.family) / h2);
    if (tetherSlots > 0) {
        pool->parallelFor(
            n,
            [&](int k0, int k1) {
                cloth::projectTethers(
                    particles.data(),
                    {k0, k1, tetherSlots, n, tetherAnchor.data(), tetherLength.data()}, isa);
            },
            kMinParallelParticles);
    }
    if (!colliders.empty())
        pool->parallelFor(
            n, [&](int a, int b) { collide(a, b, true); }, 1024);
}

int Cloth::Impl::soaSplit() const { return n >= soaMinParallel() ? 1 : INT_MAX; }

void Cloth::Impl::fromSoa() {
    const cloth::SoaParticles s = soaParticles();
    const cloth::SoaGrid grid{params.nx, params.ny, 2 * params.bendDistance, soaSegment};
    pool->parallelFor(
        params.ny,
        [&](int j0, int j1) {
            cloth::soaRowsToRecords(s, particles.data(), j0, j1, grid, soaSlot.data());
        },
        soaSplit());
}

void Cloth::Impl::relaxSoa(float h) {
    const float h2 = h * h;
    const cloth::SoaParticles s = soaParticles();
    for (size_t b = 0; b < batches.size(); ++b) {
        const cloth::Batch& batch = batches[b];
        const cloth::Constraint& first = constraints[size_t(batch.begin)];
        const cloth::DenseBatchJob job{batch.rowBegin,
                                       batch.rowEnd,
                                       soaSegment,
                                       batchSegments.data() + batch.segmentsBegin,
                                       batch.segmentsEnd - batch.segmentsBegin,
                                       batch.dx == 0 ? std::abs(batch.dy) : 0,
                                       batch.parity,
                                       denseRest.data() + b * size_t(soaSlots),
                                       denseLambda.data() + b * size_t(soaSlots),
                                       compliance(params, batch.family) / h2,
                                       rest[size_t(first.b)] - rest[size_t(first.a)]};
        pool->parallelFor(
            params.ny,
            [&](int j0, int j1) {
                cloth::DenseBatchJob part = job;
                part.rowBegin = std::max(job.rowBegin, j0);
                part.rowEnd = std::min(job.rowEnd, j1);
                if (part.rowEnd > part.rowBegin) cloth::projectDense(s, part);
            },
            soaSplit());
    }
    if (tetherSlots > 0) {
        const int m = 2 * params.bendDistance, stride = params.ny * soaSegment;
        pool->parallelFor(
            params.ny,
            [&](int j0, int j1) {
                for (int c = 0; c < m; ++c)
                    cloth::projectTethersSoa(
                        s, {{c * stride + j0 * soaSegment, c * stride + j1 * soaSegment,
                             tetherSlots, soaSlots, tetherAnchorSoa.data(), tetherLengthSoa.data()},
                            tetherTable.empty() ? nullptr : tetherTable.data(),
                            int(tetherTable.size())});
            },
            soaSplit());
    }
}

void Cloth::Impl::substep(float h, float damping) {
    const bool windy = wind.strength != 0.0f;
    if (windy) computeNormals();
    const glm::vec3 r = windy ? glm::normalize(wind.direction) : glm::vec3(0.0f);
    const glm::vec3 g = params.gravity;
    if (hasPendingVelocity) {
        for (int k = 0; k < n; ++k)
            previous[size_t(k)].x =
                particles[size_t(k)].x - pendingVelocity[size_t(k)] * h + 0.5f * g * h * h;
        hasPendingVelocity = false;
    }
    if (params.selfCollision) rememberSelfStart();
    for (size_t q = 0; q < grabbed.size(); ++q) {
        const int k = grabbed[q];
        previous[size_t(k)].x = particles[size_t(k)].x;
        particles[size_t(k)].x = grabTargets[q];
    }
    const cloth::IntegrateJob job{0,
                                  0,
                                  pinned.data(),
                                  hole.data(),
                                  g,
                                  h,
                                  damping,
                                  windy ? normals.data() : nullptr,
                                  r,
                                  wind.strength};
    const bool compliant =
        params.complianceStretch > 0 || params.complianceShear > 0 || params.complianceBend > 0;
    if (useSoa && colliders.empty()) {
        // the same integration and sweeps on the structure-of-arrays layout (bit-identical
        // results); the integration writes the new positions there directly
        if (denseStale) syncDense();
        if (compliant) std::fill(denseLambda.begin(), denseLambda.end(), 0.0f);
        const cloth::SoaParticles s = soaParticles();
        const cloth::SoaGrid grid{params.nx, params.ny, 2 * params.bendDistance, soaSegment};
        pool->parallelFor(
            params.ny,
            [&](int j0, int j1) {
                cloth::IntegrateJob part = job;
                part.begin = j0;
                part.end = j1;
                cloth::integrateRowsToSoa(particles.data(), previous.data(), part, s, grid,
                                          soaSlot.data());
            },
            soaSplit());
        for (int it = 0; it < params.iterations; ++it) relaxSoa(h);
        fromSoa();
    } else {
        pool->parallelFor(
            n,
            [&](int k0, int k1) {
                cloth::IntegrateJob part = job;
                part.begin = k0;
                part.end = k1;
                cloth::integrate(particles.data(), previous.data(), part, isa);
            },
            kMinParallelParticles);
        if (compliant) std::fill(lambda.begin(), lambda.end(), 0.0f);
        for (int it = 0; it < params.iterations; ++it) relax(h);
    }
    if (params.selfCollision) selfCollide();
}

void Cloth::Impl::afterStep(float dt) {
    if (params.tearStrain > 0.0f) tearFaces();
    if (params.sleepThreshold > 0.0f) {
        double sum = 0.0;
        int count = 0;
        for (int k = 0; k < n; ++k) {
            if (particles[size_t(k)].w == 0.0f) continue;
            sum += glm::length(particles[size_t(k)].x - previous[size_t(k)].x);
            ++count;
        }
        const double h = double(dt) / params.substeps;
        const double meanSpeed = count ? sum / count / h : 0.0;
        quietSteps = meanSpeed < params.sleepThreshold ? quietSteps + 1 : 0;
        if (quietSteps >= params.sleepSteps) asleep = true;
    }
}

} // namespace weft
