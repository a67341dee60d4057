#include "vk/ComputePipeline.h"

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

DescriptorSetLayout createComputeSetLayout(
    Context& ctx, const std::vector<std::pair<uint32_t, VkDescriptorType>>& bindings) {
    std::vector<VkDescriptorSetLayoutBinding> b;
    for (auto [binding, type] : bindings)
        b.push_back({binding, type, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = uint32_t(b.size());
    info.pBindings = b.data();
    VkDescriptorSetLayout layout;
    VK_CHECK(vkCreateDescriptorSetLayout(ctx.device(), &info, nullptr, &layout));
    return DescriptorSetLayout(&ctx, layout, vkDestroyDescriptorSetLayout);
}

PipelineLayout createComputePipelineLayout(Context& ctx, const std::vector<VkDescriptorSetLayout>& sets,
                                           uint32_t pushConstantBytes) {
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = uint32_t(sets.size());
    info.pSetLayouts = sets.data();
    info.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
    info.pPushConstantRanges = &range;
    VkPipelineLayout layout;
    VK_CHECK(vkCreatePipelineLayout(ctx.device(), &info, nullptr, &layout));
    return PipelineLayout(&ctx, layout, vkDestroyPipelineLayout);
}

} // namespace weft::vk
