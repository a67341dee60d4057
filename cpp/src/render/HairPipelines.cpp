#include "render/HairPipelines.h"

#include "render/HairGpuTypes.h"
#include "render/RenderTargets.h"
#include "render/ScenePipelines.h"

namespace weft::render {

namespace {

VkPipelineColorBlendAttachmentState blend(VkBlendFactor src, VkBlendFactor dst,
                                          VkBlendFactor srcAlpha, VkBlendFactor dstAlpha,
                                          VkBlendOp alphaOp = VK_BLEND_OP_ADD) {
    VkPipelineColorBlendAttachmentState b{};
    b.blendEnable = VK_TRUE;
    b.srcColorBlendFactor = src;
    b.dstColorBlendFactor = dst;
    b.colorBlendOp = VK_BLEND_OP_ADD;
    b.srcAlphaBlendFactor = srcAlpha;
    b.dstAlphaBlendFactor = dstAlpha;
    b.alphaBlendOp = alphaOp;
    b.colorWriteMask = 0xF;
    return b;
}

} // namespace

HairPipelines::HairPipelines(vk::Context& c, const ScenePipelines& scene) : mCtx(c) {
    hairSetLayout = vk::createSetLayout(c, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                            {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                            {2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}});
    domSetLayout = vk::createSetLayout(c, {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                           {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                           {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}});
    VkPhysicalDeviceFeatures features{};
    vkGetPhysicalDeviceFeatures(c.physicalDevice(), &features);
    sampleMasks = features.fragmentStoresAndAtomics == VK_TRUE;
    oitSetLayout = vk::createSetLayout(c, {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                           {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}});
    layout = vk::createPipelineLayout(
        c, {scene.frameSetLayout, scene.materialSetLayout, hairSetLayout, domSetLayout},
        sizeof(glm::mat4) + sizeof(glm::vec4));
    compositeLayout = vk::createPipelineLayout(c, {oitSetLayout}, 0);

    vk::GraphicsPipelineDesc l;
    l.vertexShader = "hair/hair_light.vert";
    l.vertexLayout = vk::VertexLayout::None;
    l.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    l.cullMode = VK_CULL_MODE_NONE;
    l.depthFormat = kDepthFormat;
    l.layout = layout;
    lightDepth = vk::createGraphicsPipeline(c, l);
    l.fragmentShader = "hair/dom_opacity.frag";
    l.depthFormat = VK_FORMAT_UNDEFINED; // every fragment counts (no depth test)
    l.colorFormats = {kDomOpacityFormat};
    l.blends = {blend(VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE,
                      VK_BLEND_FACTOR_ONE, VK_BLEND_OP_MIN)};
    domOpacity = vk::createGraphicsPipeline(c, l);

    vk::GraphicsPipelineDesc o;
    o.vertexShader = "render/fullscreen.vert";
    o.fragmentShader = "hair/oit_composite.frag";
    o.vertexLayout = vk::VertexLayout::None;
    o.cullMode = VK_CULL_MODE_NONE;
    o.depthTest = o.depthWrite = false;
    o.colorFormats = {kHdrFormat};
    o.blends = {blend(VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
                      VK_BLEND_FACTOR_ZERO, VK_BLEND_FACTOR_ONE)};
    o.layout = compositeLayout;
    composite = vk::createGraphicsPipeline(c, o);
}

const HairShadedPipelines& HairPipelines::shaded(uint32_t features, HairModel model,
                                                 OitWeight weight) {
    const uint64_t key = uint64_t(features) | uint64_t(model) << 32 | uint64_t(weight) << 40;
    auto found = mShaded.find(key);
    if (found != mShaded.end()) return found->second;
    HairShadedPipelines& p = mShaded[key];
    // constant 1 (the meshes' material flags) is not read by the hair shaders
    const std::vector<uint32_t> constants = {features, gpu::MATERIAL_ALL, uint32_t(model),
                                             uint32_t(weight)};
    for (int ribbons = 0; ribbons < 2; ++ribbons) {
        vk::GraphicsPipelineDesc d;
        d.vertexShader = "hair/hair.vert";
        d.fragmentShader = "hair/hair.frag";
        d.vertexLayout = vk::VertexLayout::None;
        d.topology =
            ribbons ? VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST : VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
        d.cullMode = VK_CULL_MODE_NONE;
        d.colorFormats = {kHdrFormat};
        d.depthFormat = kDepthFormat;
        d.layout = layout;
        d.fragmentConstants = constants;
        p.opaque[ribbons] = vk::createGraphicsPipeline(mCtx, d);
        d.fragmentShader = "hair/hair_debug.frag";
        d.colorFormats = {kHdrFormat, kDebugFormat, kDebugFormat, kDebugFormat, kDebugFormat};
        p.debug[ribbons] = vk::createGraphicsPipeline(mCtx, d);
        d.vertexShader = "hair/hair_oit.vert";
        d.fragmentShader = "hair/hair_oit.frag";
        d.colorFormats = {kOitAccumFormat, kOitWeightFormat};
        d.depthWrite = false; // tested against the opaque scene only
        const VkPipelineColorBlendAttachmentState accumulate =
            blend(VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ZERO,
                  VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA);
        d.blends = {accumulate, accumulate}; // hair_oit.frag: what each channel accumulates
        p.oit[ribbons] = vk::createGraphicsPipeline(mCtx, d);
    }

    vk::GraphicsPipelineDesc a;
    a.vertexShader = "hair/hair_aa_core.vert";
    a.fragmentShader = "hair/hair_aa_core.frag";
    a.vertexLayout = vk::VertexLayout::None;
    a.cullMode = VK_CULL_MODE_NONE;
    a.colorFormats = {kHdrFormat};
    a.depthFormat = kDepthFormat;
    a.layout = layout;
    a.fragmentConstants = constants;
    p.aaCore = vk::createGraphicsPipeline(mCtx, a);
    a.vertexShader = "hair/hair_aa_oit.vert";
    a.fragmentShader = "hair/hair_aa_oit.frag"; // transparent: independent alphas (a * coverage)
    a.colorFormats = {kOitAccumFormat, kOitWeightFormat};
    a.depthWrite = false; // partial coverage hides nothing behind it
    const VkPipelineColorBlendAttachmentState accumulate =
        blend(VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ZERO,
              VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA);
    a.blends = {accumulate, accumulate};
    p.aaOit = vk::createGraphicsPipeline(mCtx, a);
    if (sampleMasks) {
        a.fragmentShader = "hair/hair_aa_fringe1.frag";
        p.aaFringe[1] = vk::createGraphicsPipeline(mCtx, a);
        a.fragmentShader = "hair/hair_aa_fringe0.frag"; // only writes the sample depths
        for (VkPipelineColorBlendAttachmentState& b : a.blends) b.colorWriteMask = 0;
        p.aaFringe[0] = vk::createGraphicsPipeline(mCtx, a);
    } else {
        p.aaFringe[0] = vk::createGraphicsPipeline(mCtx, a); // coverage as independent alphas
    }

    return p;
}

} // namespace weft::render
