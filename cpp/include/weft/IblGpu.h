#pragma once
// The GPU versions of two IblFilter.h filters (compute shaders on the shared Vulkan device). They
// are the renderer's layer: the CPU filters of IblFilter.h build and run without Vulkan.
#include <weft/CubeMap.h>

namespace weft {

/// irradianceExact as a Vulkan compute shader on the shared device (a GPU, or lavapipe): the same
/// arguments, checks and sum (the same source table, accumulated in float per 64-texel tile, one
/// dispatch per 32768 source texels), equal to the CPU result up to float rounding. `dispatchMs`
/// (optional) receives the wall time of the submission (building the source table, the upload
/// and pipeline creation excluded). Throws InvalidArgument for bad arguments (as the CPU
/// version), weft::Error when no Vulkan device is usable.
CubeMap irradianceExactGpu(const CubeMap& radiance, int size, int sourceSize = 64,
                           double* dispatchMs = nullptr);
/// prefilterGgx as a Vulkan compute shader on the shared device (a GPU, or lavapipe): the same
/// plan (samples, points, level 0 computed on the CPU), equal to the CPU result up to float
/// rounding. `dispatchMs` (optional) receives the wall time
/// of the recorded dispatches and copy (upload of the source chain and pipeline creation
/// excluded). Throws weft::Error when no Vulkan device is usable, InvalidArgument when the
/// source levels the samples read exceed the device's texel buffer size or `samples` exceeds
/// kMaxGpuGgxSamples (lavapipe silently ends a shader's loops after 65535 iterations).
constexpr int kMaxGpuGgxSamples = 16384;
CubeMap prefilterGgxGpu(const CubeMap& radiance, int size, int levels = 5, int samples = 64,
                        double* dispatchMs = nullptr);

} // namespace weft
