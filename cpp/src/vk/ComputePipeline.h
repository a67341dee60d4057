#pragma once
// Compute pipelines from embedded SPIR-V.
#include "vk/Resources.h"

namespace weft::vk {

/// A compute pipeline running `main` of the embedded shader `embeddedShaderName` (path relative
/// to glsl/, e.g. "ibl/prefilter_ggx.comp") with `layout`.
Pipeline createComputePipeline(Context& ctx, const char* embeddedShaderName,
                               VkPipelineLayout layout);

} // namespace weft::vk
