// Exact irradiance on the GPU: the source texels (direction, solid angle, radiance x solid angle)
// in one storage buffer, compute dispatches over the output texels (one per 32768 source
// texels, glsl/ibl/irradiance_exact.comp), read back into a CubeMap.
#include <weft/IblGpu.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include <weft/Error.h>

#include "ibl/CubeTexels.h"
#include "ibl/IblValidate.h"
#include "vk/StorageCompute.h"

namespace weft {

namespace {

// Output texels per workgroup of irradiance_exact.comp: TILE invocations x OUTPUTS each.
constexpr uint32_t kPerGroup = 64 * 8;
// Source texels per dispatch: 512 tiles of 64. lavapipe ends a shader's loops after 65535
// iterations in all, silently; the shader counts about 65 per tile (the loop over the tile's
// texels; those over the outputs are unrolled), 33k per dispatch.
constexpr int kTexelsPerDispatch = 512 * 64;

constexpr VkDeviceSize kTexelBytes = 8 * sizeof(float);
constexpr VkDeviceSize kWindowBytes = kTexelsPerDispatch * kTexelBytes; // 1 MiB

struct IrradiancePush {
    int32_t outSize, texelCount, accumulate;
};

} // namespace

CubeMap irradianceExactGpu(const CubeMap& radiance, int size, int sourceSize, double* dispatchMs) {
    requireExactIrradianceArguments(radiance, size, sourceSize);
    // The very table the CPU version sums, interleaved as two vec4 per texel: (w, dw), (L dw, 0).
    const CubeMap source = reducedCube(radiance, sourceSize);
    const CubeTexels t = cubeTexels(source);
    const int n = int(t.size());
    const int windows = (n + kTexelsPerDispatch - 1) / kTexelsPerDispatch;
    // Whole windows (the last one zero-padded), each bound in turn at a dynamic offset.
    std::vector<float> texels(size_t(windows) * kTexelsPerDispatch * 8, 0.0f);
    for (size_t k = 0; k < size_t(n); ++k) {
        float* p = texels.data() + k * 8;
        p[0] = t.x[k];
        p[1] = t.y[k];
        p[2] = t.z[k];
        p[3] = t.dw[k];
        p[4] = t.r[k];
        p[5] = t.g[k];
        p[6] = t.b[k];
    }
    CubeMap out(size);

    auto shared = vk::Context::shared();
    vk::Context& ctx = *shared;
    // The output, at most 6 x 1024^2 x 12 bytes = 72 MiB, is bound whole: every device allows
    // 128 MiB. The source is bound 1 MiB at a time, a multiple of any offset alignment.
    const VkDeviceSize srcBytes = texels.size() * sizeof(float);
    const VkDeviceSize dstBytes = out.floatCount() * sizeof(float);
    vk::Buffer src(&ctx, srcBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::Upload);
    vk::Buffer dst(&ctx, dstBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::Readback);
    src.write(texels.data(), srcBytes);
    const vk::StorageCompute compute = vk::createStorageCompute(
        ctx, "ibl/irradiance_exact.comp", {{&src, kWindowBytes}, {&dst}}, sizeof(IrradiancePush));

    // At most 6 * 1024^2 / 512 = 12288 groups: within the 65535 every device allows in x.
    const uint32_t groups = uint32_t((out.floatCount() / 3 + kPerGroup - 1) / kPerGroup);
    const double ms = vk::runStorageCompute(ctx, compute, [&](VkCommandBuffer cmd) {
        for (int w = 0; w < windows; ++w) {
            if (w > 0) {
                vk::computeToComputeBarrier(cmd); // this window adds to dst
                vk::bindStorageCompute(cmd, compute, {uint32_t(w * kWindowBytes)});
            }
            const int begin = w * kTexelsPerDispatch;
            const IrradiancePush push{size, std::min(n - begin, kTexelsPerDispatch), w > 0 ? 1 : 0};
            vkCmdPushConstants(cmd, compute.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push),
                               &push);
            vkCmdDispatch(cmd, groups, 1, 1);
        }
    });
    if (dispatchMs) *dispatchMs = ms;
    std::memcpy(out.data(), dst.mapped(), dstBytes);
    return out;
}

} // namespace weft
