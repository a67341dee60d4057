#include "render/ScenePipelines.h"

#include <cmath>
#include <string>

#include <weft/Renderer.h>

#include "render/BounceProbes.h"
#include "render/GpuCache.h"
#include "render/GpuTypes.h"
#include "render/RenderTargets.h"

namespace weft::render {

ScenePipelines::ScenePipelines(vk::Context& c) : mCtx(c) {
    VkSamplerCreateInfo s{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    s.magFilter = s.minFilter = VK_FILTER_LINEAR;
    s.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    s.addressModeU = s.addressModeV = s.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    s.maxLod = VK_LOD_CLAMP_NONE;
    VkSampler sampler;
    VK_CHECK(vkCreateSampler(c.device(), &s, nullptr, &sampler));
    textureSampler = vk::Sampler(&c, sampler, vkDestroySampler);
    s.magFilter = s.minFilter = VK_FILTER_NEAREST;
    s.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    s.addressModeU = s.addressModeV = s.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    s.maxLod = 0.0f;
    VK_CHECK(vkCreateSampler(c.device(), &s, nullptr, &sampler));
    nearestSampler = vk::Sampler(&c, sampler, vkDestroySampler);
    s.magFilter = s.minFilter = VK_FILTER_LINEAR;
    VK_CHECK(vkCreateSampler(c.device(), &s, nullptr, &sampler));
    cookieSampler = vk::Sampler(&c, sampler, vkDestroySampler);
    s.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    s.maxLod = VK_LOD_CLAMP_NONE;
    VK_CHECK(vkCreateSampler(c.device(), &s, nullptr, &sampler));
    environmentSampler = vk::Sampler(&c, sampler, vkDestroySampler);

    frameSetLayout = vk::createSetLayout(
        c, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
            {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, uint32_t(kMaxCookies)},
            {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {8, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {9, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {10, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {11, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {12, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {13, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {14, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {15, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {16, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {17, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {18, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}});
    materialSetLayout = vk::createSetLayout(c, {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}});
    outputSetLayout = vk::createSetLayout(c, {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}});
    sceneLayout =
        vk::createPipelineLayout(c, {frameSetLayout, materialSetLayout}, sizeof(uint32_t));
    shadowLayout = vk::createPipelineLayout(c, {materialSetLayout}, sizeof(ShadowPush));
    outputLayout = vk::createPipelineLayout(c, {outputSetLayout}, sizeof(OutputPush));
    domeBlurSetLayout = vk::createSetLayout(c, {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}});
    domeBlurLayout = vk::createPipelineLayout(c, {domeBlurSetLayout}, sizeof(DomeBlurPush));
    bounceShSetLayout = vk::createSetLayout(c, {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}});
    bounceShLayout = vk::createPipelineLayout(c, {bounceShSetLayout}, sizeof(BounceShPush));
    createPipelines();
}

namespace {
int sampleIndex(uint32_t samples) { // 1, 2, 4, 8 -> 0..3
    return samples >= 8 ? 3 : samples >= 4 ? 2 : samples >= 2 ? 1 : 0;
}

// The forward pass's colour attachments (glsl/common/forward_outputs.glsl): the colour, the
// debug outputs, the dome's two.
std::vector<VkFormat> forwardColorFormats(bool debug, bool dome) {
    std::vector<VkFormat> formats = {kHdrFormat};
    if (debug) formats.insert(formats.end(), 4, kDebugFormat);
    if (dome) formats.insert(formats.end(), {kDomeFormat, kDomeAuxFormat});
    return formats;
}
} // namespace

VkPipeline ScenePipelines::forwardFor(bool debug, bool dome, bool mirrored, bool twoSided,
                                      uint32_t samples, uint32_t features, uint32_t material) {
    const int facing = twoSided ? 2 : mirrored ? 1 : 0;
    features &= gpu::FEATURE_ALL;
    material &= gpu::MATERIAL_ALL;
    static_assert(gpu::FEATURE_ALL < (1u << 14) && gpu::MATERIAL_ALL < (1u << 16),
                  "the key's bits");
    const uint64_t key = features | uint64_t(sampleIndex(samples)) << 14 | uint64_t(facing) << 16 |
                         uint64_t(dome) << 18 | uint64_t(debug) << 19 | uint64_t(material) << 20;
    vk::Pipeline& p = mForward[key];
    if (p) return p;
    static const char* const shaders[2][2] = {
        {"render/forward.frag", "render/forward_dome.frag"},
        {"render/forward_debug.frag", "render/forward_debug_dome.frag"}};
    vk::GraphicsPipelineDesc d;
    d.vertexStride = kVertexStride;
    d.vertexShader = "render/forward.vert";
    d.fragmentShader = shaders[debug][dome];
    d.colorFormats = forwardColorFormats(debug, dome);
    d.depthFormat = kDepthFormat;
    d.layout = sceneLayout;
    d.cullMode = facing == 2 ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
    d.frontFace = facing == 1 ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE;
    d.samples = VkSampleCountFlagBits(samples);
    d.fragmentConstants = {features, material};
    p = vk::createGraphicsPipeline(mCtx, d);
    return p;
}

VkPipeline ScenePipelines::backgroundFor(const GpuFrame& frame, bool behind, uint32_t samples,
                                         bool debug, bool dome) {
    // background.frag's kBackground: 0 the image, 1 the sharp radiance, 2 the glossy chain
    const uint32_t kind = frame.options.w > 0.5f ? 0u : frame.sky.y < 0.0f ? 1u : 2u;
    const uint32_t key = kind | uint32_t(sampleIndex(samples)) << 2 | uint32_t(behind) << 4 |
                         uint32_t(debug) << 5 | uint32_t(dome) << 6;
    vk::Pipeline& p = mBackground[key];
    if (p) return p;
    vk::GraphicsPipelineDesc d; // a full-screen triangle
    d.vertexShader = "render/fullscreen.vert";
    d.vertexLayout = vk::VertexLayout::None;
    d.colorFormats = forwardColorFormats(debug, dome);
    d.cullMode = VK_CULL_MODE_NONE;
    d.depthTest = behind; // drawn at the far plane (the caller's viewport): where nothing was
    d.depthWrite = false;
    d.depthFormat = kDepthFormat;
    static const char* const shaders[2][2] = {
        {"render/background.frag", "render/background_dome.frag"},
        {"render/background_debug.frag", "render/background_debug_dome.frag"}};
    d.fragmentShader = shaders[debug][dome]; // the extra outputs as the forward pass clears them
    d.fragmentConstants = {gpu::FEATURE_ALL, gpu::MATERIAL_ALL, kind};
    d.layout = sceneLayout;
    d.samples = VkSampleCountFlagBits(samples);
    p = vk::createGraphicsPipeline(mCtx, d);
    return p;
}

void ScenePipelines::createPipelines() {
    vk::Context& c = mCtx;
    mForward.clear(); // created again on first use
    mBackground.clear();

    vk::GraphicsPipelineDesc fd; // full-screen passes into the hdr target
    fd.vertexShader = "render/fullscreen.vert";
    fd.vertexLayout = vk::VertexLayout::None;
    fd.colorFormats = {kHdrFormat};
    fd.cullMode = VK_CULL_MODE_NONE;
    fd.depthTest = fd.depthWrite = false;
    fd.layout = domeBlurLayout;
    fd.colorFormats = {kDomeBlurFormat};
    fd.fragmentShader = "render/dome_gather.frag";
    domeGather = vk::createGraphicsPipeline(c, fd);
    fd.fragmentShader = "render/dome_blur_x.frag";
    domeBlurRows = vk::createGraphicsPipeline(c, fd);
    fd.fragmentShader = "render/dome_blur.frag";
    fd.colorFormats = {kHdrFormat};
    VkPipelineColorBlendAttachmentState add{};
    add.blendEnable = VK_TRUE;
    add.srcColorBlendFactor = add.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
    add.colorBlendOp = VK_BLEND_OP_ADD;
    add.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
    add.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    add.alphaBlendOp = VK_BLEND_OP_ADD;
    add.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                         VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    fd.blends = {add};
    domeBlur = vk::createGraphicsPipeline(c, fd);
    fd.blends.clear();
    fd.layout = bounceShLayout;
    fd.fragmentShader = "render/bounce_sh.frag";
    fd.colorFormats = {BounceProbes::kShFormat};
    bounceSh = vk::createGraphicsPipeline(c, fd);
    fd.fragmentShader = "render/bounce_geometry.frag";
    bounceGeometry = vk::createGraphicsPipeline(c, fd);
    fd.layout = sceneLayout;
    fd.fragmentShader = "render/bounce_radiance.frag";
    bounceRadiance = vk::createGraphicsPipeline(c, fd);

    vk::GraphicsPipelineDesc sd;
    sd.vertexShader = "render/shadow.vert";
    sd.vertexLayout = vk::VertexLayout::Position;
    sd.vertexStride = kVertexStride;
    sd.depthFormat = kDepthFormat;
    sd.cullMode = VK_CULL_MODE_NONE; // open meshes (planes, cloth) must cast from both sides
    sd.layout = shadowLayout;
    shadow = vk::createGraphicsPipeline(c, sd);
    sd.vertexShader = "render/shadow_alpha.vert";
    sd.fragmentShader = "render/shadow_alpha.frag"; // discards texels below the alpha cutoff
    sd.vertexLayout = vk::VertexLayout::PositionUv;
    shadowAlpha = vk::createGraphicsPipeline(c, sd);
    mOutput.clear(); // created again on first use
}

VkPipeline ScenePipelines::outputPipeline(VkFormat format, uint32_t toneMap) {
    const uint64_t key = uint64_t(format) << 8 | toneMap;
    auto it = mOutput.find(key);
    if (it != mOutput.end()) return it->second;
    vk::GraphicsPipelineDesc d;
    d.vertexShader = "render/fullscreen.vert";
    d.fragmentShader = "render/output.frag";
    d.vertexLayout = vk::VertexLayout::None;
    d.colorFormats = {format};
    d.cullMode = VK_CULL_MODE_NONE;
    d.depthTest = d.depthWrite = false;
    d.layout = outputLayout;
    d.fragmentConstants = {toneMap}; // output.frag's kToneMap
    return mOutput.emplace(key, vk::createGraphicsPipeline(mCtx, d)).first->second;
}

} // namespace weft::render
