#include "vk/StorageCompute.h"

#include <chrono>

#include "vk/ComputePipeline.h"

namespace weft::vk {

namespace {

VkDescriptorType typeOf(const StorageBinding& b) {
    return b.dynamicRange > 0 ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC
                              : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

} // namespace

StorageCompute createStorageCompute(Context& ctx, const char* shader,
                                    const std::vector<StorageBinding>& bindings,
                                    uint32_t pushConstantBytes) {
    const uint32_t n = uint32_t(bindings.size());
    StorageCompute c;
    std::vector<std::pair<uint32_t, VkDescriptorType>> types;
    uint32_t plain = 0;
    for (uint32_t k = 0; k < n; ++k) {
        types.push_back({k, typeOf(bindings[k])});
        (bindings[k].dynamicRange > 0 ? c.dynamicCount : plain) += 1;
    }
    const ComputeProgram& program = cachedComputeProgram(ctx, shader, types, pushConstantBytes);
    c.layout = program.layout;
    c.pipeline = program.pipeline;

    std::vector<VkDescriptorPoolSize> sizes;
    if (plain) sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, plain});
    if (c.dynamicCount)
        sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, c.dynamicCount});
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.maxSets = 1;
    info.poolSizeCount = uint32_t(sizes.size());
    info.pPoolSizes = sizes.data();
    VkDescriptorPool handle;
    VK_CHECK(vkCreateDescriptorPool(ctx.device(), &info, nullptr, &handle));
    c.pool = DescriptorPool(&ctx, handle, vkDestroyDescriptorPool);
    const VkDescriptorSetLayout setLayout = program.setLayout;
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = c.pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &setLayout;
    VK_CHECK(vkAllocateDescriptorSets(ctx.device(), &alloc, &c.set));

    std::vector<VkDescriptorBufferInfo> infos(n);
    std::vector<VkWriteDescriptorSet> writes(n);
    for (uint32_t k = 0; k < n; ++k) {
        const StorageBinding& b = bindings[k];
        infos[k] = {b.buffer->get(), 0, b.dynamicRange > 0 ? b.dynamicRange : VK_WHOLE_SIZE};
        writes[k] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[k].dstSet = c.set;
        writes[k].dstBinding = k;
        writes[k].descriptorCount = 1;
        writes[k].descriptorType = typeOf(b);
        writes[k].pBufferInfo = &infos[k];
    }
    vkUpdateDescriptorSets(ctx.device(), n, writes.data(), 0, nullptr);
    return c;
}

void bindStorageCompute(VkCommandBuffer cmd, const StorageCompute& compute,
                        const std::vector<uint32_t>& dynamicOffsets) {
    std::vector<uint32_t> offsets = dynamicOffsets;
    offsets.resize(compute.dynamicCount, 0);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, compute.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, compute.layout, 0, 1, &compute.set,
                            uint32_t(offsets.size()), offsets.data());
}

double runStorageCompute(Context& ctx, const StorageCompute& compute,
                         const std::function<void(VkCommandBuffer)>& record) {
    const auto start = std::chrono::steady_clock::now();
    ctx.immediate([&](VkCommandBuffer cmd) {
        bindStorageCompute(cmd, compute);
        record(cmd);
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                             0, 1, &barrier, 0, nullptr, 0, nullptr);
    });
    const auto elapsed = std::chrono::steady_clock::now() - start;
    return std::chrono::duration<double, std::milli>(elapsed).count();
}

void computeToComputeBarrier(VkCommandBuffer cmd) {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
}

} // namespace weft::vk
