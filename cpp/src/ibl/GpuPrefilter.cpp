// The GGX chain on the GPU: the source mip chain in one storage buffer, one compute dispatch per
// output level (glsl/ibl/prefilter_ggx.comp), read back into a CubeMap.
#include <weft/IblFilter.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <string>

#include <weft/Error.h>

#include "CubeTexels.h"
#include "IblValidate.h"
#include "vk/ComputePipeline.h"

namespace weft {

namespace {

constexpr float kPi = 3.14159265358979f;

struct PrefilterPush {
    int32_t srcSize, srcLevels, outSize, outOffset, samples;
    float alpha, lod0, texelOmega;
};

VkDescriptorSet bindBuffers(vk::Context& ctx, vk::DescriptorPool& pool,
                            VkDescriptorSetLayout layout, const vk::Buffer& src,
                            const vk::Buffer& dst) {
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.maxSets = 1;
    info.poolSizeCount = 1;
    info.pPoolSizes = &size;
    VkDescriptorPool handle;
    VK_CHECK(vkCreateDescriptorPool(ctx.device(), &info, nullptr, &handle));
    pool = vk::DescriptorPool(&ctx, handle, vkDestroyDescriptorPool);
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &layout;
    VkDescriptorSet set;
    VK_CHECK(vkAllocateDescriptorSets(ctx.device(), &alloc, &set));
    VkDescriptorBufferInfo buffers[2] = {{src.get(), 0, VK_WHOLE_SIZE},
                                         {dst.get(), 0, VK_WHOLE_SIZE}};
    VkWriteDescriptorSet writes[2];
    for (uint32_t k = 0; k < 2; ++k) {
        writes[k] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[k].dstSet = set;
        writes[k].dstBinding = k;
        writes[k].descriptorCount = 1;
        writes[k].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[k].pBufferInfo = &buffers[k];
    }
    vkUpdateDescriptorSets(ctx.device(), 2, writes, 0, nullptr);
    return set;
}

} // namespace

CubeMap prefilterGgxGpu(const CubeMap& radiance, int size, int levels, int samples,
                        double* dispatchMs) {
    requireGgxArguments(radiance, size, levels, samples);
    CubeMap out(size);
    out.buildMips(); // allocates every level; the dispatches overwrite those kept
    out.keepLevels(levels);
    const CubeMap chain = withMips(radiance);

    auto shared = vk::Context::shared();
    vk::Context& ctx = *shared;
    size_t srcFloats = 0, dstFloats = 0;
    for (int l = 0; l < chain.levels(); ++l) srcFloats += chain.floatCount(l);
    for (int l = 0; l < out.levels(); ++l) dstFloats += out.floatCount(l);
    vk::Buffer src(&ctx, srcFloats * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                   vk::MemoryUsage::Upload);
    vk::Buffer dst(&ctx, dstFloats * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                   vk::MemoryUsage::Readback);
    size_t offset = 0;
    for (int l = 0; l < chain.levels(); ++l) {
        src.write(chain.data(l), chain.floatCount(l) * sizeof(float), offset * sizeof(float));
        offset += chain.floatCount(l);
    }
    vk::DescriptorSetLayout setLayout = vk::createComputeSetLayout(
        ctx, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}, {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}});
    vk::PipelineLayout layout = vk::createComputePipelineLayout(ctx, {setLayout},
                                                                sizeof(PrefilterPush));
    vk::Pipeline pipeline = vk::createComputePipeline(ctx, "ibl/prefilter_ggx.comp", layout);
    vk::DescriptorPool pool;
    const VkDescriptorSet set = bindBuffers(ctx, pool, setLayout, src, dst);

    const float texelOmega = 4.0f * kPi / (6.0f * float(radiance.size()) * float(radiance.size()));
    const auto start = std::chrono::steady_clock::now();
    ctx.immediate([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0,
                                nullptr);
        int32_t dstOffset = 0;
        for (int m = 0; m < levels; ++m) {
            const int s = out.levelSize(m);
            const float rough = levels > 1 ? float(m) / float(levels - 1) : 0.0f;
            PrefilterPush push{radiance.size(), chain.levels(), s, dstOffset, m == 0 ? 0 : samples,
                               std::max(rough * rough, 1e-3f),
                               std::max(0.0f, std::log2(float(radiance.size()) / float(size))),
                               texelOmega};
            vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            vkCmdDispatch(cmd, uint32_t((6 * s * s + 63) / 64), 1, 1);
            dstOffset += int32_t(out.floatCount(m));
        }
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                             0, 1, &barrier, 0, nullptr, 0, nullptr);
    });
    if (dispatchMs) {
        const auto elapsed = std::chrono::steady_clock::now() - start;
        *dispatchMs = std::chrono::duration<double, std::milli>(elapsed).count();
    }
    offset = 0;
    for (int m = 0; m < levels; ++m) {
        std::memcpy(out.data(m), static_cast<const float*>(dst.mapped()) + offset,
                    out.floatCount(m) * sizeof(float));
        offset += out.floatCount(m);
    }
    return out;
}

} // namespace weft
