#include <weft/HairShadeEval.h>

#include <cmath>
#include <cstring>
#include <string>

#include <weft/Error.h>

#include "hair/HairShadingGpu.h"
#include "vk/ComputePipeline.h"

namespace weft {

namespace {

struct EvalInput {
    glm::vec4 t, l, v;
    uint32_t strand[4];
};
static_assert(sizeof(EvalInput) == 64, "must match glsl/hair/shade_eval.comp");

constexpr uint32_t kGroupSize = 64;

glm::vec3 unit(const glm::vec3& d, const char* what, size_t i) {
    const float len = glm::length(d);
    if (!std::isfinite(len) || len < 1e-20f)
        throw InvalidArgument(std::string("hair shading: ") + what + "[" + std::to_string(i) +
                              "] must be finite and non-zero");
    return d / len;
}

} // namespace

std::vector<glm::vec3> evaluateHairShading(const HairMaterial& material,
                                           const std::vector<glm::vec3>& t,
                                           const std::vector<glm::vec3>& l,
                                           const std::vector<glm::vec3>& v,
                                           const std::vector<uint32_t>& strandIds) {
    const hair::HairShadingGpu params = hair::packHairShading(material);
    const size_t n = t.size();
    if (l.size() != n || v.size() != n || strandIds.size() != n)
        throw InvalidArgument("hair shading: t, l, v and strand ids must have the same length");
    if (n == 0) return {};
    if (n > (size_t(1) << 26)) throw InvalidArgument("hair shading: at most 2^26 samples per call");
    std::vector<EvalInput> inputs(n);
    for (size_t i = 0; i < n; ++i) {
        inputs[i].t = glm::vec4(unit(t[i], "t", i), 0.0f);
        inputs[i].l = glm::vec4(unit(l[i], "l", i), 0.0f);
        inputs[i].v = glm::vec4(unit(v[i], "v", i), 0.0f);
        inputs[i].strand[0] = strandIds[i];
    }

    auto ctx = vk::Context::shared();
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    vk::Buffer paramBuf(ctx.get(), sizeof params, storage, vk::MemoryUsage::Upload);
    vk::Buffer inBuf(ctx.get(), n * sizeof(EvalInput), storage, vk::MemoryUsage::Upload);
    vk::Buffer outBuf(ctx.get(), n * sizeof(glm::vec4), storage, vk::MemoryUsage::Readback);
    paramBuf.write(&params, sizeof params);
    inBuf.write(inputs.data(), n * sizeof(EvalInput));

    const VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    vk::DescriptorSetLayout setLayout = vk::createComputeSetLayout(*ctx, {{0, type}, {1, type}, {2, type}});
    vk::PipelineLayout layout = vk::createComputePipelineLayout(*ctx, {setLayout.get()}, 4);
    vk::Pipeline pipeline = vk::createComputePipeline(*ctx, "hair/shade_eval.comp", layout);

    VkDescriptorPoolSize poolSize{type, 3};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &poolSize;
    VkDescriptorPool rawPool;
    VK_CHECK(vkCreateDescriptorPool(ctx->device(), &poolInfo, nullptr, &rawPool));
    vk::DescriptorPool pool(ctx.get(), rawPool, vkDestroyDescriptorPool);
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    VkDescriptorSetLayout rawLayout = setLayout.get();
    alloc.pSetLayouts = &rawLayout;
    VkDescriptorSet set;
    VK_CHECK(vkAllocateDescriptorSets(ctx->device(), &alloc, &set));
    VkDescriptorBufferInfo infos[3] = {{paramBuf.get(), 0, VK_WHOLE_SIZE},
                                       {inBuf.get(), 0, VK_WHOLE_SIZE},
                                       {outBuf.get(), 0, VK_WHOLE_SIZE}};
    VkWriteDescriptorSet writes[3];
    for (uint32_t b = 0; b < 3; ++b) {
        writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[b].dstSet = set;
        writes[b].dstBinding = b;
        writes[b].descriptorCount = 1;
        writes[b].descriptorType = type;
        writes[b].pBufferInfo = &infos[b];
    }
    vkUpdateDescriptorSets(ctx->device(), 3, writes, 0, nullptr);

    const uint32_t count = uint32_t(n);
    ctx->immediate([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
        vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 4, &count);
        vkCmdDispatch(cmd, (count + kGroupSize - 1) / kGroupSize, 1, 1);
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0,
                             1, &barrier, 0, nullptr, 0, nullptr);
    });

    std::vector<glm::vec3> out(n);
    const glm::vec4* result = static_cast<const glm::vec4*>(outBuf.mapped());
    for (size_t i = 0; i < n; ++i) out[i] = glm::vec3(result[i]);
    return out;
}

} // namespace weft
