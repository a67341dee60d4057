// Exact irradiance on the GPU: the source texels (direction, solid angle, radiance x solid angle)
// in one storage buffer, compute dispatches over the output texels (one per 32768 source
// texels, glsl/ibl/irradiance_exact.comp), read back into a CubeMap.
#include <weft/IblFilter.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include <weft/Error.h>

#include "CubeTexels.h"
#include "IblValidate.h"
#include "vk/StorageCompute.h"

namespace weft {

namespace {

// Output texels per workgroup of irradiance_exact.comp: TILE invocations x OUTPUTS each.
constexpr uint32_t kPerGroup = 64 * 8;
// Source texels per dispatch: 512 tiles of 64. lavapipe ends a shader's loops after 65535
// iterations in all, silently; the shader counts about 65 per tile (the loop over the tile's
// texels; those over the outputs are unrolled), 33k per dispatch.
constexpr int kTexelsPerDispatch = 512 * 64;

struct IrradiancePush {
    int32_t outSize, texelBegin, texelEnd, accumulate;
};

} // namespace

CubeMap irradianceExactGpu(const CubeMap& radiance, int size, int sourceSize,
                           double* dispatchMs) {
    requireExactIrradianceArguments(radiance, size, sourceSize);
    // The very table the CPU version sums, interleaved as two vec4 per texel: (w, dw), (L dw, 0).
    const CubeMap source = reducedCube(radiance, sourceSize);
    const CubeTexels t = cubeTexels(source);
    const size_t n = t.size();
    std::vector<float> texels(n * 8, 0.0f);
    for (size_t k = 0; k < n; ++k) {
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
    const VkDeviceSize srcBytes = texels.size() * sizeof(float);
    const VkDeviceSize dstBytes = out.floatCount() * sizeof(float);
    const uint32_t range = ctx.properties().limits.maxStorageBufferRange;
    if (srcBytes > range || dstBytes > range)
        throw InvalidArgument("exact irradiance on the GPU: " + std::to_string(size) +
                              "^2 output from a " + std::to_string(source.size()) +
                              "^2 source exceeds this device's storage buffer range (" +
                              std::to_string(range) + " bytes); reduce the sizes");
    vk::Buffer src(&ctx, srcBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::Upload);
    vk::Buffer dst(&ctx, dstBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::Readback);
    src.write(texels.data(), srcBytes);
    const vk::StorageCompute compute = vk::createStorageCompute(
        ctx, "ibl/irradiance_exact.comp", {&src, &dst}, sizeof(IrradiancePush));

    // At most 6 * 1024^2 / 512 = 12288 groups: within the 65535 every device allows in x.
    const uint32_t groups = uint32_t((out.floatCount() / 3 + kPerGroup - 1) / kPerGroup);
    const double ms = vk::runStorageCompute(ctx, compute, [&](VkCommandBuffer cmd) {
        for (int begin = 0; begin < int(n); begin += kTexelsPerDispatch) {
            if (begin > 0) vk::computeToComputeBarrier(cmd); // the next part adds to dst
            const IrradiancePush push{size, begin, std::min(int(n), begin + kTexelsPerDispatch),
                                      begin > 0 ? 1 : 0};
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
