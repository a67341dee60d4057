#pragma once
// Light sources (SPEC §1.2). The light list is data; shaders loop over it.
#include <glm/glm.hpp>

namespace weft {

/// Parallel light (sun). `direction` points from the light into the scene, so the vector
/// towards the light is l = -normalize(direction). Radiance L = color * intensity, a = 1.
struct DirectionalLight {
    glm::vec3 direction{0.0f, -1.0f, 0.0f};
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    bool castShadows = true;

    /// Throws InvalidArgument for a zero/non-finite direction or negative/non-finite colour.
    void validate() const;
    glm::vec3 toLight() const { return -glm::normalize(direction); }
    glm::vec3 radiance() const { return color * intensity; }
};

} // namespace weft
