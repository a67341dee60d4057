// Shadow-map passes: one per view of every shadow-casting scene light (skipped while the maps
// still hold exactly these views of these casters) and one per dome light due this frame. While
// some casters move and others stand still (a cloth over a terrain), the still ones are drawn
// once into their own maps, copied in every frame, and only the moving ones drawn over them.
#include "render/DomeShadows.h"
#include "render/FramePasses.h"
#include "render/HairPasses.h"
#include "render/PassSetup.h"
#include "render/ScenePipelines.h"

namespace weft::render {

void drawMesh(VkCommandBuffer cmd, const MeshGpu& mesh) {
    const VkDeviceSize offset = 0;
    const VkBuffer vertices = mesh.vertices.get();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
    vkCmdBindIndexBuffer(cmd, mesh.indices.get(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, mesh.indexCount, 1, 0, 0, 0);
}

void drawCasters(const FramePassContext& f, VkCommandBuffer cmd, VkImageView view, uint32_t size,
                 const glm::mat4& viewProj, bool withHair, Casters which, bool clear) {
    VkRenderingAttachmentInfo depth = clearedDepth(view);
    if (!clear) depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    // a draw is in the set `which` asks for
    auto wanted = [&](bool moved) {
        return which == Casters::All || moved == (which == Casters::Moving);
    };
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {size, size}};
    info.layerCount = 1;
    info.pDepthAttachment = &depth;
    f.ctx.fn().cmdBeginRendering(cmd, &info);
    setViewport(cmd, size, size);
    VkPipeline bound = VK_NULL_HANDLE;
    for (size_t i = 0; i < f.data.draws.size(); ++i) {
        const Draw& d = f.data.draws[i];
        if (!d.castShadows || d.mesh->indexCount == 0) continue;
        if (!wanted(i < f.moving.size() && f.moving[i])) continue;
        const VkPipeline p =
            d.alphaCutoff > 0.0f ? f.pipes.shadowAlpha.get() : f.pipes.shadow.get();
        if (p != bound) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound = p);
        if (d.alphaCutoff > 0.0f)
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.pipes.shadowLayout, 0,
                                    1, &d.material, 0, nullptr);
        const ShadowPush push{viewProj * d.model, d.alphaCutoff};
        vkCmdPushConstants(cmd, f.pipes.shadowLayout,
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        drawMesh(cmd, *d.mesh);
    }
    if (f.hair && withHair && wanted(f.hairMoving)) f.hair->drawDepth(cmd, viewProj);
    f.ctx.fn().cmdEndRendering(cmd);
}

void addShadowPasses(FrameGraph& g, FramePassContext& f) {
    f.rShadow = g.addResource("shadow_maps", &f.shadowMaps);
    if (f.splitShadows && !f.reuseShadows) { // the still casters' depth copied in first
        const int rStill = g.addResource("still_shadows", &f.stillShadows);
        for (const ShadowView& s : f.data.shadowViews) {
            const std::string name = "shadow_still[" + std::to_string(s.layer) + "]";
            if (!f.drawStill) { // it holds these casters in these views
                f.reused.push_back(name);
                continue;
            }
            g.addPass({name, {}, {{rStill, Use::DepthWrite}}, [&f, s](VkCommandBuffer cmd) {
                           drawCasters(f, cmd, f.stillShadows.layerView(uint32_t(s.layer)),
                                       f.settings.shadowMapSize, s.frustum.viewProj, true,
                                       Casters::Still);
                       }});
        }
        g.addPass({"shadow_copy",
                   {{rStill, Use::TransferRead}},
                   {{f.rShadow, Use::TransferWrite}},
                   [&f](VkCommandBuffer cmd) {
                       const uint32_t size = f.settings.shadowMapSize;
                       VkImageCopy region{};
                       region.srcSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0,
                                                uint32_t(f.data.shadowViews.size())};
                       region.dstSubresource = region.srcSubresource;
                       region.extent = {size, size, 1};
                       vkCmdCopyImage(cmd, f.stillShadows.get(),
                                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, f.shadowMaps.get(),
                                      VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
                   }});
    }
    for (const ShadowView& s : f.data.shadowViews) {
        std::string name = "shadow[" + std::to_string(s.lightIndex) + "]";
        if (f.scene.lights()[size_t(s.lightIndex)].index() == 1) // a point light's six views
            name += "." + std::to_string(s.layer - f.shadowInfos[size_t(s.lightIndex)].layer);
        if (f.reuseShadows) { // the map already holds exactly this view of these casters
            f.reused.push_back(std::move(name));
            continue;
        }
        g.addPass({name, {}, {{f.rShadow, Use::DepthWrite}}, [&f, s](VkCommandBuffer cmd) {
                       // over the still casters' depth, the moving ones; or every caster
                       const bool split = f.splitShadows;
                       drawCasters(f, cmd, f.shadowMaps.layerView(uint32_t(s.layer)),
                                   f.settings.shadowMapSize, s.frustum.viewProj, true,
                                   split ? Casters::Moving : Casters::All, !split);
                   }});
    }
}

void addDomePasses(FrameGraph& g, FramePassContext& f) {
    if (!f.dome.active()) return;
    const std::vector<GpuDomeLight>& lights = f.dome.lights();
    f.rDomeMaps = g.addResource("dome_maps", &f.dome.maps());
    std::vector<uint8_t> due(lights.size(), 0);
    for (int i : f.domeDue) due[size_t(i)] = 1;
    for (size_t i = 0; i < lights.size(); ++i) {
        std::string name = "dome[" + std::to_string(i) + "]";
        if (!due[i]) {
            f.reused.push_back(std::move(name));
            continue;
        }
        g.addPass({name, {}, {{f.rDomeMaps, Use::DepthWrite}}, [&f, i](VkCommandBuffer cmd) {
                       drawCasters(f, cmd, f.dome.maps().layerView(uint32_t(i)), f.dome.mapSize(),
                                   f.dome.lights()[i].viewProj, true);
                   }});
    }
}

} // namespace weft::render
