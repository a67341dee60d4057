// One bounce of diffuse light (BounceProbes.h): each caster's cube capture of the receivers,
// where its texels lie as seen from the caster's points (bounce_geometry.frag, once), then one
// pass projecting every capture onto SH9 at those points (bounce_sh.frag); twice, the second
// round's receivers lit by the first round's casters. The forward pass reads the second.
#include "render/BounceProbes.h"
#include "render/FramePasses.h"
#include "render/PassSetup.h"
#include "render/RendererImpl.h"

namespace weft::render {

// The casters' radiance as proxy spheres (bounce_radiance.frag) from the SH9 `rSh` into `out`
// (resource `rOut`), drawn with frame set `set` (whose own binding of `out` it does not read).
static void addRadiancePass(FrameGraph& g, FramePassContext& f, const char* name, int rSh, int rOut,
                            vk::Image& out, VkDescriptorSet set) {
    g.addPass({name,
               {{rSh, Use::Sampled}, {f.rShadow, Use::Sampled}},
               {{rOut, Use::ColorWrite}},
               [&f, &out, set](VkCommandBuffer cmd) {
                   drawFullscreen(f, cmd, out.view(), BounceProbes::kRadianceColumns,
                                  f.bounce.count(), VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                  f.pipes.bounceRadiance.get(), f.pipes.sceneLayout, set, nullptr,
                                  0);
               }});
}

// A pass over the probes' points into `out` (`width` columns): bounce_geometry.frag (a column
// per capture texel) or bounce_sh.frag (per coefficient); one draw per probe over its kPoints
// rows, its centre and extents pushed.
static void drawPerPoint(FramePassContext& f, VkCommandBuffer cmd, vk::Image& out,
                         VkPipeline pipeline, uint32_t w) {
    const BounceProbes& b = f.bounce;
    const uint32_t h = b.count() * BounceProbes::kPoints;
    beginColorTarget(f, cmd, out.view(), w, h, VK_ATTACHMENT_LOAD_OP_DONT_CARE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.pipes.bounceShLayout, 0, 1,
                            &f.sets.bounceSh, 0, nullptr);
    for (uint32_t p = 0; p < b.count(); ++p) {
        const uint32_t y = p * BounceProbes::kPoints;
        VkViewport vp{0.0f, float(y), float(w), float(BounceProbes::kPoints), 0.0f, 1.0f};
        VkRect2D sc{{0, int32_t(y)}, {w, BounceProbes::kPoints}};
        vkCmdSetViewport(cmd, 0, 1, &vp);
        vkCmdSetScissor(cmd, 0, 1, &sc);
        const BounceShPush push{
            glm::vec4(f.data.frame.environment.x, float(BounceProbes::kFaceSize), float(p), 0.0f),
            glm::vec4(b.position(p), 0.0f), glm::vec4(b.half(p), 0.0f)};
        vkCmdPushConstants(cmd, f.pipes.bounceShLayout, vk::kGraphicsStages, 0, sizeof(push),
                           &push);
        vkCmdDraw(cmd, 3, 1, 0, 0);
    }
    f.ctx.fn().cmdEndRendering(cmd);
}

void addBouncePasses(FrameGraph& g, FramePassContext& f) {
    BounceProbes& b = f.bounce;
    if (b.count() == 0) return;
    f.rBounceSh = g.addResource("bounce_sh", &b.sh());
    // the captures themselves: what the casters' glossy reflections see of the receivers
    const int rFaces = f.rBounceFaces = g.addResource("bounce_faces", &b.faces());
    // ... and their depths: where a glossy caster's reflected ray meets the receivers
    const int rDepth = f.rBounceDepth = g.addResource("bounce_depth", &b.depth());
    // the casters' radiance, every frame with probes: the lights may move while captures stand
    f.rBounceRadiance = g.addResource("bounce_radiance", &b.radiance());
    if (!f.captureBounce) {
        f.reused.push_back("bounce");
        addRadiancePass(g, f, "bounce_radiance", f.rBounceSh, f.rBounceRadiance, b.radiance(),
                        f.sets.frame);
        return;
    }
    const int rGeometry = g.addResource("bounce_geometry", &b.geometry());
    const int rFirst = g.addResource("bounce_sh_first", &b.shFirst());
    const int rRadianceFirst = g.addResource("bounce_radiance_first", &b.radianceFirst());
    const uint32_t perRound = 6 * b.count();
    for (uint32_t round = 0; round < BounceProbes::kRounds; ++round) {
        const bool last = round + 1 == BounceProbes::kRounds;
        std::vector<ResourceUse> reads = {{f.rShadow, Use::Sampled}};
        if (f.rDomeMaps >= 0) reads.push_back({f.rDomeMaps, Use::Sampled});
        if (round > 0) { // the casters' light (first SH)
            reads.push_back({rFirst, Use::Sampled});
            reads.push_back({rRadianceFirst, Use::Sampled});
        }
        for (uint32_t i = 0; i < perRound; ++i) {
            const uint32_t set = round * perRound + i;
            g.addPass({"bounce" + std::to_string(round) + "[" + std::to_string(i / 6) + "][" +
                           std::to_string(i % 6) + "]",
                       reads,
                       {{rFaces, Use::ColorWrite}, {rDepth, Use::DepthWrite}},
                       [&f, i, set](VkCommandBuffer cmd) {
                           // the receivers alone, over alpha 0: the sky they leave uncovered
                           drawCaptureFace(
                               f, cmd, f.bounce.faces().layerView(i), f.bounce.depth().layerView(i),
                               true, BounceProbes::kFaceSize, f.sets.bounceFaces[set],
                               glm::vec4(0.0f), false,
                               [](const Draw& d, int) { return !d.castShadows; }, 0);
                       }});
        }
        if (round == 0) // the receivers stand as they stood: the second round's depths are these
            g.addPass({"bounce_geometry",
                       {{rDepth, Use::Sampled}},
                       {{rGeometry, Use::ColorWrite}},
                       [&f](VkCommandBuffer cmd) {
                           drawPerPoint(f, cmd, f.bounce.geometry(), f.pipes.bounceGeometry.get(),
                                        6 * BounceProbes::kFaceSize * BounceProbes::kFaceSize);
                       }});
        g.addPass({last ? "bounce_sh" : "bounce_sh_first",
                   {{rFaces, Use::Sampled}, {rGeometry, Use::Sampled}},
                   {{last ? f.rBounceSh : rFirst, Use::ColorWrite}},
                   [&f, last](VkCommandBuffer cmd) {
                       drawPerPoint(f, cmd, last ? f.bounce.sh() : f.bounce.shFirst(),
                                    f.pipes.bounceSh.get(), BounceProbes::kShColumns);
                   }});
        if (!last) // with a second round's set: its SH9 binding holds the first round's
            addRadiancePass(g, f, "bounce_radiance_first", rFirst, rRadianceFirst,
                            b.radianceFirst(), f.sets.bounceFaces[perRound]);
    }
    addRadiancePass(g, f, "bounce_radiance", f.rBounceSh, f.rBounceRadiance, b.radiance(),
                    f.sets.frame);
}

} // namespace weft::render
