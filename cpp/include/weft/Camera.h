#pragma once
// Perspective camera. Matrices follow Vulkan's clip space: +Y down in NDC, depth in [0, 1].
#include <glm/glm.hpp>
#include <weft/Error.h>

namespace weft {

struct Camera {
    glm::vec3 position{0.0f, 1.0f, 4.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovY = 0.7853982f; // vertical field of view in radians (45 degrees)
    float zNear = 0.05f;
    float zFar = 100.0f;

    /// Throws InvalidArgument for non-finite values, position == target, up parallel to the
    /// view direction, fovY outside (0, pi) or 0 < zNear < zFar violated.
    void validate() const;
    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;
};

} // namespace weft
