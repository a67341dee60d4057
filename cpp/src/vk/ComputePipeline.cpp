#include "vk/ComputePipeline.h"

#include <string>

#include <weft/ShaderReload.h>

#include "vk/Pipeline.h"

namespace weft::vk {

Pipeline createComputePipeline(Context& ctx, const char* shader, VkPipelineLayout layout) {
    ShaderModule module = createShaderModule(ctx, shader);
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.layout = layout;
    VkPipeline pipeline;
    VK_CHECK(vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    return Pipeline(&ctx, pipeline, vkDestroyPipeline);
}

DescriptorSetLayout
createComputeSetLayout(Context& ctx,
                       const std::vector<std::pair<uint32_t, VkDescriptorType>>& bindings) {
    std::vector<SetBinding> b;
    for (auto [binding, type] : bindings) b.push_back({binding, type});
    return createSetLayout(ctx, b, 0, VK_SHADER_STAGE_COMPUTE_BIT);
}

const ComputeProgram&
cachedComputeProgram(Context& ctx, const char* shader,
                     const std::vector<std::pair<uint32_t, VkDescriptorType>>& bindings,
                     uint32_t pushConstantBytes) {
    std::string key = std::string("compute:") + shader + ":" + std::to_string(pushConstantBytes) +
                      ":" + std::to_string(shaderGeneration());
    for (auto [binding, type] : bindings)
        key += ":" + std::to_string(binding) + "=" + std::to_string(int(type));
    const std::shared_ptr<void> program = ctx.cached(key, [&] {
        auto p = std::make_shared<ComputeProgram>();
        p->setLayout = createComputeSetLayout(ctx, bindings);
        p->layout = createComputePipelineLayout(ctx, {p->setLayout}, pushConstantBytes);
        p->pipeline = createComputePipeline(ctx, shader, p->layout);
        return std::shared_ptr<void>(p);
    });
    return *static_cast<const ComputeProgram*>(program.get());
}

PipelineLayout createComputePipelineLayout(Context& ctx,
                                           const std::vector<VkDescriptorSetLayout>& sets,
                                           uint32_t pushConstantBytes) {
    return createPipelineLayout(ctx, sets, pushConstantBytes, VK_SHADER_STAGE_COMPUTE_BIT);
}

} // namespace weft::vk
