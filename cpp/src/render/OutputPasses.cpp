// The end of a frame: the output pass (exposure, tone mapping and sRGB encoding of the linear
// hdr image into the 8-bit target), readback copies of what the caller asked for, and the
// hand-over to the presentation engine.
#include <cmath>

#include "render/FrameOverlay.h"
#include "render/FramePasses.h"
#include "render/GpuTypes.h"
#include "render/PassSetup.h"
#include "render/RenderTargets.h"
#include "render/RendererImpl.h"
#include "render/ScenePipelines.h"

namespace weft::render {

void drawFullscreen(const FramePassContext& f, VkCommandBuffer cmd, VkImageView target,
                    VkAttachmentLoadOp load, VkPipeline pipeline, VkPipelineLayout layout,
                    VkDescriptorSet set, const void* push, uint32_t pushBytes) {
    drawFullscreen(f, cmd, target, f.targets.width, f.targets.height, load, pipeline, layout, set,
                   push, pushBytes);
}

void beginColorTarget(const FramePassContext& f, VkCommandBuffer cmd, VkImageView target,
                      uint32_t w, uint32_t h, VkAttachmentLoadOp load) {
    VkRenderingAttachmentInfo a =
        attachment(target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, false);
    a.loadOp = load;
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {w, h}};
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &a;
    f.ctx.fn().cmdBeginRendering(cmd, &info);
    setViewport(cmd, w, h);
}

void drawFullscreen(const FramePassContext& f, VkCommandBuffer cmd, VkImageView target, uint32_t w,
                    uint32_t h, VkAttachmentLoadOp load, VkPipeline pipeline,
                    VkPipelineLayout layout, VkDescriptorSet set, const void* push,
                    uint32_t pushBytes) {
    beginColorTarget(f, cmd, target, w, h, load);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
    if (pushBytes) vkCmdPushConstants(cmd, layout, vk::kGraphicsStages, 0, pushBytes, push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    f.ctx.fn().cmdEndRendering(cmd);
}

void addOutputPasses(FrameGraph& g, FramePassContext& f) {
    RenderTargets& t = f.targets;
    const VkPipeline pipeline =
        f.pipes.outputPipeline(f.ldr->desc().format, uint32_t(f.settings.toneMap));
    const OutputPush push{
        glm::vec4(std::exp2(f.settings.exposure), float(f.settings.toneMap), 0, 0)};
    g.addPass({"output",
               {{f.rHdr, Use::Sampled}},
               {{f.rLdr, Use::ColorWrite}},
               [&f, pipeline, push](VkCommandBuffer cmd) {
                   drawFullscreen(f, cmd, f.ldr->view(), VK_ATTACHMENT_LOAD_OP_DONT_CARE, pipeline,
                                  f.pipes.outputLayout, f.sets.output, &push, sizeof(push));
               }});
    if (f.overlay) f.overlay->addPasses(g, f); // over the tone-mapped image (FrameOverlay.h)

    // Readback copies: colour (ldr), linear (hdr), debug images.
    std::vector<std::pair<int, vk::Image*>> copies;
    if (f.outputs & OutputColor) copies.push_back({f.rLdr, f.ldr});
    if (f.outputs & OutputLinear) copies.push_back({f.rHdr, &t.hdr});
    if (f.debug) {
        vk::Image* images[4] = {&t.position, &t.normal, &t.surface, &t.albedo};
        for (int i = 0; i < 4; ++i) copies.push_back({f.rDebug[i], images[i]});
    }
    if (!copies.empty()) {
        std::vector<ResourceUse> reads;
        for (auto& [r, im] : copies) reads.push_back({r, Use::TransferRead});
        g.addPass({"readback",
                   reads,
                   {},
                   [&f, copies](VkCommandBuffer cmd) {
                       for (auto& [r, im] : copies) {
                           vk::Buffer& dst = f.targets.readbackFor(f.ctx, im);
                           VkBufferImageCopy region{};
                           region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                           region.imageExtent = {f.targets.width, f.targets.height, 1};
                           vkCmdCopyImageToBuffer(cmd, im->get(),
                                                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.get(),
                                                  1, &region);
                       }
                   },
                   true});
    }
    if (f.present)
        g.addPass({"present", {{f.rLdr, Use::Present}}, {}, [](VkCommandBuffer) {}, true});
}

} // namespace weft::render
