#pragma once
// Compute pipelines and compute-stage descriptor/pipeline layouts.
#include <utility>
#include <vector>

#include "vk/Resources.h"

namespace weft::vk {

/// A compute pipeline from the embedded shader `shader` (path relative to glsl/).
Pipeline createComputePipeline(Context& ctx, const char* shader, VkPipelineLayout layout);

/// Descriptor set layout from (binding, type) pairs, visible to the compute stage.
DescriptorSetLayout createComputeSetLayout(
    Context& ctx, const std::vector<std::pair<uint32_t, VkDescriptorType>>& bindings);
/// Pipeline layout whose push constants (if any) are visible to the compute stage.
PipelineLayout createComputePipelineLayout(Context& ctx, const std::vector<VkDescriptorSetLayout>& sets,
                                           uint32_t pushConstantBytes);

} // namespace weft::vk
