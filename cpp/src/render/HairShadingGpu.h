#pragma once
// The GPU layout of a HairMaterial: struct HairShading of glsl/common/hair_gpu_types.h, the one
// definition the hair shaders read too.
#include <glm/glm.hpp>

#include <weft/HairMaterial.h>

#include "hair_gpu_types.h"

namespace weft::hair {

using HairShadingGpu = render::gpu::HairShading;
static_assert(sizeof(HairShadingGpu) == 160, "HairShading must keep its std140/std430 size");
static_assert(render::gpu::HAIR_MODEL_KAJIYA_KAY == int(HairModel::KajiyaKay) &&
                  render::gpu::HAIR_MODEL_MARSCHNER == int(HairModel::Marschner) &&
                  render::gpu::HAIR_MODEL_SADEGHI == int(HairModel::Sadeghi),
              "the shaders' model numbers are weft::HairModel's");

/// Validates `m` and packs it.
HairShadingGpu packHairShading(const HairMaterial& m);

} // namespace weft::hair
