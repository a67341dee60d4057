#pragma once
// The GPU structs of the scene passes, defined once for C++ and GLSL in glsl/common/gpu_types.h
// (namespace gpu), under the renderer's names; plus push-constant blocks of single passes.
#include <glm/glm.hpp>

#include "gpu_types.h"

namespace weft::render {

constexpr int kMaxShadowLayers = gpu::MAX_SHADOW_LAYERS;
constexpr int kMaxCookies = gpu::MAX_COOKIES;

enum GpuLightType : int {
    kLightDirectional = gpu::LIGHT_DIRECTIONAL,
    kLightPoint = gpu::LIGHT_POINT,
    kLightSpot = gpu::LIGHT_SPOT,
};

using GpuLight = gpu::Light;
using GpuShadowLayer = gpu::ShadowLayer;
using GpuDomeLight = gpu::DomeLight;
using GpuInstance = gpu::Instance;
using GpuFrame = gpu::Frame;

/// Push constants of the dome-shadow blur (glsl/render/dome_blur.frag).
struct DomeBlurPush {
    glm::vec4 params; // x: radius in pixels, y: camera near, z: camera far, w: depth tolerance
    glm::vec4 flags;  // x: interleaved dome lights, y: the multi-bounce fit (ambient dome)
};

/// Push constants of the bounce projection (glsl/render/bounce_sh.frag), one draw per probe.
struct BounceShPush {
    glm::vec4 params; // x: environment intensity (0: none), y: texels per face, z: probe
    glm::vec4 centre; // xyz: the probe's position (its caster's bounds' centre)
    glm::vec4 half;   // xyz: its caster's bounds' half extents
};

/// Push constants of the output pass (glsl/render/output.frag).
struct OutputPush {
    glm::vec4 params; // x: exposure scale 2^EV, y: tone map (weft::ToneMap), zw: unused
};

static_assert(sizeof(GpuLight) == 80, "GpuLight must keep its std140/std430 size");
static_assert(sizeof(GpuShadowLayer) == 80, "GpuShadowLayer must keep its std140/std430 size");
static_assert(sizeof(GpuDomeLight) == 96, "GpuDomeLight must keep its std430 size");
static_assert(sizeof(GpuInstance) == 240, "GpuInstance must keep its std140/std430 size");
static_assert(sizeof(GpuFrame) ==
                  64 + 48 + 32 + 16 + 144 + 64 + 32 + 64 + 16 +
                      16 * (2 * gpu::MAX_BOUNCE_CASTERS + gpu::MAX_BOUNCE_CASTERS / 4) + 32,
              "GpuFrame must keep its std140/std430 size");

} // namespace weft::render
