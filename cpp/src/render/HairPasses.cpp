#include "render/HairPasses.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "render/HairShadingGpu.h"
#include "render/PassSetup.h"
#include "render/RenderTargets.h"
#include "render/ScenePipelines.h"

namespace weft::render {

namespace {

constexpr VkShaderStageFlags kStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

} // namespace

// The pixels the strands can cover: each draw's bounds, grown by its widest ribbon, projected,
// plus three pixels for an anti-aliased strip's reach across and past its ends (at most 1.2);
// the whole target where a bound reaches behind the camera.
VkRect2D HairPasses::screenRect(const Camera& camera, const RenderSettings& settings,
                                uint32_t width, uint32_t height) const {
    const VkRect2D whole{{0, 0}, {width, height}};
    const glm::mat4 viewProj = camera.projection(float(width) / float(height)) * camera.view();
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const HairDraw& d : mDraws) {
        glm::vec3 worldLo(1e30f), worldHi(-1e30f);
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 c((i & 1) ? d.hi.x : d.lo.x, (i & 2) ? d.hi.y : d.lo.y,
                              (i & 4) ? d.hi.z : d.lo.z);
            const glm::vec3 w(d.model * glm::vec4(c, 1.0f));
            worldLo = glm::min(worldLo, w);
            worldHi = glm::max(worldHi, w);
        }
        const glm::vec3 grow(settings.hairWidth * d.gpu->maxThickness);
        worldLo -= grow;
        worldHi += grow;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 c((i & 1) ? worldHi.x : worldLo.x, (i & 2) ? worldHi.y : worldLo.y,
                              (i & 4) ? worldHi.z : worldLo.z);
            const glm::vec4 clip = viewProj * glm::vec4(c, 1.0f);
            if (!(clip.w > 1e-6f)) return whole;
            const glm::vec2 pixel =
                (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(float(width), float(height));
            lo = glm::min(lo, pixel);
            hi = glm::max(hi, pixel);
        }
    }
    const float margin = 3.0f;
    const glm::vec2 size{float(width), float(height)};
    lo = glm::clamp(glm::floor(lo - margin), glm::vec2(0.0f), size - 1.0f);
    hi = glm::clamp(glm::ceil(hi + margin), lo + 1.0f, size);
    return {{int32_t(lo.x), int32_t(lo.y)}, {uint32_t(hi.x - lo.x), uint32_t(hi.y - lo.y)}};
}

void HairPasses::prepare(uint32_t slotIndex, const Scene& scene, const Camera& camera,
                         const RenderSettings& settings, uint32_t width, uint32_t height,
                         const std::vector<int>& gpuLightIndex, uint32_t lightFeatures) {
    mRibbons = settings.hairPrimitive == HairPrimitive::Ribbons;
    // Hair is drawn after the forward pass's MSAA resolve, so it anti-aliases itself with
    // coverage; msaa = 1 asks for no anti-aliasing and keeps one strand per pixel.
    mAntialias = settings.msaa > 1;
    mDraws.clear();
    std::vector<GpuHairInstance> instances;
    bool anyTransparent = false;
    for (const HairInstance& h : scene.hairs()) {
        HairGpu& gpu = mCache.get(h.strands, mRibbons || mAntialias);
        if (gpu.lineIndexCount == 0) continue; // single-point strands only: nothing to draw
        const bool transparent = settings.hairTransparency && gpu.transparent;
        anyTransparent |= transparent;
        mDraws.push_back({&gpu, VK_NULL_HANDLE, uint32_t(instances.size()), h.material.model,
                          nullptr, h.lo, h.hi, h.castShadows, transparent, h.transform});
        instances.push_back({h.transform, hair::packHairShading(h.material)});
    }
    mOit = anyTransparent;
    mSampleDepths =
        mAntialias && mPipes.sampleMasks &&
        std::any_of(mDraws.begin(), mDraws.end(), [](const HairDraw& d) { return !d.transparent; });
    fitDoms(scene, settings);
    // the shadow-map path only where a shadowed directional light has no deep opacity map
    for (size_t i = 0; i < scene.lights().size(); ++i) {
        const auto* light = std::get_if<DirectionalLight>(&scene.lights()[i]);
        const auto hasDom = [&](const Dom& d) { return d.light == int(i); };
        if (light && light->castShadows && std::none_of(mDoms.begin(), mDoms.end(), hasDom))
            lightFeatures |= gpu::FEATURE_HAIR_SHADOW_MAPS;
    }
    for (HairDraw& d : mDraws)
        d.shaded = &mPipes.shaded(lightFeatures, d.shading, settings.hairOitWeight);
    mMeshesShadowHair =
        !mDoms.empty() && std::any_of(scene.instances().begin(), scene.instances().end(),
                                      [](const MeshInstance& m) { return m.castShadows; });
    ensureImages(settings, width, height);
    std::vector<uint64_t> key = domKey();
    mReuseDoms = settings.reuseShadowMaps && !mDoms.empty() && key == mDomKey;
    mDomKey = std::move(key);
    for (const Dom& d : mDoms) mLastDoms[size_t(d.light)] = d.info;
    mRect = screenRect(camera, settings, width, height);

    GpuHairFrame f{};
    f.cameraForward =
        glm::vec4(glm::normalize(camera.target - camera.position), settings.hairWidth);
    f.params = glm::ivec4(mRibbons ? 1 : 0, int(settings.hairOitWeight), int(mDoms.size()),
                          settings.hairDomLogSpacing ? 1 : 0);
    f.domLight = glm::ivec4(-1);
    for (size_t i = 0; i < mDoms.size(); ++i) {
        f.domLight[int(i)] = gpuLightIndex[size_t(mDoms[i].light)]; // as the shaders index them
        f.domViewProj[i] = mDoms[i].viewProj;
        f.domMeshViewProj[i] = mDoms[i].meshViewProj;
        f.domLayer[i] = glm::vec4(mDoms[i].layerNdc, 0, 0, 0);
    }
    Slot& slot = mSlots[slotIndex % mSlots.size()];
    ensureBuffer(mCtx, slot.instances, instances.size() * sizeof(GpuHairInstance),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ensureBuffer(mCtx, slot.frame, sizeof(f), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    if (!instances.empty())
        slot.instances.write(instances.data(), instances.size() * sizeof(GpuHairInstance));
    slot.frame.write(&f, sizeof(f));
    allocateSets(slot, uint32_t(mDraws.size()));
    writeSets(slot);
}

void HairPasses::drawDepth(VkCommandBuffer cmd, const glm::mat4& viewProj) const {
    drawFromLight(cmd, mPipes.lightDepth, viewProj, glm::vec4(0.0f));
}

void HairPasses::drawFromLight(VkCommandBuffer cmd, VkPipeline pipeline, const glm::mat4& viewProj,
                               const glm::vec4& params) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    for (const HairDraw& d : mDraws) {
        if (!d.castShadows) continue;
        const struct {
            glm::mat4 mvp;
            glm::vec4 params;
        } push{viewProj * d.model, params};
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipes.layout, 2, 1, &d.set,
                                0, nullptr);
        vkCmdPushConstants(cmd, mPipes.layout, kStages, 0, sizeof(push), &push);
        vkCmdBindIndexBuffer(cmd, d.gpu->lines.get(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, d.gpu->lineIndexCount, 1, 0, 0, 0);
    }
}

void HairPasses::drawCamera(VkCommandBuffer cmd, const Targets& t, const PipelineOf& pipeline,
                            VkDescriptorSet domSet, bool transparent, bool strips) const {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipes.layout, 0, 1, &t.frameSet,
                            0, nullptr);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipes.layout, 3, 1, &domSet, 0,
                            nullptr);
    VkPipeline bound = VK_NULL_HANDLE;
    for (const HairDraw& d : mDraws) {
        if (d.transparent != transparent) continue;
        const VkPipeline p = pipeline(*d.shaded); // the draw's model (all share one layout)
        if (p != bound) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound = p);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipes.layout, 2, 1, &d.set,
                                0, nullptr);
        vkCmdPushConstants(cmd, mPipes.layout, kStages, 0, sizeof(uint32_t), &d.instance);
        const bool ribbons = strips && d.gpu->ribbons;
        vkCmdBindIndexBuffer(cmd, ribbons ? d.gpu->ribbons.get() : d.gpu->lines.get(), 0,
                             VK_INDEX_TYPE_UINT32);
        const uint32_t count = ribbons ? d.gpu->ribbonIndexCount : d.gpu->lineIndexCount;
        vkCmdDrawIndexed(cmd, count, 1, 0, 0, 0);
    }
}

void HairPasses::addPasses(FrameGraph& g, const Targets& t) {
    if (mDraws.empty()) return;
    const int ribbons = mRibbons ? 1 : 0;
    const bool aa = mAntialias && !t.debug; // debug outputs: one strand per pixel, as drawn
    std::vector<ResourceUse> shadingReads = {{t.shadow, Use::Sampled}};
    if (!mDoms.empty()) {
        const int rZ0 = g.addResource("hair_dom_depth", &mDomDepth);
        const int rOpacity = g.addResource("hair_dom_opacity", &mDomOpacity);
        shadingReads.push_back({rOpacity, Use::Sampled});
        // The mesh casters in each DOM's view: hair behind them is in their shadow.
        if (mMeshesShadowHair) {
            const int rMeshes = g.addResource("hair_dom_meshes", &mDomMeshDepth);
            shadingReads.push_back({rMeshes, Use::Sampled});
            g.addPass({"hair_dom_meshes",
                       {},
                       {{rMeshes, Use::DepthWrite}},
                       [this, t](VkCommandBuffer cmd) {
                           for (size_t s = 0; s < mDoms.size(); ++s)
                               t.meshDepth(cmd, mDomMeshDepth.layerView(uint32_t(s)), mDomSize,
                                           mDoms[s].meshViewProj);
                       }});
        }
        if (mReuseDoms) { // the maps hold these views of these strands
            if (t.reused) t.reused->insert(t.reused->end(), {"hair_dom_depth", "hair_dom_opacity"});
        } else {
            g.addPass({"hair_dom_depth", {}, {{rZ0, Use::DepthWrite}}, [this](VkCommandBuffer cmd) {
                           for (size_t s = 0; s < mDoms.size(); ++s) {
                               VkRenderingAttachmentInfo depth =
                                   attachment(mDomDepth.layerView(uint32_t(s)),
                                              VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, true);
                               depth.clearValue.depthStencil = {1.0f, 0};
                               VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                               info.renderArea = {{0, 0}, {mDomSize, mDomSize}};
                               info.layerCount = 1;
                               info.pDepthAttachment = &depth;
                               mCtx.fn().cmdBeginRendering(cmd, &info);
                               setViewport(cmd, mDomSize, mDomSize);
                               drawFromLight(cmd, mPipes.lightDepth, mDoms[s].viewProj,
                                             glm::vec4(0.0f));
                               mCtx.fn().cmdEndRendering(cmd);
                           }
                       }});
            g.addPass({"hair_dom_opacity",
                       {{rZ0, Use::Sampled}},
                       {{rOpacity, Use::ColorWrite}},
                       [this](VkCommandBuffer cmd) {
                           for (size_t s = 0; s < mDoms.size(); ++s) {
                               VkRenderingAttachmentInfo color =
                                   attachment(mDomOpacity.layerView(uint32_t(s)),
                                              VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true);
                               color.clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}};
                               VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                               info.renderArea = {{0, 0}, {mDomSize, mDomSize}};
                               info.layerCount = 1;
                               info.colorAttachmentCount = 1;
                               info.pColorAttachments = &color;
                               mCtx.fn().cmdBeginRendering(cmd, &info);
                               setViewport(cmd, mDomSize, mDomSize);
                               vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                                       mPipes.layout, 3, 1, &mZ0Set, 0, nullptr);
                               drawFromLight(cmd, mPipes.domOpacity, mDoms[s].viewProj,
                                             glm::vec4(float(s), mDoms[s].layerNdc, 0.0f, 0.0f));
                               mCtx.fn().cmdEndRendering(cmd);
                           }
                       }});
        }
    }
    const bool anyOpaque =
        std::any_of(mDraws.begin(), mDraws.end(), [](const HairDraw& d) { return !d.transparent; });
    if (anyOpaque) {
        std::vector<ResourceUse> writes = {{t.hdr, Use::ColorWrite}, {t.depth, Use::DepthWrite}};
        if (t.debug)
            for (int i = 0; i < 4; ++i) writes.push_back({t.debug[i], Use::ColorWrite});
        const bool debug = t.debug != nullptr;
        g.addPass(
            {"hair", shadingReads, writes, [this, t, debug, ribbons, aa](VkCommandBuffer cmd) {
                 std::vector<VkRenderingAttachmentInfo> colors = {attachment(
                     t.hdrImage->view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, false)};
                 if (debug)
                     for (vk::Image* im : t.debugImages)
                         colors.push_back(attachment(
                             im->view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, false));
                 VkRenderingAttachmentInfo depth = attachment(
                     t.depthImage->view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, false);
                 VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                 const vk::ImageDesc& desc = t.hdrImage->desc();
                 info.renderArea = {{0, 0}, {desc.width, desc.height}};
                 info.layerCount = 1;
                 info.colorAttachmentCount = uint32_t(colors.size());
                 info.pColorAttachments = colors.data();
                 info.pDepthAttachment = &depth;
                 mCtx.fn().cmdBeginRendering(cmd, &info);
                 setViewport(cmd, desc.width, desc.height);
                 // anti-aliased: only the pixels strands cover entirely (hair_fringe adds
                 // the rest)
                 const auto pipeline = [aa, debug, ribbons](const HairShadedPipelines& p) {
                     return aa      ? p.aaCore.get()
                            : debug ? p.debug[ribbons].get()
                                    : p.opaque[ribbons].get();
                 };
                 drawCamera(cmd, t, pipeline, mOpacitySet, false, aa || mRibbons);
                 mCtx.fn().cmdEndRendering(cmd);
             }});
    }
    const bool fringe = aa && anyOpaque;
    if (!fringe && !mOit) return;
    const int rAccum = g.addResource("hair_oit_accum", &mAccum);
    const int rWeight = g.addResource("hair_oit_weight", &mWeight);
    // Begins rendering into the accumulation targets (cleared by the first pass that draws
    // into them), depth tested against the meshes and opaque hair.
    auto beginAccumulation = [this, t](VkCommandBuffer cmd, bool clear) {
        VkRenderingAttachmentInfo colors[2] = {
            attachment(mAccum.view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, clear),
            attachment(mWeight.view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, clear)};
        colors[0].clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}}; // a: revealage
        colors[1].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
        VkRenderingAttachmentInfo depth =
            attachment(t.depthImage->view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, false);
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = mRect; // cleared (and composited) where strands can be only
        info.layerCount = 1;
        info.colorAttachmentCount = 2;
        info.pColorAttachments = colors;
        info.pDepthAttachment = &depth;
        mCtx.fn().cmdBeginRendering(cmd, &info);
        setViewport(cmd, mWidth, mHeight);
        vkCmdSetScissor(cmd, 0, 1, &mRect);
    };
    const std::vector<ResourceUse> accumulates = {
        {rAccum, Use::ColorWrite}, {rWeight, Use::ColorWrite}, {t.depth, Use::DepthWrite}};
    if (fringe)
        g.addPass(
            {"hair_fringe", shadingReads, accumulates,
             [this, t, beginAccumulation](VkCommandBuffer cmd) {
                 if (!mPipes.sampleMasks) { // coverage as independent alphas
                     beginAccumulation(cmd, true);
                     drawCamera(
                         cmd, t, [](const HairShadedPipelines& p) { return p.aaFringe[0].get(); },
                         mOpacitySet, false, true);
                     mCtx.fn().cmdEndRendering(cmd);
                     return;
                 }
                 // no depth at any sample point (all ones), no point covered, sums 0
                 vk::transition(mCtx, cmd, mSamples, VK_IMAGE_LAYOUT_GENERAL,
                                VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
                 VkClearColorValue clear{};
                 for (uint32_t layer = 0; layer < mSamples.desc().layers; ++layer) {
                     clear.uint32[0] = layer < kHairAaDepthSamples ? ~0u : 0u;
                     const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, layer, 1};
                     vkCmdClearColorImage(cmd, mSamples.get(), VK_IMAGE_LAYOUT_GENERAL, &clear, 1,
                                          &range);
                 }
                 // pass 0 writes the nearest depths, pass 1 reads them once all are in
                 for (int i = 0; i < 2; ++i) {
                     vk::transition(mCtx, cmd, mSamples, VK_IMAGE_LAYOUT_GENERAL,
                                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
                     beginAccumulation(cmd, i == 0);
                     drawCamera(
                         cmd, t, [i](const HairShadedPipelines& p) { return p.aaFringe[i].get(); },
                         mOpacitySet, false, true);
                     mCtx.fn().cmdEndRendering(cmd);
                 }
             }});
    if (mOit)
        g.addPass({"hair_oit", shadingReads, accumulates,
                   [this, t, ribbons, aa, fringe, beginAccumulation](VkCommandBuffer cmd) {
                       beginAccumulation(cmd, !fringe);
                       drawCamera(
                           cmd, t,
                           [aa, ribbons](const HairShadedPipelines& p) {
                               return aa ? p.aaOit.get() : p.oit[ribbons].get();
                           },
                           mOpacitySet, true, aa || mRibbons);
                       mCtx.fn().cmdEndRendering(cmd);
                   }});
    g.addPass({"hair_composite",
               {{rAccum, Use::Sampled}, {rWeight, Use::Sampled}},
               {{t.hdr, Use::ColorWrite}},
               [this, t](VkCommandBuffer cmd) {
                   VkRenderingAttachmentInfo color = attachment(
                       t.hdrImage->view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, false);
                   VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                   info.renderArea = mRect; // no strand elsewhere: nothing to composite
                   info.layerCount = 1;
                   info.colorAttachmentCount = 1;
                   info.pColorAttachments = &color;
                   mCtx.fn().cmdBeginRendering(cmd, &info);
                   setViewport(cmd, mWidth, mHeight);
                   vkCmdSetScissor(cmd, 0, 1, &mRect);
                   vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipes.composite);
                   vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                           mPipes.compositeLayout, 0, 1, &mOitSet, 0, nullptr);
                   vkCmdDraw(cmd, 3, 1, 0, 0);
                   mCtx.fn().cmdEndRendering(cmd);
               }});
}

} // namespace weft::render
