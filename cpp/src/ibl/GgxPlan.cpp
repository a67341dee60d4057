// The GGX chain's per-level plan (see GgxPlan.h).
#include "GgxPlan.h"

#include <algorithm>
#include <cmath>

#include "CubeTexels.h"
#include "IblParallel.h"

namespace weft {

namespace {

constexpr float kPi = 3.14159265358979f;

float luminance(const float* c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

// W(alpha) = integral of D(h) (n.l) dl over n.l > 0 with l = reflect(n, h), dl = 4 (n.h) dh:
// 4 E[max(2 (n.h)^2 - 1, 0)] over h drawn with pdf D (n.h), written in the sampler's uniform
// variable u ((n.h)^2 = (1 - u) / (1 + (alpha^2 - 1) u)): a smooth 1D integral, midpoint rule.
float ggxNormaliser(float alpha) {
    const double a2 = double(alpha) * alpha;
    const int n = 1 << 14;
    double sum = 0.0;
    for (int k = 0; k < n; ++k) {
        const double u = (k + 0.5) / n;
        const double c2 = (1.0 - u) / (1.0 + (a2 - 1.0) * u);
        sum += std::max(2.0 * c2 - 1.0, 0.0);
    }
    return float(4.0 * sum / n);
}

// Texel clusters of every mip level of a cube: radiance x solid angle and the luminance-weighted
// sum of directions (whose direction is the cluster's mean direction), merged 2x2 as
// CubeMap::buildMips merges texels (also for sizes that are not powers of two).
struct Cluster {
    glm::dvec3 power{0.0};
    glm::dvec3 moment{0.0};
};

// Merges level-0 clusters (6 x s0 x s0) up to the level of size `lastLevelSize`.
std::vector<std::vector<Cluster>> clusterPyramid(std::vector<Cluster> base, int s0,
                                                 int lastLevelSize) {
    std::vector<std::vector<Cluster>> out;
    out.push_back(std::move(base));
    for (int fine = s0; fine > std::max(1, lastLevelSize); fine = std::max(1, fine >> 1)) {
        const int s = std::max(1, fine >> 1);
        std::vector<Cluster> level(size_t(6) * s * s);
        const std::vector<Cluster>& prev = out.back();
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < s; ++j)
                for (int i = 0; i < s; ++i) {
                    Cluster& k = level[(size_t(f) * s + j) * s + i];
                    for (int fj = j * fine / s; fj < (j + 1) * fine / s; ++fj)
                        for (int fi = i * fine / s; fi < (i + 1) * fine / s; ++fi) {
                            const Cluster& c = prev[(size_t(f) * fine + fj) * fine + fi];
                            k.power += c.power;
                            k.moment += c.moment;
                        }
                }
        out.push_back(std::move(level));
    }
    return out;
}

// The non-black clusters of one level as points (a black-luminance cluster with colour, which
// only a negative-weighted mix could make, sits at its texel centre).
std::vector<GgxPoint> points(const std::vector<Cluster>& level, int size) {
    std::vector<GgxPoint> out;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                const Cluster& c = level[(size_t(f) * size + j) * size + i];
                if (c.power.x <= 0.0 && c.power.y <= 0.0 && c.power.z <= 0.0) continue;
                const double len = glm::length(c.moment);
                const glm::vec3 dir =
                    len > 0.0 ? glm::vec3(c.moment / len) : cubeTexelDirection(f, i, j, size);
                out.push_back({dir, glm::vec3(c.power)});
            }
    return out;
}

int levelSizeOf(int s0, int level) { return std::max(1, s0 >> level); }

CubeMap mirrorLevel(const CubeMap& radiance, const CubeMap& chain, int size) {
    CubeMap out(size);
    const float lod0 = ggxMirrorLod(radiance.size(), size);
    const int copy = int(lod0);
    if (float(copy) == lod0 && chain.levelSize(copy) == size) { // a source level: exact copy
        std::copy(chain.data(copy), chain.data(copy) + chain.floatCount(copy), out.data());
        return out;
    }
    iblParallelFor(6 * size, [&](int begin, int end) {
        for (int row = begin; row < end; ++row) {
            const int f = row / size, j = row % size;
            for (int i = 0; i < size; ++i) {
                const glm::vec3 c = chain.sampleLod(cubeTexelDirection(f, i, j, size), lod0);
                float* p = out.texel(f, i, j);
                p[0] = c.x;
                p[1] = c.y;
                p[2] = c.z;
            }
        }
    });
    return out;
}

} // namespace

GgxPlan ggxPlan(const CubeMap& radiance, int size, int levels, int samples) {
    GgxPlan plan;
    const int s0 = radiance.size();
    const float lod0 = ggxMirrorLod(s0, size);
    if (lod0 == 0.0f && s0 == size) { // level 0 is the source itself: no chain needed
        plan.mirror = CubeMap(size);
        std::copy(radiance.data(), radiance.data() + radiance.floatCount(), plan.mirror.data());
    } else {
        plan.mirror = mirrorLevel(radiance, withMips(radiance), size);
    }
    plan.level.resize(size_t(levels));
    if (levels < 2) return plan;

    // One pass over the source: solid angles (the same on every face), directions, luminance.
    const size_t texels = size_t(6) * s0 * s0;
    std::vector<double> solidAngle(size_t(s0) * s0);
    for (int j = 0; j < s0; ++j)
        for (int i = 0; i < s0; ++i) solidAngle[size_t(j) * s0 + i] = cubeTexelSolidAngle(i, j, s0);
    std::vector<float> lum(texels);
    double lumSum = 0.0;
    for (size_t t = 0; t < texels; ++t) {
        lum[t] = luminance(radiance.data() + t * 3);
        lumSum += lum[t] * solidAngle[t % (size_t(s0) * s0)];
    }
    // The clamp: kClampFactor x the solid-angle weighted mean luminance.
    const float clampLum = kClampFactor * float(lumSum / (4.0 * double(kPi)));
    CubeMap clamped(s0);
    std::vector<Cluster> full(texels), extra(texels);
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < s0; ++j)
            for (int i = 0; i < s0; ++i) {
                const size_t t = (size_t(f) * s0 + j) * s0 + i;
                const float* c = radiance.data() + t * 3;
                const float keep = lum[t] > clampLum ? clampLum / lum[t] : 1.0f;
                const double w = solidAngle[size_t(j) * s0 + i];
                const glm::dvec3 d(cubeTexelDirection(f, i, j, s0));
                glm::dvec3 removed(0.0);
                for (int k = 0; k < 3; ++k) {
                    clamped.data()[t * 3 + k] = c[k] * keep;
                    removed[k] = double(c[k]) - double(c[k] * keep);
                }
                full[t] = {glm::dvec3(c[0], c[1], c[2]) * (double(keep) * w),
                           d * (double(lum[t] * keep) * w)};
                if (keep < 1.0f) extra[t] = {removed * w, d * (double(lum[t] - clampLum) * w)};
            }
    clamped.buildMips();
    plan.clamped = std::move(clamped);

    const int budget = std::min(kExactPointsPerSample * samples, 16384);
    int exactLevel = 0; // the finest source mip whose clusters fit the budget
    while (6 * levelSizeOf(s0, exactLevel) * levelSizeOf(s0, exactLevel) > budget) ++exactLevel;
    const int exactSize = levelSizeOf(s0, exactLevel);
    const auto excess = clusterPyramid(std::move(extra), s0, 1);
    int excessLevel = 0;
    auto excessPoints = points(excess[0], s0);
    while (int(excessPoints.size()) > kMaxExcessPoints && excessLevel + 1 < int(excess.size())) {
        ++excessLevel;
        excessPoints = points(excess[size_t(excessLevel)], levelSizeOf(s0, excessLevel));
    }
    // Exact levels: the clamped source's clusters plus the excess, which stays finer (a sun
    // merged into one coarse cluster would switch off at once where it crosses n.l = 0).
    std::vector<GgxPoint> exactPoints =
        points(clusterPyramid(std::move(full), s0, exactSize).back(), exactSize);
    exactPoints.insert(exactPoints.end(), excessPoints.begin(), excessPoints.end());

    const float texelOmega = 4.0f * kPi / (6.0f * float(s0) * float(s0));
    for (int m = 1; m < levels; ++m) {
        GgxLevelPlan& p = plan.level[size_t(m)];
        p.alpha = ggxLevelAlpha(m, levels);
        p.invNorm = 1.0f / ggxNormaliser(p.alpha);
        // The cluster mip resolves the lobe when its texels (~ pi / (2 size) wide) are at most
        // half the lobe's width alpha: exact; else sampling plus the excess.
        if (exactLevel == 0 || float(exactSize) * p.alpha >= kExactSizeAlpha) {
            p.points = exactPoints;
        } else {
            p.samples = ggxSamples(p.alpha, samples, texelOmega);
            p.points = excessPoints;
        }
    }
    return plan;
}

} // namespace weft
