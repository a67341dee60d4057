#pragma once
// CPU mirrors of the hair passes' shader structs in glsl/common/hair_frame.glsl (std430/std140).
#include <cstdint>

#include <glm/glm.hpp>

#include "hair/HairShadingGpu.h"

namespace weft::render {

constexpr int kMaxHairDoms = 4; // directional lights with a deep opacity map per frame

struct GpuHairVertex {
    glm::vec4 position; // xyz object space; w: thickness
    glm::vec4 tangent;  // xyz unit tangent (root to tip); w: opacity alpha = 1 - transparency
    glm::vec3 color;    // linear RGB
    uint32_t strand;    // strand index (Sadeghi's per-strand glint)
};

struct GpuHairInstance {
    glm::mat4 model;
    hair::HairShadingGpu shading;
};

struct GpuHairFrame {
    glm::vec4 cameraForward;               // xyz: unit view axis; w: ribbon width per thickness
    glm::ivec4 params;                     // x: ribbons, y: OIT weight (7..10), z: DOMs, w: log
    glm::ivec4 domLight;                   // scene light index of DOM slot i, -1 unused
    glm::mat4 domViewProj[kMaxHairDoms];   // world -> DOM clip (orthographic, depth [0, 1])
    glm::vec4 domLayer[kMaxHairDoms];      // x: layer size d in stored-depth units
    glm::mat4 domMeshViewProj[kMaxHairDoms]; // the same x, y; depth from the casters nearest the
                                             // light to the DOM's far plane (mesh shadows)
};

static_assert(sizeof(GpuHairVertex) == 48, "GpuHairVertex must match hair_frame.glsl");
static_assert(sizeof(GpuHairInstance) == 224, "GpuHairInstance must match hair_frame.glsl");
static_assert(sizeof(GpuHairFrame) == 48 + 144 * kMaxHairDoms, "GpuHairFrame must match");

} // namespace weft::render
