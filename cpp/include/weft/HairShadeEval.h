#pragma once
// A testing and analysis entry point: evaluates glsl/common/hair_shading.glsl in a Vulkan
// compute shader (glsl/hair/shade_eval.comp) for a batch of directions, so that the GLSL the
// renderer uses can be compared with an independent reference.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include <weft/HairMaterial.h>

namespace weft {

/// The scattering value f (RGB; diffuse + specular, per unit light radiance) for tangents t,
/// light directions l and view directions v (all pointing away from the fibre, normalised
/// here; zero or non-finite vectors throw InvalidArgument), and the strand ids that choose
/// Sadeghi's per-strand glint angle. All four arrays have the same length.
std::vector<glm::vec3> evaluateHairShading(const HairMaterial& material,
                                           const std::vector<glm::vec3>& t,
                                           const std::vector<glm::vec3>& l,
                                           const std::vector<glm::vec3>& v,
                                           const std::vector<uint32_t>& strandIds);

} // namespace weft
