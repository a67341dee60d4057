#pragma once
// The GPU layout of a HairMaterial: struct HairShading in glsl/common/hair_shading.glsl.
#include <cstdint>

#include <glm/glm.hpp>

#include <weft/HairMaterial.h>

namespace weft::hair {

struct HairShadingGpu {
    int32_t model[4];
    glm::vec4 diffuse;
    glm::vec4 specular;
    glm::vec4 colorR;
    glm::vec4 colorTT;
    glm::vec4 colorTRT;
    glm::vec4 shift;
    glm::vec4 width;
    glm::vec4 glint;
    glm::vec4 absorption;
};
static_assert(sizeof(HairShadingGpu) == 160, "must match glsl struct HairShading");

/// Validates `m` and packs it.
HairShadingGpu packHairShading(const HairMaterial& m);

} // namespace weft::hair
