#pragma once
// The hair passes' GPU structs, defined once for C++ and GLSL in glsl/common/hair_gpu_types.h,
// under the renderer's names.
#include "hair_gpu_types.h"
#include "render/HairShadingGpu.h"

namespace weft::render {

constexpr int kMaxHairDoms = gpu::HAIR_MAX_DOMS; // directional lights with a deep opacity map

using GpuHairVertex = gpu::HairVertex;
using GpuHairInstance = gpu::HairInstance;
using GpuHairFrame = gpu::HairFrame;

static_assert(sizeof(GpuHairVertex) == 48, "HairVertex must keep its std430 size");
static_assert(sizeof(GpuHairInstance) == 224, "HairInstance must keep its std430 size");
static_assert(sizeof(GpuHairFrame) == 48 + 144 * kMaxHairDoms, "HairFrame must keep its size");

} // namespace weft::render
