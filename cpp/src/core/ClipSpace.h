#pragma once
// Vulkan's clip-space convention, shared by the camera (scene) and the shadow fits (render).
#include <glm/glm.hpp>

namespace weft {

/// Clip-space Y flip that turns OpenGL-style projections into Vulkan's convention (y down).
inline glm::mat4 vulkanClipFlip() {
    glm::mat4 flip(1.0f);
    flip[1][1] = -1.0f;
    return flip;
}

} // namespace weft
