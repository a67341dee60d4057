#pragma once
// How each level of the GGX chain is integrated, computed once and shared by the CPU filter
// (GlossyFilter.cpp) and the compute dispatcher (render/GpuPrefilter.cpp), so both run one
// algorithm.
//
// Filtered importance sampling alone is 20-30% off (100% at worst) next to a small bright sun:
// the mip a tail sample reads spreads the sun with a box, not the GGX lobe. So the integral
// (N = V = R) of level m is split into
//  - rough levels (lobe wide enough that a source mip of at most `24 samples` texel clusters
//    resolves it): an exact sum over every cluster of that mip, each cluster a point at its
//    luminance-weighted mean direction carrying its radiance x solid angle (a single source
//    texel is its centre: the brute-force definition);
//  - narrow levels: filtered importance sampling of the environment clamped to kClampFactor x
//    its mean luminance (a bounded, smooth-enough signal the samples converge on), plus the
//    exact sum over the clusters of what the clamp removed (the sun), taken at the finest mip
//    where they are at most kMaxExcessPoints.
// Exact sums are divided by the analytic normaliser W(alpha) = integral of D(h) (n.l) dl.
#include <vector>

#include <weft/CubeMap.h>

#include "GgxSamples.h"

namespace weft {

/// A cluster of source texels as a point light: unit direction and radiance x solid angle.
struct GgxPoint {
    glm::vec3 dir;
    glm::vec3 power;
};

struct GgxLevelPlan {
    float alpha = 0.0f;
    float invNorm = 0.0f;           // 1 / W(alpha)
    std::vector<GgxSample> samples; // filtered importance samples of `clamped` (may be empty)
    std::vector<GgxPoint> points;   // summed exactly
};

struct GgxPlan {
    CubeMap clamped;                 // the clamped source with its mips: what samples read
    CubeMap mirror;                  // level 0 of the chain (the unclamped source resampled)
    std::vector<GgxLevelPlan> level; // [levels]; level[0] unused
};

/// Luminance clamp of the sampled part, in multiples of the environment's mean luminance.
constexpr float kClampFactor = 8.0f;
/// Most points of the excess (clamped-away) list per level.
constexpr int kMaxExcessPoints = 256;
/// Exact sums use at most this many points per texel per importance sample asked for.
constexpr int kExactPointsPerSample = 24;
/// A level is summed exactly when its cluster mip's face size x alpha reaches this.
constexpr float kExactSizeAlpha = 2.0f;

GgxPlan ggxPlan(const CubeMap& radiance, int size, int levels, int samples);
/// The weight D(h) (n.l) of a point at cosine `nl` to the texel's direction (0 below).
inline float ggxPointWeight(float nl, float alpha2) {
    if (nl <= 0.0f) return 0.0f;
    const float nh2 = 0.5f * (1.0f + nl);
    const float d = nh2 * (alpha2 - 1.0f) + 1.0f;
    return alpha2 / (3.14159265358979f * d * d) * nl;
}

} // namespace weft
