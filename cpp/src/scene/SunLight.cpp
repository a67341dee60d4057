#include <weft/SunLight.h>

#include <algorithm>

#include <glm/gtc/constants.hpp>

namespace weft {

DirectionalLight sunLight(const SkyParams& params) {
    const glm::vec3 colour = sunIrradiance(params) / glm::pi<float>();
    const float peak = std::max(colour.x, std::max(colour.y, colour.z));
    DirectionalLight light;
    light.direction = -glm::normalize(params.sunDirection);
    light.color = peak > 0.0f ? colour / peak : glm::vec3(1.0f);
    light.intensity = peak;
    light.castShadows = peak > 0.0f;
    light.angularRadius = float(kSunAngularRadius); // its shadow's penumbra
    return light;
}

} // namespace weft
