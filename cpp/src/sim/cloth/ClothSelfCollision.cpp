// Self-collision (SPEC §2.5): particle-particle repulsion with a thickness T, accelerated by a
// spatial hash, made continuous over the substep so that a layer cannot pass through another
// between two checks (issue 17 item 7), and followed by the colliders again so that it never
// leaves a particle inside a collider's thickness.
//
// A pair (p, q) whose rest distance exceeds T interacts in two ways, judged from the positions
// at the start of the substep (with their normals) and now:
// - crossed: they are more than kLayerRest T apart at rest (not neighbours in one smooth
//   sheet), p was strictly on one side of q's start tangent plane and is now on the other (or
//   in it), and their straight relative path met that plane within T of q (through the cloth
//   around q): p goes back to its side, T from the plane. A check of the end positions alone
//   (the seed's repulsion) pushes such a particle further through.
// - otherwise, closer than T now: pushed apart along their separation to T (an isolated pair
//   ends exactly T apart).
// Corrections are weighted w_p / (w_p + w_q), except that a particle resting on a collider gives
// way to none that is not (the collider would push it straight back, and the pair would stay
// half resolved). Each particle moves by the mean of its pairs' corrections, all computed from
// the same positions (Jacobi, so the result does not depend on the thread count), in
// kSelfCollisionPasses passes; after each, the colliders project again.
// The NumPy cloth runs the same algorithm (weft/reference/cloth_self.py).
#include <algorithm>
#include <cmath>

#include "sim/cloth/ClothImpl.h"

namespace weft {

using cloth::Particle;

namespace {
// Pairs at most this many T apart at rest may lie in one smooth sheet, where a wrinkle takes
// one through the other's tangent plane without any layer being crossed: for them only the
// distance counts.
constexpr float kLayerRest = 2.0f;
// A particle closer to a collider than its thickness plus this fraction of T rests on it.
constexpr float kGroundSlack = 0.01f;
// The hash's cell grows with the spread of the substep's motion (below); past this many T
// the search would cost too much, and faster relative motion may still tunnel.
constexpr float kMaxCellOverT = 2.0f;
// Candidate pairs: relative paths within this many T; at most kMaxCandidates per particle
// (a dozen per layer within reach: room for ~5 stacked layers).
constexpr float kCandidateOverT = 2.0f;
constexpr int kMaxCandidates = 64;
} // namespace

void Cloth::Impl::rememberSelfStart() {
    const int nx = params.nx, ny = params.ny;
    selfStart.resize(size_t(n));
    selfStartNormal.resize(size_t(n));
    for (int k = 0; k < n; ++k) selfStart[size_t(k)] = particles[size_t(k)].x;
    pool->parallelFor(
        ny,
        [&](int j0, int j1) {
            for (int j = j0; j < j1; ++j) {
                const int jm = std::max(j - 1, 0), jp = std::min(j + 1, ny - 1);
                for (int i = 0; i < nx; ++i) {
                    const int im = std::max(i - 1, 0), ip = std::min(i + 1, nx - 1);
                    const glm::vec3 du =
                        selfStart[size_t(j * nx + ip)] - selfStart[size_t(j * nx + im)];
                    const glm::vec3 dv =
                        selfStart[size_t(jp * nx + i)] - selfStart[size_t(jm * nx + i)];
                    const glm::vec3 c = glm::cross(dv, du);
                    const float len = glm::length(c);
                    selfStartNormal[size_t(j * nx + i)] = len > 1e-20f ? c / len : glm::vec3(0.0f);
                }
            }
        },
        64);
}

void Cloth::Impl::selfCollide() {
    const float spacingU = params.nx > 1 ? params.size.x / float(params.nx - 1) : params.size.y;
    const float spacingV = params.ny > 1 ? params.size.y / float(params.ny - 1) : params.size.x;
    const float T =
        params.selfThickness > 0.0f ? params.selfThickness : 0.9f * std::min(spacingU, spacingV);
    // The swept test of a pair needs the distance of their midpoints m = (x0 + x) / 2 below
    // T + (|e_p| + |e_q|) / 2, where e is a particle's motion minus the mean motion (a cloth
    // falling as a whole needs no wider search). Hashing the midpoints with cells of
    // T + max |e| keeps every such pair within the 27 cells around each particle.
    glm::dvec3 meanMotion(0.0);
    int moving = 0;
    for (int k = 0; k < n; ++k) {
        if (hole[size_t(k)]) continue;
        meanMotion += glm::dvec3(particles[size_t(k)].x - selfStart[size_t(k)]);
        ++moving;
    }
    const glm::vec3 mean = moving ? glm::vec3(meanMotion / double(moving)) : glm::vec3(0.0f);
    float spread = 0.0f;
    for (int k = 0; k < n; ++k)
        if (!hole[size_t(k)])
            spread =
                std::max(spread, glm::length(particles[size_t(k)].x - selfStart[size_t(k)] - mean));
    const float cell = std::min(T + spread, kMaxCellOverT * T);

    std::vector<glm::vec3> mid(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k)
        mid[size_t(k)] = 0.5f * (selfStart[size_t(k)] + particles[size_t(k)].x);
    const size_t tableSize = size_t(2 * n + 1);
    auto cellOf = [&](const glm::vec3& x) { return glm::ivec3(glm::floor(x / cell)); };
    auto hashOf = [&](const glm::ivec3& c) {
        return size_t((uint32_t(c.x) * 73856093u) ^ (uint32_t(c.y) * 19349663u) ^
                      (uint32_t(c.z) * 83492791u)) %
               tableSize;
    };
    std::vector<int> start(tableSize + 1, 0);
    std::vector<int> order(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) ++start[hashOf(cellOf(mid[size_t(k)])) + 1];
    for (size_t b = 0; b < tableSize; ++b) start[b + 1] += start[b];
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int k = 0; k < n; ++k) order[size_t(fill[hashOf(cellOf(mid[size_t(k)]))]++)] = k;

    // Candidates, once per substep: pairs whose relative path comes within kCandidateOverT T
    // (the passes move particles by up to ~T, so closer pairs may form after the first one).
    // The sign of q records whether the pair may be in different layers (rest > kLayerRest T).
    candidateCount.assign(size_t(n), 0);
    candidates.resize(size_t(n) * kMaxCandidates);
    const float reach2 = kCandidateOverT * kCandidateOverT * T * T;
    pool->parallelFor(
        n,
        [&](int k0, int k1) {
            for (int k = k0; k < k1; ++k) {
                if (particles[size_t(k)].w == 0.0f || hole[size_t(k)]) continue;
                const glm::ivec3 c = cellOf(mid[size_t(k)]);
                // The 27 cells may share buckets (hash collisions): visit each bucket once, so
                // no neighbour is counted twice.
                size_t buckets[27];
                int bucketCount = 0;
                for (int dz = -1; dz <= 1; ++dz)
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const size_t h = hashOf(c + glm::ivec3(dx, dy, dz));
                            if (std::find(buckets, buckets + bucketCount, h) ==
                                buckets + bucketCount)
                                buckets[bucketCount++] = h;
                        }
                int* list = candidates.data() + size_t(k) * kMaxCandidates;
                int count = 0;
                for (int bi = 0; bi < bucketCount && count < kMaxCandidates; ++bi) {
                    const size_t h = buckets[bi];
                    for (int s = start[h]; s < start[h + 1] && count < kMaxCandidates; ++s) {
                        const int q = order[size_t(s)];
                        if (q == k || hole[size_t(q)]) continue;
                        // Neighbours that are closer than T at rest are the constraints' job.
                        const float restDistance = glm::length(rest[size_t(k)] - rest[size_t(q)]);
                        if (restDistance <= T) continue;
                        const glm::vec3 r0 = selfStart[size_t(k)] - selfStart[size_t(q)];
                        const glm::vec3 dr = (particles[size_t(k)].x - particles[size_t(q)].x) - r0;
                        const float dr2 = glm::dot(dr, dr);
                        const float t =
                            dr2 > 0.0f ? std::clamp(-glm::dot(r0, dr) / dr2, 0.0f, 1.0f) : 0.0f;
                        const glm::vec3 closest = r0 + t * dr;
                        if (glm::dot(closest, closest) >= reach2) continue;
                        list[count++] = restDistance > kLayerRest * T ? q : -1 - q;
                    }
                }
                candidateCount[size_t(k)] = count;
            }
        },
        1024);

    std::vector<uint8_t> grounded(static_cast<size_t>(n), 0);
    std::vector<glm::vec3> delta(static_cast<size_t>(n));
    for (int pass = 0; pass < cloth::kSelfCollisionPasses; ++pass) {
        if (!colliders.empty()) {
            pool->parallelFor(
                n,
                [&](int k0, int k1) {
                    for (int k = k0; k < k1; ++k) {
                        grounded[size_t(k)] = 0;
                        for (const Collider& c : localColliders) {
                            glm::vec3 nrm;
                            if (c.distance(particles[size_t(k)].x, nrm) <
                                params.thickness + kGroundSlack * T)
                                grounded[size_t(k)] = 1;
                        }
                    }
                },
                1024);
        }
        pool->parallelFor(
            n,
            [&](int k0, int k1) {
                for (int k = k0; k < k1; ++k) {
                    const Particle& p = particles[size_t(k)];
                    const int* list = candidates.data() + size_t(k) * kMaxCandidates;
                    glm::vec3 sum(0.0f);
                    int contacts = 0;
                    for (int ci = 0; ci < candidateCount[size_t(k)]; ++ci) {
                        const bool layers = list[ci] >= 0;
                        const int q = layers ? list[ci] : -1 - list[ci];
                        // A particle resting on a collider does not give way (the collider would
                        // push it straight back): the other one takes the whole correction.
                        float share = p.w / (p.w + particles[size_t(q)].w);
                        if (grounded[size_t(k)] != grounded[size_t(q)])
                            share = grounded[size_t(k)] ? 0.0f : 1.0f;
                        const glm::vec3 r0 = selfStart[size_t(k)] - selfStart[size_t(q)];
                        const glm::vec3 r1 = p.x - particles[size_t(q)].x;
                        const glm::vec3& nq = selfStartNormal[size_t(q)];
                        const float side0 = glm::dot(r0, nq), side1 = glm::dot(r1, nq);
                        if (layers && side0 != 0.0f && (side0 > 0.0f) != (side1 > 0.0f)) {
                            // p went through q's tangent plane: through the layer if it did so
                            // within T of q (the cloth is there)
                            const float t = side0 / (side0 - side1);
                            const glm::vec3 at = r0 + t * (r1 - r0);
                            if (glm::dot(at, at) < T * T) {
                                // back to the start side, T from q's tangent plane
                                const float sign = side0 > 0.0f ? 1.0f : -1.0f;
                                sum += nq * (sign * (T - sign * side1) * share);
                                ++contacts;
                                continue;
                            }
                        }
                        const float len2 = glm::dot(r1, r1);
                        if (len2 >= T * T || len2 < 1e-24f) continue;
                        const float len = std::sqrt(len2);
                        sum += r1 * ((T - len) / len * share);
                        ++contacts;
                    }
                    delta[size_t(k)] = contacts ? sum / float(contacts) : glm::vec3(0.0f);
                }
            },
            1024);
        bool moved = false;
        for (int k = 0; k < n; ++k) {
            particles[size_t(k)].x += delta[size_t(k)];
            moved = moved || delta[size_t(k)] != glm::vec3(0.0f);
        }
        if (!moved) break; // no contact left: the next passes would do nothing
        // The pushes may have moved particles into a collider's thickness: out again (the
        // colliders have the last word, as in the relaxation).
        if (!colliders.empty())
            pool->parallelFor(
                n, [&](int a, int b) { collide(a, b, false); }, 1024);
    }
}

} // namespace weft
