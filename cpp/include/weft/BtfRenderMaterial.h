#pragma once
// A fitted BTF material as the renderer's material (SPEC §3.5): albedo -> base texture T,
// normals -> tangent-space normal map (x right, y up in the image, as the fit's frame),
// ambient -> ambient map (I_A per texel), specular -> specular map with K_S = 1, exponent ->
// shininess, n_s = (0, 0, 1) -> the highlight from the vertex normal. K_A = K_D = 1.
#include <weft/BtfFit.h>
#include <weft/Material.h>

namespace weft {

/// Maps become linear 8-bit textures (values clamped to [0, 1], mipmapped); the renderer clamps
/// n.l at 0 whatever clampDiffuse says and draws the scalar exponent (not exponentMap).
Material btfRenderMaterial(const BtfMaterialMaps& maps);

} // namespace weft
