#pragma once
// A fitted BTF material as the renderer's material (SPEC §3.5), and the model exactly as the
// renderer draws it.
//
// P = ρ ⊙ (a + max(n·l, 0)) + k max(n_s·h, 0)^e, the specular term only where n·l > 0
// (shading.glsl's shade(); BtfMaterialMaps::clampDiffuse = true). Every map becomes a linear
// RGBA8 texture (mipmapped) holding value / scale, rounded to 1/255 and clamped to [0, 1], with
// one scale per channel = the map's maximum (0 when the map is <= 0 everywhere), so nothing
// above 1 is clipped:
// - albedo ρ -> base texture T, K_D = scale (baseColor = 1);
// - ρ ⊙ a (the constant term) -> ambient map with Material::ambientMapIsRadiance, K_A = scale:
//   one quantised product, not two (ρ tiny with a large stays exact to 1/510 of the maximum);
// - specular k -> specular map RGB, K_S = scale (none: K_S = 0), except that per channel the
//   scale is at most 4x the 99th percentile of the non-zero k (100 or more of them): rare
//   needle lobes above that are clipped rather than rounding every other texel's k to 0;
// - exponent -> shininess; an exponent map -> the specular map's alpha, log-encoded between
//   its minimum and maximum over texels whose specular texel is not 0 (Material::shininessMax);
//   exponents below 1e-3 are drawn as 1e-3;
// - normal n -> tangent-space normal map ((x / s, y / s, z) + 1) / 2 with normalScale s = the
//   largest |x|, |y| (at least 1e-3), x right, y up in the image as the fit's frame; the shader
//   decodes m = (2 texel - 1) * (s, s, 1) and renormalises;
// - n_s = (0, 0, 1) -> the highlight from the vertex normal (specularVertexNormal).
// Negative values (unconstrained fits) are drawn as 0.
#include <weft/BtfFit.h>
#include <weft/Material.h>

namespace weft {

/// The renderer's material for `maps` (see above). Throws InvalidArgument for invalid maps.
Material btfRenderMaterial(const BtfMaterialMaps& maps);

/// The maps as btfRenderMaterial's textures hold them and the shader decodes them at a texel
/// centre: every value quantised as above, normals decoded and renormalised, albedo ρ' = K_D T,
/// ambient a' = K_A A / ρ' (where ρ' is 0 but the drawn constant term K_A A is not, ρ' = 1e-30
/// so that ρ' a' is that term and ρ' n·l is below float resolution), clampDiffuse = true, the
/// exponent (map) as drawn. Its evaluation (btfSampleErrors) is what the renderer draws, up to
/// texture filtering and float rounding.
BtfMaterialMaps btfDrawnMaps(const BtfMaterialMaps& maps);

} // namespace weft
