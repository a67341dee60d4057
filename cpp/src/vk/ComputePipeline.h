#pragma once
// Compute pipelines and compute-stage descriptor/pipeline layouts.
#include <utility>
#include <vector>

#include "vk/Resources.h"

namespace weft::vk {

/// A compute shader's set-0 layout, pipeline layout and pipeline.
struct ComputeProgram {
    DescriptorSetLayout setLayout;
    PipelineLayout layout;
    Pipeline pipeline;
};

/// The program of `shader` with these set-0 (binding, type) pairs and push-constant bytes, made
/// once per context (again after a shader hot reload) and kept until the context goes.
const ComputeProgram&
cachedComputeProgram(Context& ctx, const char* shader,
                     const std::vector<std::pair<uint32_t, VkDescriptorType>>& bindings,
                     uint32_t pushConstantBytes);

/// A compute pipeline from the embedded shader `shader` (path relative to glsl/).
Pipeline createComputePipeline(Context& ctx, const char* shader, VkPipelineLayout layout);

/// Descriptor set layout from (binding, type) pairs, visible to the compute stage.
DescriptorSetLayout
createComputeSetLayout(Context& ctx,
                       const std::vector<std::pair<uint32_t, VkDescriptorType>>& bindings);
/// Pipeline layout whose push constants (if any) are visible to the compute stage.
PipelineLayout createComputePipelineLayout(Context& ctx,
                                           const std::vector<VkDescriptorSetLayout>& sets,
                                           uint32_t pushConstantBytes);

} // namespace weft::vk
