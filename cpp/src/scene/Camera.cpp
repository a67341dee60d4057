#include <weft/Camera.h>

#include <cmath>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "core/ClipSpace.h"
#include "core/Validate.h"

namespace weft {

void Camera::validate() const {
    requireFinite(position, "Camera.position");
    requireFinite(target, "Camera.target");
    requireFinite(up, "Camera.up");
    requireFinite(fovY, "Camera.fov_y");
    const glm::vec3 forward = target - position;
    if (glm::length(forward) < 1e-9f)
        throw InvalidArgument("Camera.position and Camera.target must differ");
    if (glm::length(up) < 1e-9f ||
        glm::length(glm::cross(glm::normalize(forward), glm::normalize(up))) < 1e-6f)
        throw InvalidArgument("Camera.up must not be zero or parallel to the view direction");
    if (!(fovY > 0.0f && fovY < 3.14159f))
        throw InvalidArgument("Camera.fov_y must be in (0, pi) radians");
    if (!(std::isfinite(zNear) && std::isfinite(zFar) && zNear > 0.0f && zFar > zNear)) {
        std::ostringstream msg;
        msg << "Camera needs 0 < near < far (got near=" << zNear << ", far=" << zFar << ")";
        throw InvalidArgument(msg.str());
    }
}

glm::mat4 Camera::view() const { return glm::lookAtRH(position, target, up); }

glm::mat4 Camera::projection(float aspect) const {
    requirePositive(aspect, "aspect ratio");
    return vulkanClipFlip() * glm::perspectiveRH_ZO(fovY, aspect, zNear, zFar);
}

} // namespace weft
