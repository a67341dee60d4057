#pragma once
// Everything the scene passes draw with: samplers, descriptor-set and pipeline layouts, and
// the graphics pipelines (shadow depth, forward, forward + debug outputs, sRGB output).
#include <unordered_map>

#include <glm/glm.hpp>

#include "render/GpuTypes.h"
#include "vk/Pipeline.h"

namespace weft::render {

/// Push constants of the shadow pipelines.
struct ShadowPush {
    glm::mat4 lightMvp;
    float alphaCutoff;
};

struct ScenePipelines {
    explicit ScenePipelines(vk::Context& ctx);

    vk::Sampler textureSampler;     // trilinear, repeat
    vk::Sampler nearestSampler;     // texel fetches (shadow maps, hdr)
    vk::Sampler cookieSampler;      // bilinear, clamp to edge, level 0 (spot-light cookies)
    vk::Sampler environmentSampler; // trilinear over the whole chain (environment cube)
    vk::DescriptorSetLayout frameSetLayout, materialSetLayout, outputSetLayout, domeBlurSetLayout,
        bounceShSetLayout;
    vk::PipelineLayout sceneLayout, shadowLayout, outputLayout, domeBlurLayout, bounceShLayout;
    vk::Pipeline shadow, shadowAlpha;
    vk::Pipeline domeGather;     // the dome's visibility per pixel, for the blur
    vk::Pipeline domeBlurRows;   // the dome blur's row pass
    vk::Pipeline domeBlur;       // its column pass, adding the dome-shadowed diffuse light
    vk::Pipeline bounceGeometry; // where the captures' texels lie from the casters' points
    vk::Pipeline bounceSh;       // the bounce captures projected onto SH9 (BounceProbes.h)
    vk::Pipeline bounceRadiance; // the casters' radiance in SH9, from the frame set

    /// Forward shading for an output set (`debug` outputs, `dome` output for the blur pass) and
    /// a facing: back faces culled, the same for mirroring transforms (det < 0 reverses the
    /// winding), or two-sided (no culling). Created on first use.
    /// `samples`: MSAA samples of the targets (1, 2, 4, 8). `features`: the gpu::FEATURE_* bits
    /// the frame may use (frameFeatures); the others' code is left out of the pipeline.
    /// `material`: the Instance::flags.x bits the draw's material may have (the same).
    VkPipeline forwardFor(bool debug, bool dome, bool mirrored, bool twoSided, uint32_t samples,
                          uint32_t features = gpu::FEATURE_ALL,
                          uint32_t material = gpu::MATERIAL_ALL);
    /// The background of `frame` (its image, or its environment sharp or blurred: only that
    /// one's code in the pipeline). `behind` false: under a cube capture's surfaces, drawn first
    /// into its colour target (its depth neither tested nor written). `behind` true: the forward
    /// pass's last draw, into its attachments (forwardFor's `debug`, `dome`: those get their
    /// clear values) where its depth test against the far plane finds nothing drawn, so a GPU's
    /// early depth test shades only the pixels the background shows (ForwardPasses.cpp).
    VkPipeline backgroundFor(const GpuFrame& frame, bool behind, uint32_t samples = 1,
                             bool debug = false, bool dome = false);

    /// Builds every pipeline again from the current shaders (hot reload); layouts and samplers
    /// stay, so descriptor sets made for them stay valid. Old pipelines are retired.
    void createPipelines();

    /// The sRGB output pipeline for a colour format (offscreen RGBA8 or a swapchain's format)
    /// and a tone map (weft::ToneMap: only its operator's code in the pipeline).
    VkPipeline outputPipeline(VkFormat format, uint32_t toneMap);

private:
    vk::Context& mCtx;
    std::unordered_map<uint64_t, vk::Pipeline> mOutput; // by format and tone map
    // by debug, dome, facing, samples 1, 2, 4, 8 and features (forwardFor)
    std::unordered_map<uint64_t, vk::Pipeline> mForward;
    // by behind, debug, dome, samples and background.frag's kind (backgroundFor)
    std::unordered_map<uint32_t, vk::Pipeline> mBackground;
};

} // namespace weft::render
