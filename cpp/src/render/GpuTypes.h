#pragma once
// CPU mirrors of the shader-side structs in glsl/common/frame.glsl (std140 / std430).
#include <glm/glm.hpp>

namespace weft::render {

constexpr int kMaxShadowLights = 4;

struct GpuLight {
    glm::vec4 toLight;
    glm::vec4 radiance; // w: shadow layer or -1
};

struct GpuInstance {
    glm::mat4 model;
    glm::mat4 normalMatrix;
    glm::vec4 ka;
    glm::vec4 kd;
    glm::vec4 ks; // w: shininess
    glm::vec4 baseColor;
};

struct GpuFrame {
    glm::mat4 viewProj;
    glm::vec4 cameraPos;
    glm::vec4 ambient;
    glm::vec4 background;
    glm::mat4 lightViewProj[kMaxShadowLights];
    glm::vec4 normalOffset[kMaxShadowLights];
    glm::vec4 bias;
    glm::ivec4 counts;
};

static_assert(sizeof(GpuInstance) == 192, "GpuInstance must match frame.glsl");
static_assert(sizeof(GpuFrame) == 64 + 48 + 4 * 64 + 4 * 16 + 32, "GpuFrame must match frame.glsl");

} // namespace weft::render
