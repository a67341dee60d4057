#pragma once
// The dome of shadow lights (SPEC §4.5, seed eq. 2.21-2.23): N cells around fixed directions
// over the upper hemisphere (+Y), each with an intensity taken from the environment so that the
// lights together reproduce the environment's irradiance from above the horizon.
//
// Layouts: Fibonacci (default; point k at height y = 1 - (k + 0.5) / N, azimuth k x the golden
// angle: equal-area, nearly uniform cells) or Rings (the seed's rings of 8: N / 8 equal-area
// bands, 8 lights per band at the band's middle height, odd rings turned by half a step).
// Intensity of light i (eq. 2.21 with T integrated over the light's cell): T_i = integral of L
// over the environment texels above the horizon that are nearer to light i than to any other
// (its Voronoi cell). Its direction V_i is the cell's luminance-weighted mean direction (the
// layout direction for a black cell), so that a sun's shadow points away from the sun. Then
// H_i = T_i max(0, N.V_i), D = sum of visible H_i (eq. 2.22) or
// D = E(N) - sum of occluded H_i (eq. 2.23), with E the irradiance.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include <weft/CubeMap.h>

namespace weft {

enum class DomeLayout { Fibonacci, Rings };

struct DomeLight {
    glm::vec3 direction{0.0f, 1.0f, 0.0f}; ///< unit, towards the light (y > 0)
    glm::vec3 intensity{0.0f};             ///< T_i: radiance integrated over the cell (RGB)
    float solidAngle = 0.0f;               ///< sr of the cell
    /// Half-angle (radians) of the uniform cone with the cell's luminance-weighted spread about
    /// `direction`: about the cell's radius under a smooth sky, near 0 for a sun. The renderer
    /// sizes each light's soft-shadow filter by it.
    float angularRadius = 0.0f;
};

class ShadowDome {
public:
    /// Throws InvalidArgument unless count is a positive multiple of 8 up to 4096.
    static std::vector<glm::vec3> directions(int count, DomeLayout layout);
    /// Integrates `radiance` (reduced to <= sourceSize per face) over each light's cell.
    ShadowDome(const CubeMap& radiance, int count, DomeLayout layout = DomeLayout::Fibonacci,
               int sourceSize = 128);

    const std::vector<DomeLight>& lights() const { return mLights; }
    int size() const { return int(mLights.size()); }
    /// Eq. 2.22: sum over lights with visible[i] != 0 of T_i max(0, n.V_i).
    glm::vec3 diffuseVisible(const glm::vec3& normal, const std::vector<uint8_t>& visible) const;
    /// Eq. 2.23: irradiance minus the sum over lights with visible[i] == 0.
    glm::vec3 diffuseSubtract(const glm::vec3& normal, const glm::vec3& irradiance,
                              const std::vector<uint8_t>& visible) const;
    /// Round-robin refresh: the `perFrame` lights whose shadow maps update in frame `frame`
    /// (every light once per ceil(N / perFrame) frames).
    std::vector<int> refreshSet(long long frame, int perFrame) const;

private:
    std::vector<DomeLight> mLights;
};

} // namespace weft
