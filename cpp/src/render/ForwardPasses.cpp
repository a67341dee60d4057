// The forward pass: every instance shaded per pixel into the hdr target (plus the debug outputs
// or the dome's output for the blur), then the environment or the scene's background image
// behind them.
// With MSAA it renders into multisampled targets resolved at the end of the pass: colour and the
// dome output averaged, depth from sample 0 (what later passes depth-test against).
#include "render/FramePasses.h"
#include "render/GpuCache.h"
#include "render/PassSetup.h"
#include "render/RenderTargets.h"
#include "render/RendererImpl.h"
#include "render/ScenePipelines.h"

namespace weft::render {

namespace {

// Resolves `a` (multisampled) into `target` at the end of the pass.
void resolveInto(VkRenderingAttachmentInfo& a, VkImageView target, VkImageLayout layout,
                 VkResolveModeFlagBits mode) {
    a.resolveImageView = target;
    a.resolveImageLayout = layout;
    a.resolveMode = mode;
    a.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE; // only the resolved image is read later
}

} // namespace

void addForwardPasses(FrameGraph& g, FramePassContext& f) {
    RenderTargets& t = f.targets;
    const bool ms = f.samples > 1;
    const int rHdrMs = ms ? g.addResource("hdr_ms", &t.hdrMs) : -1;
    const int rDepthMs = ms ? g.addResource("depth_ms", &t.depthMs) : -1;
    const int rDomeMs = ms && f.domeBlur ? g.addResource("dome_ms", &t.domeMs) : -1;
    const int rDomeAuxMs = ms && f.domeBlur ? g.addResource("dome_aux_ms", &t.domeAuxMs) : -1;

    // the depth is kept when hair tests against it or the dome blur reads it (with MSAA the
    // multisampled one; its resolve is written either way)
    const bool keepDepth = f.hasHair || f.domeBlur;
    const Use depthUse = keepDepth ? Use::DepthWrite : Use::DepthScratch;
    std::vector<ResourceUse> writes = {{f.rHdr, Use::ColorWrite},
                                       {f.rDepth, ms ? Use::DepthWrite : depthUse}};
    if (ms) {
        writes.push_back({rHdrMs, Use::ColorWrite});
        writes.push_back({rDepthMs, depthUse});
    }
    for (int r : f.rDebug)
        if (r >= 0) writes.push_back({r, Use::ColorWrite});
    if (f.domeBlur) {
        f.rDomeLight = g.addResource("dome_light", &t.dome);
        f.rDomeAux = g.addResource("dome_aux", &t.domeAux);
        writes.push_back({f.rDomeLight, Use::ColorWrite});
        writes.push_back({f.rDomeAux, Use::ColorWrite});
        if (ms) {
            writes.push_back({rDomeMs, Use::ColorWrite});
            writes.push_back({rDomeAuxMs, Use::ColorWrite});
        }
    }
    std::vector<ResourceUse> reads = {{f.rShadow, Use::Sampled}};
    if (f.rDomeMaps >= 0) reads.push_back({f.rDomeMaps, Use::Sampled});
    if (f.rProbe >= 0) reads.push_back({f.rProbe, Use::Sampled});
    if (f.rBounceSh >= 0) reads.push_back({f.rBounceSh, Use::Sampled});
    if (f.rBounceFaces >= 0) reads.push_back({f.rBounceFaces, Use::Sampled});
    if (f.rBounceDepth >= 0) reads.push_back({f.rBounceDepth, Use::Sampled});
    if (f.rBounceRadiance >= 0) reads.push_back({f.rBounceRadiance, Use::Sampled});

    g.addPass(
        {"forward", reads, writes, [&f, ms, keepDepth](VkCommandBuffer cmd) {
             RenderTargets& t = f.targets;
             std::vector<VkRenderingAttachmentInfo> colors;
             auto color = [&](VkImageView view, const glm::vec4& clear) {
                 colors.push_back(clearedColor(view, clear));
             };
             color(ms ? t.hdrMs.view() : t.hdr.view(), glm::vec4(f.scene.background(), 1.0f));
             if (ms)
                 resolveInto(colors.back(), t.hdr.view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                             VK_RESOLVE_MODE_AVERAGE_BIT);
             if (f.debug) { // background: not covered, not shadowed (never multisampled)
                 color(t.position.view(), glm::vec4(0.0f));
                 color(t.normal.view(), gpu::NO_SURFACE_NORMAL);
                 color(t.surface.view(), glm::vec4(0.0f));
                 color(t.albedo.view(), glm::vec4(0.0f));
             }
             if (f.domeBlur) { // no surface: no light to darken, nothing occluded, floor 1
                 color(ms ? t.domeMs.view() : t.dome.view(), glm::vec4(0.0f));
                 if (ms)
                     resolveInto(colors.back(), t.dome.view(),
                                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                 VK_RESOLVE_MODE_AVERAGE_BIT);
                 color(ms ? t.domeAuxMs.view() : t.domeAux.view(), gpu::NO_SURFACE_DOME_AUX);
                 if (ms)
                     resolveInto(colors.back(), t.domeAux.view(),
                                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                 VK_RESOLVE_MODE_AVERAGE_BIT);
             }
             VkRenderingAttachmentInfo depth =
                 clearedDepth(ms ? t.depthMs.view() : t.depth.view(), keepDepth);
             if (ms)
                 resolveInto(depth, t.depth.view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                             VK_RESOLVE_MODE_SAMPLE_ZERO_BIT);
             VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
             info.renderArea = {{0, 0}, {t.width, t.height}};
             info.layerCount = 1;
             info.colorAttachmentCount = uint32_t(colors.size());
             info.pColorAttachments = colors.data();
             info.pDepthAttachment = &depth;
             f.ctx.fn().cmdBeginRendering(cmd, &info);
             setViewport(cmd, t.width, t.height);
             VkPipeline bound = VK_NULL_HANDLE;
             const uint32_t features = frameFeatures(f.data);
             for (const Draw& d : f.data.draws) {
                 if (d.mesh->indexCount == 0) continue; // e.g. a cloth torn to pieces
                 const VkPipeline p =
                     f.pipes.forwardFor(f.debug, f.domeBlur, d.mirrored, d.twoSided, f.samples,
                                        features, materialFeatures(f.data, d.instance));
                 if (p != bound) {
                     vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound = p);
                     vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                             f.pipes.sceneLayout, 0, 1, &f.sets.frame, 0, nullptr);
                 }
                 vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.pipes.sceneLayout,
                                         1, 1, &d.material, 0, nullptr);
                 vkCmdPushConstants(cmd, f.pipes.sceneLayout, vk::kGraphicsStages, 0,
                                    sizeof(uint32_t), &d.instance);
                 drawMesh(cmd, *d.mesh);
             }
             // The background image (AR: the camera frame) or the environment, last: at the far
             // plane (a viewport of depth 1 to 1) where the depth test finds nothing drawn, so
             // that a GPU's early depth test leaves the covered pixels unshaded. Under everything
             // as a pass of its own it cost 1.18 of the demo's 7.93 GPU ms at 1080p on an H200.
             if (f.background) {
                 vkCmdBindPipeline(
                     cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                     f.pipes.backgroundFor(f.data.frame, true, f.samples, f.debug, f.domeBlur));
                 vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.pipes.sceneLayout,
                                         0, 1, &f.sets.frame, 0, nullptr);
                 const VkViewport far{0.0f, 0.0f, float(t.width), float(t.height), 1.0f, 1.0f};
                 vkCmdSetViewport(cmd, 0, 1, &far);
                 vkCmdDraw(cmd, 3, 1, 0, 0);
             }
             f.ctx.fn().cmdEndRendering(cmd);
         }});
}

} // namespace weft::render
