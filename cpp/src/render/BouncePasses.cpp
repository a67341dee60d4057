// One bounce of diffuse light (BounceProbes.h): each caster's cube capture of the receivers,
// then one pass projecting every capture onto SH9 (bounce_sh.frag); twice, the second round's
// receivers lit by the first round's casters. The forward pass reads the second.
#include "render/BounceProbes.h"
#include "render/FramePasses.h"
#include "render/PassSetup.h"
#include "render/RendererImpl.h"

namespace weft::render {

void addBouncePasses(FrameGraph& g, FramePassContext& f) {
    BounceProbes& b = f.bounce;
    if (b.count() == 0) return;
    f.rBounceSh = g.addResource("bounce_sh", &b.sh());
    // the captures themselves: what the casters' glossy reflections see of the receivers
    const int rFaces = f.rBounceFaces = g.addResource("bounce_faces", &b.faces());
    if (!f.captureBounce) {
        f.reused.push_back("bounce");
        return;
    }
    const int rDepth = g.addResource("bounce_depth", &b.depth());
    const int rFirst = g.addResource("bounce_sh_first", &b.shFirst());
    // x: environment intensity (0: none), y: texels per face, z: probes
    const glm::vec4 push(f.data.frame.environment.x, float(BounceProbes::kFaceSize),
                         float(b.count()), 0.0f);
    const uint32_t perRound = 6 * b.count();
    for (uint32_t round = 0; round < BounceProbes::kRounds; ++round) {
        const bool last = round + 1 == BounceProbes::kRounds;
        std::vector<ResourceUse> reads = {{f.rShadow, Use::Sampled}};
        if (f.rDomeMaps >= 0) reads.push_back({f.rDomeMaps, Use::Sampled});
        if (round > 0) reads.push_back({rFirst, Use::Sampled}); // the casters' light (first SH)
        for (uint32_t i = 0; i < perRound; ++i) {
            const uint32_t set = round * perRound + i;
            g.addPass({"bounce" + std::to_string(round) + "[" + std::to_string(i / 6) + "][" +
                           std::to_string(i % 6) + "]",
                       reads, {{rFaces, Use::ColorWrite}, {rDepth, Use::DepthWrite}},
                       [&f, i, set](VkCommandBuffer cmd) {
                           // the receivers alone, over alpha 0: the sky they leave uncovered
                           drawCaptureFace(f, cmd, f.bounce.faces().layerView(i),
                                           f.bounce.depth().view(), BounceProbes::kFaceSize,
                                           f.sets.bounceFaces[set], glm::vec4(0.0f), false,
                                           [](const Draw& d, int) { return !d.castShadows; }, 0);
                       }});
        }
        g.addPass({last ? "bounce_sh" : "bounce_sh_first", {{rFaces, Use::Sampled}},
                   {{last ? f.rBounceSh : rFirst, Use::ColorWrite}},
                   [&f, push, last](VkCommandBuffer cmd) { // one fragment per coefficient, probe
                       vk::Image& out = last ? f.bounce.sh() : f.bounce.shFirst();
                       drawFullscreen(f, cmd, out.view(), BounceProbes::kShColumns,
                                      f.bounce.count(), VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                      f.pipes.bounceSh.get(), f.pipes.bounceShLayout,
                                      f.sets.bounceSh, &push, sizeof(push));
                   }});
    }
}

} // namespace weft::render
