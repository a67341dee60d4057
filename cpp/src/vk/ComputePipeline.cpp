#include "vk/ComputePipeline.h"

namespace weft::vk {

Pipeline createComputePipeline(Context& ctx, const char* embeddedShaderName,
                               VkPipelineLayout layout) {
    ShaderModule module = createShaderModule(ctx, embeddedShaderName);
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

} // namespace weft::vk
