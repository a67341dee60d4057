// The dome's shadows blurred (rows, then columns, depth-aware), times the diffuse light they
// darken, added to the colour (SPEC §4.5). Only when the scene's environment (or the ambient
// occlusion setting, for a dome over the ambient) asks for a blur.
#include "render/FramePasses.h"
#include "render/GpuTypes.h"
#include "render/RenderTargets.h"
#include "render/RendererImpl.h"
#include "render/ScenePipelines.h"

namespace weft::render {

void addDomeBlurPasses(FrameGraph& g, FramePassContext& f) {
    if (!f.domeBlur) return;
    const DomeBlurPush push{
        glm::vec4(f.dome.blurRadius(), f.camera.zNear, f.camera.zFar, f.dome.blurDepthTolerance())};
    const int rRows = g.addResource("dome_rows", &f.targets.domeRows);
    g.addPass({"dome_blur_x",
               {{f.rDomeLight, Use::Sampled}, {f.rDepth, Use::Sampled}},
               {{rRows, Use::ColorWrite}},
               [&f, push](VkCommandBuffer cmd) {
                   drawFullscreen(f, cmd, f.targets.domeRows.view(),
                                  VK_ATTACHMENT_LOAD_OP_DONT_CARE, f.pipes.domeBlurRows.get(),
                                  f.pipes.domeBlurLayout, f.sets.domeRows, &push, sizeof(push));
               }});
    g.addPass({"dome_blur",
               {{f.rDomeLight, Use::Sampled}, {rRows, Use::Sampled}},
               {{f.rHdr, Use::ColorWrite}},
               [&f, push](VkCommandBuffer cmd) {
                   drawFullscreen(f, cmd, f.targets.hdr.view(), VK_ATTACHMENT_LOAD_OP_LOAD,
                                  f.pipes.domeBlur.get(), f.pipes.domeBlurLayout, f.sets.domeBlur,
                                  &push, sizeof(push));
               }});
}

} // namespace weft::render
