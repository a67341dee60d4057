// Shadow-map passes: one per view of every shadow-casting scene light (skipped while the maps
// still hold exactly these views of these casters) and one per dome light due this frame.
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
                 const glm::mat4& viewProj, bool withHair) {
    const VkRenderingAttachmentInfo depth = clearedDepth(view);
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {size, size}};
    info.layerCount = 1;
    info.pDepthAttachment = &depth;
    f.ctx.fn().cmdBeginRendering(cmd, &info);
    setViewport(cmd, size, size);
    VkPipeline bound = VK_NULL_HANDLE;
    for (const Draw& d : f.data.draws) {
        if (!d.castShadows || d.mesh->indexCount == 0) continue;
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
    if (f.hair && withHair) f.hair->drawDepth(cmd, viewProj);
    f.ctx.fn().cmdEndRendering(cmd);
}

void addShadowPasses(FrameGraph& g, FramePassContext& f) {
    f.rShadow = g.addResource("shadow_maps", &f.shadowMaps);
    for (const ShadowView& s : f.data.shadowViews) {
        std::string name = "shadow[" + std::to_string(s.lightIndex) + "]";
        if (f.scene.lights()[size_t(s.lightIndex)].index() == 1) // a point light's six views
            name += "." + std::to_string(s.layer - f.shadowInfos[size_t(s.lightIndex)].layer);
        if (f.reuseShadows) { // the map already holds exactly this view of these casters
            f.reused.push_back(std::move(name));
            continue;
        }
        g.addPass({name, {}, {{f.rShadow, Use::DepthWrite}}, [&f, s](VkCommandBuffer cmd) {
                       drawCasters(f, cmd, f.shadowMaps.layerView(uint32_t(s.layer)),
                                   f.settings.shadowMapSize, s.frustum.viewProj, true);
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
