#pragma once
// Light extraction from an environment (SPEC §4.5): bright regions found by thresholding a
// max-filtered downsample of the luminance, grouped into connected components on the sphere
// (4-neighbours, across cube face edges). Median cut (Debevec 2005) is in weft.ibl (Python).
#include <vector>

#include <glm/glm.hpp>

#include <weft/CubeMap.h>

namespace weft {

/// A light found in an environment.
struct EnvLight {
    glm::vec3 direction{0.0f, 1.0f, 0.0f}; ///< unit, luminance-weighted centroid (world)
    glm::vec3 colour{0.0f};                ///< integrated radiance x solid angle (RGB)
    float solidAngle = 0.0f;               ///< sr of a uniform disc as bright as the peak
                                           ///< with the same power (sum L dw / peak L)
    int texels = 0;                        ///< full-resolution texels in the light
};

struct LightExtractionParams {
    int downsample = 32;            ///< face size of the max-filtered luminance grid
    float threshold = 0.0f;         ///< absolute luminance threshold; <= 0: automatic
    float relativeThreshold = 8.0f; ///< automatic threshold = this x mean luminance
    int maxLights = 16;             ///< strongest lights kept
};

/// Rec. 709 luminance.
inline float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

/// Lights sorted by luminous power (strongest first). Within each component the light is made
/// of the full-resolution texels above the threshold. When `labels` is given it receives, per
/// level-0 texel (face-major, row-major), the index of the light it belongs to or -1: fill those
/// texels (fillUnseen with labels < 0 as the mask) for the environment without its lights.
std::vector<EnvLight> extractLights(const CubeMap& radiance, const LightExtractionParams& params,
                                    std::vector<int>* labels = nullptr);

} // namespace weft
