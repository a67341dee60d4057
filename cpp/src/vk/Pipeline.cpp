#include "vk/Pipeline.h"

namespace weft::vk {

Pipeline createGraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& d) {
    ShaderModule vert = createShaderModule(ctx, d.vertexShader);
    ShaderModule frag;
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    s.stage = VK_SHADER_STAGE_VERTEX_BIT;
    s.module = vert;
    s.pName = "main";
    stages.push_back(s);
    std::vector<VkSpecializationMapEntry> constants;
    for (uint32_t i = 0; i < d.fragmentConstants.size(); ++i)
        constants.push_back({i, uint32_t(i * sizeof(uint32_t)), sizeof(uint32_t)});
    const VkSpecializationInfo specialization{uint32_t(constants.size()), constants.data(),
                                              d.fragmentConstants.size() * sizeof(uint32_t),
                                              d.fragmentConstants.data()};
    if (d.fragmentShader) {
        frag = createShaderModule(ctx, d.fragmentShader);
        s.stage = VK_SHADER_STAGE_FRAGMENT_BIT;
        s.module = frag;
        if (!constants.empty()) s.pSpecializationInfo = &specialization;
        stages.push_back(s);
    }

    VkVertexInputBindingDescription binding{0, d.vertexStride, VK_VERTEX_INPUT_RATE_VERTEX};
    std::vector<VkVertexInputAttributeDescription> attributes;
    if (d.vertexLayout != VertexLayout::None)
        attributes.push_back({0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0});
    if (d.vertexLayout == VertexLayout::PositionUv)
        attributes.push_back({2, 0, VK_FORMAT_R32G32_SFLOAT, 24});
    if (d.vertexLayout == VertexLayout::PositionNormalUv) {
        attributes.push_back({1, 0, VK_FORMAT_R32G32B32_SFLOAT, 12});
        attributes.push_back({2, 0, VK_FORMAT_R32G32_SFLOAT, 24});
        if (d.vertexStride >= 48) attributes.push_back({3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 32});
    }
    VkPipelineVertexInputStateCreateInfo vertexInput{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    if (d.vertexLayout != VertexLayout::None) {
        vertexInput.vertexBindingDescriptionCount = 1;
        vertexInput.pVertexBindingDescriptions = &binding;
        vertexInput.vertexAttributeDescriptionCount = uint32_t(attributes.size());
        vertexInput.pVertexAttributeDescriptions = attributes.data();
    }
    VkPipelineInputAssemblyStateCreateInfo assembly{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = d.topology;
    VkPipelineViewportStateCreateInfo viewport{
        VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = d.cullMode;
    // Projections flip Y for Vulkan's clip space, which turns counter-clockwise object winding
    // into counter-clockwise framebuffer winding.
    raster.frontFace = d.frontFace;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = d.samples;
    VkPipelineDepthStencilStateCreateInfo depth{
        VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = d.depthTest;
    depth.depthWriteEnable = d.depthWrite;
    depth.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
    std::vector<VkPipelineColorBlendAttachmentState> blends = d.blends;
    if (blends.empty()) {
        blends.resize(d.colorFormats.size());
        for (auto& b : blends) b.colorWriteMask = 0xF;
    }
    if (blends.size() != d.colorFormats.size())
        throw Error("graphics pipeline: one blend state per colour attachment");
    VkPipelineColorBlendStateCreateInfo blend{
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = uint32_t(blends.size());
    blend.pAttachments = blends.data();
    const VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamicStates;

    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = uint32_t(d.colorFormats.size());
    rendering.pColorAttachmentFormats = d.colorFormats.data();
    rendering.depthAttachmentFormat = d.depthFormat;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount = uint32_t(stages.size());
    info.pStages = stages.data();
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = d.depthFormat != VK_FORMAT_UNDEFINED ? &depth : nullptr;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = d.layout;
    VkPipeline pipeline;
    VK_CHECK(vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    return Pipeline(&ctx, pipeline, vkDestroyPipeline);
}

DescriptorSetLayout createSetLayout(Context& ctx, const std::vector<SetBinding>& bindings,
                                    VkDescriptorSetLayoutCreateFlags flags,
                                    VkShaderStageFlags stages) {
    std::vector<VkDescriptorSetLayoutBinding> b;
    for (const SetBinding& s : bindings) b.push_back({s.binding, s.type, s.count, stages, nullptr});
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.flags = flags;
    info.bindingCount = uint32_t(b.size());
    info.pBindings = b.data();
    VkDescriptorSetLayout layout;
    VK_CHECK(vkCreateDescriptorSetLayout(ctx.device(), &info, nullptr, &layout));
    return DescriptorSetLayout(&ctx, layout, vkDestroyDescriptorSetLayout);
}

PipelineLayout createPipelineLayout(Context& ctx, const std::vector<VkDescriptorSetLayout>& sets,
                                    uint32_t pushConstantBytes, VkShaderStageFlags stages) {
    VkPushConstantRange range{stages, 0, pushConstantBytes};
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
