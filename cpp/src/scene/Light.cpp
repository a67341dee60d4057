// Lights: their checks, attenuation and the helpers the renderer uses on any light kind.
#include <weft/Error.h>
#include <weft/Light.h>

#include <cmath>
#include <string>

#include "core/Validate.h"

namespace weft {

void DirectionalLight::validate() const {
    requireFinite(direction, "DirectionalLight.direction");
    if (glm::length(direction) < 1e-12f)
        throw InvalidArgument("DirectionalLight.direction must not be zero");
    requireNonNegative(color, "DirectionalLight.color");
    requireFinite(intensity, "DirectionalLight.intensity");
    if (intensity < 0) throw InvalidArgument("DirectionalLight.intensity must not be negative");
    if (!(angularRadius >= 0.0f && angularRadius <= 0.5f)) // also NaN
        throw InvalidArgument("DirectionalLight.angular_radius must be in [0, 0.5] radians, got " +
                              std::to_string(angularRadius));
}

void Attenuation::validate() const {
    for (float v : {constant, linear, quadratic, radius}) {
        requireFinite(v, "Attenuation");
        if (v < 0.0f) throw InvalidArgument("attenuation terms and radius must not be negative");
    }
    if (radius == 0.0f && constant == 0.0f && linear == 0.0f && quadratic == 0.0f)
        throw InvalidArgument("attenuation needs k_c, k_l or k_q > 0 (or a radius): "
                              "1 / (k_c + k_l d + k_q d^2) is infinite");
}

float Attenuation::operator()(float d) const {
    if (radius > 0.0f) return std::max(0.0f, 1.0f - d * d / (radius * radius));
    return 1.0f / (constant + linear * d + quadratic * d * d);
}

namespace {
void validateEmitter(const glm::vec3& color, float intensity, const char* what) {
    requireNonNegative(color, what);
    requireFinite(intensity, what);
    if (intensity < 0)
        throw InvalidArgument(std::string(what) + ": intensity must not be negative");
}
} // namespace

void PointLight::validate() const {
    requireFinite(position, "PointLight.position");
    validateEmitter(color, intensity, "PointLight");
    attenuation.validate();
    requirePositive(shadowNear, "PointLight.shadow_near");
}

void SpotLight::validate() const {
    requireFinite(position, "SpotLight.position");
    requireFinite(direction, "SpotLight.direction");
    if (glm::length(direction) < 1e-12f)
        throw InvalidArgument("SpotLight.direction must not be zero");
    validateEmitter(color, intensity, "SpotLight");
    attenuation.validate();
    requirePositive(shadowNear, "SpotLight.shadow_near");
    requireFinite(innerAngle, "SpotLight.inner_angle");
    requireFinite(outerAngle, "SpotLight.outer_angle");
    if (!(innerAngle >= 0.0f && innerAngle < outerAngle && outerAngle < 1.5607964f))
        throw InvalidArgument("SpotLight angles must satisfy 0 <= inner_angle < outer_angle < "
                              "pi/2 - 0.01 (got " +
                              std::to_string(innerAngle) + ", " + std::to_string(outerAngle) + ")");
}

void validateLight(const Light& light) {
    std::visit([](const auto& l) { l.validate(); }, light);
}

bool castsShadows(const Light& light) {
    return std::visit([](const auto& l) { return l.castShadows; }, light);
}

void spotBasis(const glm::vec3& axis, glm::vec3& right, glm::vec3& up) {
    const glm::vec3 a = glm::normalize(axis);
    const glm::vec3 ref = std::abs(a.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    right = glm::normalize(glm::cross(a, ref));
    up = glm::cross(right, a);
}

} // namespace weft
