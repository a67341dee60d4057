#pragma once
// The GGX chain's per-level parameters and importance samples, shared by the CPU filter
// (GlossyFilter.cpp) and the compute shader's dispatcher (render/GpuPrefilter.cpp) so both read
// the same directions from the same mip levels.
#include <vector>

#include <glm/glm.hpp>

namespace weft {

/// One importance sample of a GGX level: the half vector in the frame of the output texel's
/// normal (z = n) and the source lod whose texel solid angle matches the sample's.
struct GgxSample {
    glm::vec3 h;
    float lod;
};

/// GGX alpha of chain level m of `levels` (perceptual roughness m / (levels - 1), squared).
float ggxLevelAlpha(int m, int levels);
/// Source lod read by level 0 (the mirror level) for a `sourceSize` source and `size` output.
float ggxMirrorLod(int sourceSize, int size);
/// `samples` Hammersley half vectors of the GGX lobe with `alpha` and their lods;
/// `texelSolidAngle` is the solid angle of a level-0 source texel.
std::vector<GgxSample> ggxSamples(float alpha, int samples, float texelSolidAngle);

} // namespace weft
