#pragma once
// Evaluation of BtfMaterialMaps for one sample direction (shared by error measurement, the
// specular fit and the synthetic renderer).
#include <cstddef>
#include <cstdint>

#include <weft/BtfFit.h>

namespace weft {

/// Writes texels [begin, end) of channel planes out[0..2] for light l and view v. `visible`
/// (per texel, may be null) zeroes the diffuse and specular terms where the light is blocked.
void btfEvaluateSample(const BtfMaterialMaps& maps, glm::vec3 l, glm::vec3 v,
                       const uint8_t* visible, size_t begin, size_t end, float* const out[3]);

/// Normalised half vector of l and v.
glm::vec3 btfHalfVector(glm::vec3 l, glm::vec3 v);

} // namespace weft
