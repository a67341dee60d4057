#pragma once
// Graphics pipelines for dynamic rendering, described by a small struct.
#include <vector>

#include "vk/Resources.h"

namespace weft::vk {

enum class VertexLayout {
    None,             // no vertex buffer (full-screen triangle)
    Position,         // vec3 position, stride of the full vertex
    PositionUv,       // vec3 position (location 0), vec2 uv at offset 24 (location 2)
    PositionNormalUv, // + tangent (vec4 at offset 32) when the stride is at least 48
};

struct GraphicsPipelineDesc {
    const char* vertexShader = nullptr;   // embedded shader names
    const char* fragmentShader = nullptr; // null: depth-only
    VertexLayout vertexLayout = VertexLayout::PositionNormalUv;
    uint32_t vertexStride = 32;
    std::vector<VkFormat> colorFormats;
    /// Per colour attachment; empty: blending off, all channels written.
    std::vector<VkPipelineColorBlendAttachmentState> blends;
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    VkCullModeFlags cullMode = VK_CULL_MODE_BACK_BIT;
    VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    bool depthTest = true;
    bool depthWrite = true;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT; // of the attachments drawn into
    VkPipelineLayout layout = VK_NULL_HANDLE;
    /// Specialization constants of the fragment shader: constant_id i takes [i] (32-bit).
    std::vector<uint32_t> fragmentConstants;
};

Pipeline createGraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc);

struct SetBinding {
    uint32_t binding;
    VkDescriptorType type;
    uint32_t count = 1; // array size
};

constexpr VkShaderStageFlags kGraphicsStages =
    VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

/// Descriptor set layout from {binding, type[, count]}, visible to `stages`.
DescriptorSetLayout createSetLayout(Context& ctx, const std::vector<SetBinding>& bindings,
                                    VkDescriptorSetLayoutCreateFlags flags = 0,
                                    VkShaderStageFlags stages = kGraphicsStages);
/// Pipeline layout whose push constants (if any) are visible to `stages`.
PipelineLayout createPipelineLayout(Context& ctx, const std::vector<VkDescriptorSetLayout>& sets,
                                    uint32_t pushConstantBytes,
                                    VkShaderStageFlags stages = kGraphicsStages);

} // namespace weft::vk
