// The dome's shadows blurred (rows, then columns, depth-aware), times the diffuse light they
// darken, added to the colour (SPEC §4.5). First the gather pass turns the forward pass's dome
// outputs into the visibility per pixel (combining the interleaved quarters of the dome's
// lights). Only when the scene's environment (or the ambient occlusion setting, for a dome over
// the ambient) asks for a blur.
#include "render/FramePasses.h"
#include "render/GpuTypes.h"
#include "render/RenderTargets.h"
#include "render/RendererImpl.h"
#include "render/ScenePipelines.h"

namespace weft::render {

void addDomeBlurPasses(FrameGraph& g, FramePassContext& f) {
    if (!f.domeBlur) return;
    const DomeBlurPush push{
        glm::vec4(f.dome.blurRadius(), f.camera.zNear, f.camera.zFar, f.dome.blurDepthTolerance()),
        glm::vec4(f.data.frame.options.z > 1.5f ? 1.0f : 0.0f,
                  f.dome.occludesAmbient() ? 1.0f : 0.0f, 0.0f, 0.0f)};
    const int rVisibility = g.addResource("dome_visibility", &f.targets.domeVisibility);
    const int rRows = g.addResource("dome_rows", &f.targets.domeRows);
    auto fullscreen = [&f, push](const char* name, std::vector<ResourceUse> reads, int write,
                                 vk::Image* target, VkAttachmentLoadOp load,
                                 const vk::Pipeline* pipeline, const VkDescriptorSet* set) {
        return Pass{name,
                    std::move(reads),
                    {{write, Use::ColorWrite}},
                    [&f, push, target, load, pipeline, set](VkCommandBuffer cmd) {
                        drawFullscreen(f, cmd, target->view(), load, pipeline->get(),
                                       f.pipes.domeBlurLayout, *set, &push, sizeof(push));
                    }};
    };
    g.addPass(fullscreen(
        "dome_gather",
        {{f.rDomeLight, Use::Sampled}, {f.rDepth, Use::Sampled}, {f.rDomeAux, Use::Sampled}},
        rVisibility, &f.targets.domeVisibility, VK_ATTACHMENT_LOAD_OP_DONT_CARE,
        &f.pipes.domeGather, &f.sets.domeGather));
    g.addPass(fullscreen("dome_blur_x", {{rVisibility, Use::Sampled}}, rRows, &f.targets.domeRows,
                         VK_ATTACHMENT_LOAD_OP_DONT_CARE, &f.pipes.domeBlurRows, &f.sets.domeRows));
    g.addPass(fullscreen("dome_blur", {{f.rDomeLight, Use::Sampled}, {rRows, Use::Sampled}}, f.rHdr,
                         &f.targets.hdr, VK_ATTACHMENT_LOAD_OP_LOAD, &f.pipes.domeBlur,
                         &f.sets.domeBlur));
}

} // namespace weft::render
