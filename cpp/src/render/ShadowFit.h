#pragma once
// Light-space projections for shadow maps.
#include <glm/glm.hpp>

namespace weft::render {

struct ShadowFrustum {
    glm::mat4 viewProj{1.0f}; // world -> clip (Vulkan: y down, depth 0..1)
    float texelWorld = 0.0f;  // world size of one shadow-map texel
};

/// Orthographic projection along `toLight` that tightly encloses the box [lo, hi].
ShadowFrustum fitDirectionalShadow(const glm::vec3& toLight, const glm::vec3& lo,
                                   const glm::vec3& hi, unsigned size);

/// Clip-space Y flip that turns OpenGL-style projections into Vulkan's convention.
glm::mat4 vulkanClipFlip();

} // namespace weft::render
