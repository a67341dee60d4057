#pragma once
// The analytic sky's sun (weft/Sky.h) as a scene light. It lives with the scene, not the sky, so
// that the IBL maths depends on nothing above core.
#include <weft/Light.h>
#include <weft/Sky.h>

namespace weft {

/// The sun as weft's directional light: direction from the sun, colour x intensity = E / pi (E:
/// sunIrradiance), the convention under which a directional light matches an environment (a
/// material's diffuse n.l L K_D T against K_D T E_env / pi); colour max-normalised, intensity the
/// largest channel (0 below the horizon).
DirectionalLight sunLight(const SkyParams& params);

} // namespace weft
