#pragma once
// Layouts and pipelines of the hair passes: camera views (opaque, debug, OIT accumulation) for
// lines and ribbons, light views (shadow-map / DOM depth, DOM opacity) and the OIT composite.
#include "vk/Pipeline.h"

namespace weft::render {

struct ScenePipelines;

constexpr VkFormat kDomOpacityFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kOitAccumFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kOitWeightFormat = VK_FORMAT_R32_SFLOAT;

struct HairPipelines {
    HairPipelines(vk::Context& ctx, const ScenePipelines& scene);

    vk::DescriptorSetLayout hairSetLayout; // set 2: vertices, instances, hair frame
    vk::DescriptorSetLayout domSetLayout;  // set 3: a DOM image array
    vk::DescriptorSetLayout oitSetLayout;  // composite: accumulation (+ revealage), weight sum
    vk::PipelineLayout layout;             // sets 0-3 + push constants (instance / light view)
    vk::PipelineLayout compositeLayout;
    // [0]: lines, [1]: ribbons
    vk::Pipeline opaque[2], debug[2], oit[2];
    vk::Pipeline lightDepth;  // lines into a depth target (shadow maps, DOM pass 1)
    vk::Pipeline domOpacity;  // DOM pass 2
    vk::Pipeline composite;
};

} // namespace weft::render
