#pragma once
// Light-space projections for shadow maps.
#include <glm/glm.hpp>

#include "core/ClipSpace.h"

namespace weft::render {

struct ShadowFrustum {
    glm::mat4 viewProj{1.0f}; // world -> clip (Vulkan: y down, depth 0..1)
    float texelWorld = 0.0f;  // world size of one shadow-map texel (perspective: per metre of
                              // distance from the light)
    bool perspective = false;
    float zNear = 0.0f, zFar = 1.0f; // perspective depth range (m)
};

/// Orthographic projection along `toLight` that tightly encloses the box [lo, hi].
ShadowFrustum fitDirectionalShadow(const glm::vec3& toLight, const glm::vec3& lo,
                                   const glm::vec3& hi, unsigned size);

/// Perspective projection from `position` along `axis` (with `up`) with vertical field of view
/// `fovY`, square; the far plane encloses the box [lo, hi] as seen from the light.
ShadowFrustum fitPerspectiveShadow(const glm::vec3& position, const glm::vec3& axis,
                                   const glm::vec3& up, float fovY, float zNear,
                                   const glm::vec3& lo, const glm::vec3& hi, unsigned size);

/// The six 90-degree views of a point light, in cube-face order +X, -X, +Y, -Y, +Z, -Z; a
/// direction belongs to the face of its largest absolute component.
void pointShadowFaces(const glm::vec3& position, float zNear, const glm::vec3& lo,
                      const glm::vec3& hi, unsigned size, ShadowFrustum faces[6]);

using weft::vulkanClipFlip; // core/ClipSpace.h

} // namespace weft::render
