#pragma once
// Everything the scene passes draw with: samplers, descriptor-set and pipeline layouts, and
// the graphics pipelines (shadow depth, forward, forward + debug outputs, sRGB output).
#include <unordered_map>

#include <glm/glm.hpp>

#include "vk/Pipeline.h"

namespace weft::render {

/// Push constants of the shadow pipelines.
struct ShadowPush {
    glm::mat4 lightMvp;
    float alphaCutoff;
};

struct ScenePipelines {
    explicit ScenePipelines(vk::Context& ctx);

    vk::Sampler textureSampler; // trilinear, repeat
    vk::Sampler nearestSampler; // texel fetches (shadow maps, hdr)
    vk::Sampler cookieSampler;  // bilinear, clamp to edge, level 0 (spot-light cookies)
    vk::Sampler environmentSampler; // trilinear over the whole chain (environment cube)
    vk::DescriptorSetLayout frameSetLayout, materialSetLayout, outputSetLayout;
    vk::PipelineLayout sceneLayout, shadowLayout, outputLayout;
    vk::Pipeline shadow, shadowAlpha;
    /// Forward shading, [debug outputs][facing]: facing 0 = back faces culled, 1 = the same for
    /// mirroring transforms (det < 0 reverses the winding), 2 = two-sided (no culling).
    vk::Pipeline forward[2][3];

    VkPipeline forwardFor(bool debug, bool mirrored, bool twoSided) const {
        return forward[debug ? 1 : 0][twoSided ? 2 : mirrored ? 1 : 0];
    }

    /// Builds every pipeline again from the current shaders (hot reload); layouts and samplers
    /// stay, so descriptor sets made for them stay valid. Old pipelines are retired.
    void createPipelines();

    /// The sRGB output pipeline for a colour format (offscreen RGBA8 or a swapchain's format).
    VkPipeline outputPipeline(VkFormat format);

private:
    vk::Context& mCtx;
    std::unordered_map<int, vk::Pipeline> mOutput; // by format
};

} // namespace weft::render
