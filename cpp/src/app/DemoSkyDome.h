#pragma once
// Stop-gap until the renderer draws the environment behind the scene: the demo's sky dome
// (Mesh::uvSphere centred at the origin) shows a radiance function through its ambient map.
// Delete this file (and its two uses in DemoScene.cpp) once the environment background lands.
#include <functional>

#include <glm/glm.hpp>

#include <weft/Material.h>

namespace weft::app {

/// Writes `radiance(direction)` into `dome`'s base texture (8-bit sRGB, `width` x `height`) laid
/// out for Mesh::uvSphere's UVs (u: azimuth from +Z towards +X, v: polar angle from +Y), scaled
/// by the brightest texel, which goes into K_A, under a white ambient map: the dome shows the
/// radiance unlit (its ambient term I_A K_A T), in 8-bit sRGB steps of its brightest point.
void paintSkyDome(Material& dome, const std::function<glm::vec3(const glm::vec3&)>& radiance,
                  int width = 128, int height = 64);

} // namespace weft::app
