// The dynamic reflection capture: six cube faces of everything but the probe's own instance,
// shaded like the forward pass with the face's descriptor set.
#include "render/FramePasses.h"
#include "render/GpuCache.h"
#include "render/PassSetup.h"
#include "render/ReflectionProbe.h"
#include "render/RendererImpl.h"

namespace weft::render {

void drawCaptureFace(const FramePassContext& f, VkCommandBuffer cmd, VkImageView color,
                     VkImageView depth, bool keepDepth, uint32_t size, VkDescriptorSet faceSet,
                     const glm::vec4& clear, bool background, bool (*include)(const Draw&, int),
                     int arg) {
    const VkRenderingAttachmentInfo colorInfo = clearedColor(color, clear);
    const VkRenderingAttachmentInfo depthInfo = clearedDepth(depth, keepDepth);
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {size, size}};
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &colorInfo;
    info.pDepthAttachment = &depthInfo;
    f.ctx.fn().cmdBeginRendering(cmd, &info);
    setViewport(cmd, size, size);
    if (background) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                          f.pipes.backgroundFor(f.data.frame, false));
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.pipes.sceneLayout, 0, 1,
                                &faceSet, 0, nullptr);
        vkCmdDraw(cmd, 3, 1, 0, 0);
    }
    VkPipeline bound = VK_NULL_HANDLE;
    const uint32_t features = frameFeatures(f.data);
    for (const Draw& d : f.data.draws) {
        if (d.mesh->indexCount == 0 || d.phantom || !include(d, arg)) continue;
        // cube faces mirror the view: the winding flips
        const VkPipeline p = f.pipes.forwardFor(false, false, !d.mirrored, d.twoSided, 1, features,
                                                materialFeatures(f.data, d.instance));
        if (p != bound) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound = p);
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.pipes.sceneLayout, 0, 1,
                                    &faceSet, 0, nullptr);
        }
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.pipes.sceneLayout, 1, 1,
                                &d.material, 0, nullptr);
        vkCmdPushConstants(cmd, f.pipes.sceneLayout, vk::kGraphicsStages, 0, sizeof(uint32_t),
                           &d.instance);
        drawMesh(cmd, *d.mesh);
    }
    f.ctx.fn().cmdEndRendering(cmd);
}

void addProbePasses(FrameGraph& g, FramePassContext& f) {
    if (f.probe.instance() < 0) return;
    f.rProbe = g.addResource("probe", &f.probe.cube());
    if (!f.captureProbe) {
        f.reused.push_back("probe");
        return;
    }
    const int probeDepth = g.addResource("probe_depth", &f.probe.depth());
    std::vector<ResourceUse> reads = {{f.rShadow, Use::Sampled}};
    if (f.rDomeMaps >= 0) reads.push_back({f.rDomeMaps, Use::Sampled});
    for (uint32_t face = 0; face < 6; ++face) {
        g.addPass({"probe[" + std::to_string(face) + "]",
                   reads,
                   {{f.rProbe, Use::ColorWrite}, {probeDepth, Use::DepthScratch}},
                   [&f, face](VkCommandBuffer cmd) {
                       ReflectionProbe& probe = f.probe;
                       // everything but the probe's own instance
                       drawCaptureFace(
                           f, cmd, probe.cube().layerView(face), probe.depth().view(), false,
                           probe.cube().desc().width, f.sets.faces[face],
                           glm::vec4(f.scene.background(), 1.0f), f.data.frame.sky.x > 0.5f,
                           [](const Draw& d, int skip) { return int(d.instance) != skip; },
                           probe.instance());
                   }});
    }
}

} // namespace weft::render
