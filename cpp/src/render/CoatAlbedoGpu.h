#pragma once
// The GGX coat's directional albedo (weft/IblFilter.h coatAlbedo) as the image the shaders sample
// (frame.glsl coatAlbedo, binding 18): R32F, COAT_COSINES x COAT_ROUGHNESS, COAT_F0 layers.
#include "vk/Resources.h"

namespace weft::render {

/// The table, computed once per process (~3 M samples), uploaded and ready to be sampled.
vk::Image uploadCoatAlbedo(vk::Context& ctx);

} // namespace weft::render
