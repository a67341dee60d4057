#pragma once
// Light sources (SPEC §1.2). The light list is data; shaders loop over it.
#include <variant>

#include <glm/glm.hpp>

#include <weft/Texture.h>

namespace weft {

/// Parallel light (sun). `direction` points from the light into the scene, so the vector
/// towards the light is l = -normalize(direction). Radiance L = color * intensity, a = 1.
struct DirectionalLight {
    glm::vec3 direction{0.0f, -1.0f, 0.0f};
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    bool castShadows = true;
    /// Angular radius (radians) of the disc the light comes from: the sun's is 0.0047. Above 0
    /// its shadow has the penumbra that disc casts (PCSS sized by it); 0 keeps the fixed PCF
    /// kernel of RenderSettings::pcfRadius. At most 0.5.
    float angularRadius = 0.0f;

    /// Throws InvalidArgument for a zero/non-finite direction, negative/non-finite colour or an
    /// angular radius outside [0, 0.5].
    void validate() const;
    glm::vec3 toLight() const { return -glm::normalize(direction); }
    glm::vec3 radiance() const { return color * intensity; }
};

/// Distance attenuation a(d) of point and spot lights (SPEC §1.2). With radius > 0 the radius
/// form a = max(0, 1 - d^2 / r^2) (eq. 2.4) is used, else a = 1 / (k_c + k_l d + k_q d^2)
/// (eq. 2.3).
struct Attenuation {
    float constant = 1.0f;
    float linear = 0.0f;
    float quadratic = 0.0f;
    float radius = 0.0f;

    /// Throws InvalidArgument for negative or non-finite values, or k_c = k_l = k_q = 0
    /// without a radius (infinite at the light).
    void validate() const;
    float operator()(float d) const;
};

/// Light radiating from a point in every direction.
struct PointLight {
    glm::vec3 position{0.0f, 2.0f, 0.0f};
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    Attenuation attenuation;
    bool castShadows = true;
    float shadowNear = 0.05f; // near plane of the six shadow views (m)

    void validate() const;
    glm::vec3 radiance() const { return color * intensity; }
};

/// Light from a point into a cone around `direction`: full intensity within `innerAngle` of the
/// axis, a smooth falloff (smoothstep in the cosine) to zero at `outerAngle` (half-angles in
/// radians), distance attenuation, and an optional projected texture ("cookie") over the cone.
struct SpotLight {
    glm::vec3 position{0.0f, 2.0f, 0.0f};
    glm::vec3 direction{0.0f, -1.0f, 0.0f};
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float innerAngle = 0.35f;
    float outerAngle = 0.5f;
    Attenuation attenuation;
    TexturePtr cookie; // RGB modulates the radiance; (0.5, 0.5) of the texture is the axis
    bool castShadows = true;
    float shadowNear = 0.05f;

    /// Throws InvalidArgument unless 0 <= inner < outer < pi/2 (angles) and values are finite.
    void validate() const;
    glm::vec3 radiance() const { return color * intensity; }
};

using Light = std::variant<DirectionalLight, PointLight, SpotLight>;

/// Throws InvalidArgument when the light's parameters are impossible.
void validateLight(const Light& light);
bool castsShadows(const Light& light);

/// The spot's cookie frame: `right` and `up` span the texture (u along right, v along -up).
void spotBasis(const glm::vec3& axis, glm::vec3& right, glm::vec3& up);

} // namespace weft
