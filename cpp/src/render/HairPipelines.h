#pragma once
// Layouts and pipelines of the hair passes: camera views (opaque, debug, OIT accumulation) for
// lines and ribbons, light views (shadow-map / DOM depth, DOM opacity) and the OIT composite.
// Anti-aliased frames draw both primitives as screen-space strips with coverage (the aa*
// pipelines, glsl/common/hair_vertex.glsl HAIR_AA); debug frames never do.
#include <unordered_map>

#include <weft/HairMaterial.h>
#include <weft/Renderer.h>

#include "vk/Pipeline.h"

namespace weft::render {

struct ScenePipelines;

constexpr VkFormat kDomOpacityFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
// sum of C a w (rgb) and the revealage (alpha): half floats as in McGuire & Bavoil 2013, whose
// weights (eq. 7-10, clamped to [0.01, 3000]) are sized for them
constexpr VkFormat kOitAccumFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
// r: sum of a w; g / b: the opaque strands' coverage of a partly covered pixel (anti-aliased
// frames; alpha unused)
constexpr VkFormat kOitWeightFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
// The partly covered pixels of opaque strands in anti-aliased frames (glsl/hair/
// hair_oit_main.glsl): sample points whose nearest depth decides the strands' visible shares,
// the 32-bit words (32 points each) that record which points some strand covers, and three sums
// that turn those into the pixel's coverage.
constexpr uint32_t kHairAaDepthSamples = 32;
constexpr uint32_t kHairAaCoverageWords = 4;
constexpr uint32_t kHairAaSampleLayers = kHairAaDepthSamples + kHairAaCoverageWords + 3;

/// The pipelines that shade strands (hair_lighting.glsl), specialized to a frame's lights.
struct HairShadedPipelines {
    // [0]: lines, [1]: ribbons
    vk::Pipeline opaque[2], debug[2], oit[2];
    // Anti-aliased strips: the pixels a strand covers entirely (opaque, depth written), the
    // partly covered ones accumulated like WBOIT (depth tested only; with sample depths in two
    // passes: the nearest depth at each sample point, then the shares it leaves each strand;
    // else one), transparent strands with coverage.
    vk::Pipeline aaCore, aaFringe[2], aaOit;
};

struct HairPipelines {
    HairPipelines(vk::Context& ctx, const ScenePipelines& scene);

    /// The shading pipelines for the gpu::FEATURE_* bits of a frame's lights (FrameData::
    /// lightFeatures; frame.glsl's kFrameFeatures), a shading model and an OIT weight: only the
    /// light groups present, the model and the weight are compiled in (hair_shading.glsl's
    /// kHairModel, hair_oit_main.glsl's kOitWeight). Created on first use.
    const HairShadedPipelines& shaded(uint32_t features, HairModel model, OitWeight weight);

    vk::DescriptorSetLayout hairSetLayout; // set 2: vertices, instances, hair frame
    vk::DescriptorSetLayout domSetLayout;  // set 3: a DOM image array, mesh depth, samples
    vk::DescriptorSetLayout oitSetLayout;  // composite: accumulation (+ revealage), weight sum
    vk::PipelineLayout layout;             // sets 0-3 + push constants (instance / light view)
    vk::PipelineLayout compositeLayout;
    /// The device has atomics in fragment shaders: a strand's share of a partly covered pixel is
    /// what it shows of it at sample points (hair_oit_main.glsl); without, independent alphas.
    bool sampleMasks = false;
    vk::Pipeline lightDepth; // lines into a depth target (shadow maps, DOM pass 1)
    vk::Pipeline domOpacity; // DOM pass 2
    vk::Pipeline composite;

private:
    vk::Context& mCtx;
    std::unordered_map<uint64_t, HairShadedPipelines> mShaded; // by features, model, weight
};

} // namespace weft::render
