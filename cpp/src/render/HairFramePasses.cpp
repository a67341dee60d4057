// The hair module's place in a frame: HairPasses adds its DOM, hair and OIT passes after the
// forward pass (and the dome blur), drawing into the resolved hdr and depth targets.
#include "render/FramePasses.h"
#include "render/HairPasses.h"
#include "render/RenderTargets.h"
#include "render/RendererImpl.h"

namespace weft::render {

void addHairPasses(FrameGraph& g, FramePassContext& f) {
    if (!f.hair) return;
    RenderTargets& t = f.targets;
    f.hair->addPasses(
        g, {f.rShadow,
            f.rDepth,
            f.rHdr,
            f.debug ? f.rDebug : nullptr,
            &t.hdr,
            &t.depth,
            {&t.position, &t.normal, &t.surface, &t.albedo},
            f.sets.frame,
            [&f](VkCommandBuffer cmd, VkImageView view, uint32_t size, const glm::mat4& viewProj) {
                drawCasters(f, cmd, view, size, viewProj, false);
            },
            &f.reused});
}

} // namespace weft::render
