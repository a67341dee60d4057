// One frame of a Renderer: its data (uploaded, and its descriptor sets written, by
// FrameDescriptors.cpp) and the frame graph of passes (shadow views, dome maps, reflection
// capture, background, forward shading, dome blur, hair, sRGB output, readback or present),
// recorded into the frame slot's command buffer.
#include "render/RendererImpl.h"

namespace weft {

using render::Draw;
using render::FrameData;
using render::FrameGraph;
using render::ShadowView;
using render::ResourceUse;
using render::Use;
using render::FrameSlot;
using render::kFrameSets;
using render::kFramesInFlight;

namespace {

// Everything a shadow map's contents depend on besides its view: every caster's geometry,
// transform and alpha test (hair: its strands object, which is immutable, and transform).
std::vector<uint64_t> casterKey(const render::FrameData& data, const Scene& scene) {
    std::vector<uint64_t> key;
    auto put = [&](const void* p, size_t bytes) {
        const size_t at = key.size();
        key.resize(at + (bytes + 7) / 8, 0);
        std::memcpy(key.data() + at, p, bytes);
    };
    for (const render::Draw& d : data.draws) {
        if (!d.castShadows) continue;
        key.push_back(d.mesh->contentId);
        put(&d.model, sizeof(glm::mat4));
        put(&d.alphaCutoff, sizeof(float));
        if (d.alphaCutoff > 0.0f) put(&d.material, sizeof(d.material));
    }
    for (const HairInstance& h : scene.hairs()) {
        if (!h.castShadows) continue;
        const HairStrands* strands = h.strands.get();
        put(&strands, sizeof(strands));
        key.push_back(h.strands->points.size());
        put(&h.transform, sizeof(glm::mat4));
    }
    return key;
}

// The light views plus the casters: equal keys mean the scene lights' maps can be reused.
std::vector<uint64_t> shadowKey(const render::FrameData& data, const std::vector<uint64_t>& casters) {
    std::vector<uint64_t> key;
    for (const render::ShadowView& v : data.shadowViews) {
        const size_t at = key.size();
        key.resize(at + sizeof(glm::mat4) / 8);
        std::memcpy(key.data() + at, &v.frustum.viewProj, sizeof(glm::mat4));
    }
    key.insert(key.end(), casters.begin(), casters.end());
    return key;
}

void drawMesh(VkCommandBuffer cmd, const render::MeshGpu& mesh) {
    const VkDeviceSize offset = 0;
    const VkBuffer vertices = mesh.vertices.get();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
    vkCmdBindIndexBuffer(cmd, mesh.indices.get(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, mesh.indexCount, 1, 0, 0, 0);
}



} // namespace

void Renderer::Impl::recordFrame(FrameSlot& slot, const Scene& scene, const Camera& camera,
                                 uint32_t outputs, vk::Image* ldr, bool present) {
    vk::Context& c = *ctx;
    const bool debug = outputs & OutputDebug;
    const float aspect = float(targets.width) / float(targets.height);

    FrameData data = buildFrameData(scene, camera, settings, aspect, *cache);
    double environmentBakeMs = 0.0;
    const bool environmentBaked = environment.prepare(scene.environment(), environmentBakeMs);
    environment.fillFrame(scene.environment(), data.frame);
    shadowInfos = data.shadowInfos;
    if (!data.shadowViews.empty()) ensureShadowMaps(uint32_t(data.shadowViews.size()));
    const std::vector<uint64_t> casters = casterKey(data, scene);
    std::vector<uint64_t> key = shadowKey(data, casters);
    const std::vector<int> domeRender = dome.prepare(scene, settings, casters, frameCounter);
    const std::vector<render::GpuDomeLight>& domeLights = dome.lights();
    data.frame.environment.z = float(domeLights.size());
    data.frame.environment.w = float(dome.mapSize());
    // The dome's diffuse light goes through the blur pass (SPEC §4.5) when a blur is asked for.
    const bool domeBlur = dome.active() && scene.environment().domeBlur > 0.0f;
    data.frame.options.z = domeBlur ? 1.0f : 0.0f;
    const bool background = scene.backgroundImage() != nullptr;
    data.frame.options.w = background ? 1.0f : 0.0f;
    data.frame.viewport = glm::vec4(1.0f / float(targets.width), 1.0f / float(targets.height), 0, 0);
    const bool captureProbe = probe.prepare(scene, data, settings.probeSize);
    const bool hasProbe = probe.instance() >= 0;
    const bool reuseShadows = settings.reuseShadowMaps && !data.shadowViews.empty() &&
                              key == shadowSignature;
    shadowSignature = std::move(key);
    const std::vector<Draw>& draws = data.draws;
    const std::vector<ShadowView>& shadowViews = data.shadowViews;
    const bool hasHair = !scene.hairs().empty();
    if (hasHair) {
        if (!hair) hair = std::make_unique<render::HairPasses>(c, pipes);
        hair->prepare(uint32_t(frameCounter % kFramesInFlight), scene, camera, settings,
                      targets.width, targets.height);
    }

    uploadFrame(slot, data, captureProbe);
    const render::FrameSets sets = bindFrame(slot, scene, data, captureProbe, domeBlur);
    const VkDescriptorSet frameSet = sets.frame, outputSet = sets.output,
                          domeRowsSet = sets.domeRows, domeBlurSet = sets.domeBlur;
    vk::Image& shadowImage = shadowViews.empty() ? dummyShadow : shadowMaps;

    // ---- frame graph ----------------------------------------------------------------------
    FrameGraph g;
    const int rShadow = g.addResource("shadow_maps", &shadowImage);
    const int rDepth = g.addResource("depth", &targets.depth);
    const int rHdr = g.addResource("hdr", &targets.hdr);
    const int rLdr = g.addResource("ldr", ldr);
    int rDebug[4] = {-1, -1, -1, -1};
    if (debug) {
        rDebug[0] = g.addResource("position", &targets.position);
        rDebug[1] = g.addResource("normal", &targets.normal);
        rDebug[2] = g.addResource("surface", &targets.surface);
        rDebug[3] = g.addResource("albedo", &targets.albedo);
    }
    // One full-screen triangle into a single colour target of the output's size.
    auto fullscreen = [&](VkCommandBuffer cmd, VkImageView target, VkAttachmentLoadOp load,
                          VkPipeline pipeline, VkPipelineLayout layout, VkDescriptorSet set,
                          const void* push, uint32_t pushBytes) {
        VkRenderingAttachmentInfo a = render::attachment(target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, false);
        a.loadOp = load;
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = {{0, 0}, {targets.width, targets.height}};
        info.layerCount = 1;
        info.colorAttachmentCount = 1;
        info.pColorAttachments = &a;
        c.fn().cmdBeginRendering(cmd, &info);
        render::setViewport(cmd, targets.width, targets.height);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
        if (pushBytes) vkCmdPushConstants(cmd, layout, vk::kGraphicsStages, 0, pushBytes, push);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        c.fn().cmdEndRendering(cmd);
    };

    // Depth of every shadow caster (meshes, alpha-tested ones with holes, hair) seen by viewProj.
    auto drawCasters = [&](VkCommandBuffer cmd, VkImageView view, uint32_t size,
                           const glm::mat4& viewProj, bool withHair) {
        const VkRenderingAttachmentInfo depth = render::clearedDepth(view);
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = {{0, 0}, {size, size}};
        info.layerCount = 1;
        info.pDepthAttachment = &depth;
        c.fn().cmdBeginRendering(cmd, &info);
        render::setViewport(cmd, size, size);
        VkPipeline bound = VK_NULL_HANDLE;
        for (const Draw& d : draws) {
            if (!d.castShadows || d.mesh->indexCount == 0) continue;
            const VkPipeline p = d.alphaCutoff > 0.0f ? pipes.shadowAlpha.get() : pipes.shadow.get();
            if (p != bound) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound = p);
            if (d.alphaCutoff > 0.0f)
                vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes.shadowLayout, 0, 1,
                                        &d.material, 0, nullptr);
            const render::ShadowPush push{viewProj * d.model, d.alphaCutoff};
            vkCmdPushConstants(cmd, pipes.shadowLayout,
                               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof(push), &push);
            drawMesh(cmd, *d.mesh);
        }
        if (hasHair && withHair) hair->drawDepth(cmd, viewProj);
        c.fn().cmdEndRendering(cmd);
    };

    std::vector<std::string> reused;
    if (scene.environment().environment && !environmentBaked) reused.push_back("environment");
    for (const ShadowView& s : shadowViews) {
        std::string name = "shadow[" + std::to_string(s.lightIndex) + "]";
        if (scene.lights()[size_t(s.lightIndex)].index() == 1) // a point light's six views
            name += "." + std::to_string(s.layer - shadowInfos[size_t(s.lightIndex)].layer);
        if (reuseShadows) { // the map already holds exactly this view of these casters
            reused.push_back(std::move(name));
            continue;
        }
        g.addPass({name, {}, {{rShadow, Use::DepthWrite}}, [&, s](VkCommandBuffer cmd) {
                       drawCasters(cmd, shadowMaps.layerView(uint32_t(s.layer)),
                                   settings.shadowMapSize, s.frustum.viewProj, true);
                   }});
    }
    // The environment's dome of shadow lights: the layers due this frame, the rest reused.
    int rDome = -1;
    if (dome.active()) {
        rDome = g.addResource("dome_maps", &dome.maps());
        std::vector<uint8_t> due(domeLights.size(), 0);
        for (int i : domeRender) due[size_t(i)] = 1;
        for (size_t i = 0; i < domeLights.size(); ++i) {
            std::string name = "dome[" + std::to_string(i) + "]";
            if (!due[i]) {
                reused.push_back(std::move(name));
                continue;
            }
            g.addPass({name, {}, {{rDome, Use::DepthWrite}}, [&, i](VkCommandBuffer cmd) {
                           drawCasters(cmd, dome.maps().layerView(uint32_t(i)), dome.mapSize(),
                                       domeLights[i].viewProj, true);
                       }});
        }
    }

    std::vector<ResourceUse> forwardWrites = {{rHdr, Use::ColorWrite}, {rDepth, Use::DepthWrite}};
    for (int r : rDebug)
        if (r >= 0) forwardWrites.push_back({r, Use::ColorWrite});
    // The dynamic reflection capture: six faces of everything but the probe's own instance.
    int rProbe = -1;
    if (hasProbe) {
        rProbe = g.addResource("probe", &probe.cube());
        if (!captureProbe) reused.push_back("probe");
    }
    if (captureProbe) {
        const int rProbeDepth = g.addResource("probe_depth", &probe.depth());
        std::vector<ResourceUse> faceReads = {{rShadow, Use::Sampled}};
        if (rDome >= 0) faceReads.push_back({rDome, Use::Sampled});
        for (uint32_t f = 0; f < 6; ++f) {
            const VkDescriptorSet faceSet = sets.faces[f];
            g.addPass({"probe[" + std::to_string(f) + "]", faceReads,
                       {{rProbe, Use::ColorWrite}, {rProbeDepth, Use::DepthWrite}},
                       [&, f, faceSet](VkCommandBuffer cmd) {
                           const uint32_t size = probe.cube().desc().width;
                           const VkRenderingAttachmentInfo color = render::clearedColor(
                               probe.cube().layerView(f), glm::vec4(scene.background(), 1.0f));
                           const VkRenderingAttachmentInfo depth =
                               render::clearedDepth(probe.depth().view(), false);
                           VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                           info.renderArea = {{0, 0}, {size, size}};
                           info.layerCount = 1;
                           info.colorAttachmentCount = 1;
                           info.pColorAttachments = &color;
                           info.pDepthAttachment = &depth;
                           c.fn().cmdBeginRendering(cmd, &info);
                           render::setViewport(cmd, size, size);
                           VkPipeline bound = VK_NULL_HANDLE;
                           for (const Draw& d : draws) {
                               if (d.mesh->indexCount == 0 || int(d.instance) == probe.instance() ||
                                   d.phantom)
                                   continue;
                               // cube faces mirror the view: the winding flips
                               const VkPipeline p = pipes.forwardFor(false, false, !d.mirrored, d.twoSided);
                               if (p != bound) {
                                   vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound = p);
                                   vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                                           pipes.sceneLayout, 0, 1, &faceSet, 0, nullptr);
                               }
                               vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                                       pipes.sceneLayout, 1, 1, &d.material, 0, nullptr);
                               vkCmdPushConstants(cmd, pipes.sceneLayout,
                                                  VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                                  0, sizeof(uint32_t), &d.instance);
                               drawMesh(cmd, *d.mesh);
                           }
                           c.fn().cmdEndRendering(cmd);
                       }});
        }
    }

    // The background image (AR: the camera frame) under everything the forward pass draws.
    if (background)
        g.addPass({"background", {}, {{rHdr, Use::ColorWrite}}, [&](VkCommandBuffer cmd) {
                       fullscreen(cmd, targets.hdr.view(), VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                  pipes.background.get(), pipes.sceneLayout, frameSet, nullptr, 0);
                   }});
    int rDomeLight = -1; // the forward pass's dome output for the blur
    if (domeBlur) {
        rDomeLight = g.addResource("dome_light", &targets.dome);
        forwardWrites.push_back({rDomeLight, Use::ColorWrite});
    }

    std::vector<ResourceUse> forwardReads = {{rShadow, Use::Sampled}};
    if (rDome >= 0) forwardReads.push_back({rDome, Use::Sampled});
    if (rProbe >= 0) forwardReads.push_back({rProbe, Use::Sampled});
    g.addPass({"forward", forwardReads, forwardWrites, [&](VkCommandBuffer cmd) {
                   std::vector<VkRenderingAttachmentInfo> colors;
                   auto color = [&](VkImageView view, const glm::vec4& clear) {
                       colors.push_back(render::clearedColor(view, clear));
                   };
                   color(targets.hdr.view(), glm::vec4(scene.background(), 1.0f));
                   if (background) colors.back().loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
                   if (debug) { // background: not covered, not shadowed
                       color(targets.position.view(), glm::vec4(0.0f));
                       color(targets.normal.view(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
                       color(targets.surface.view(), glm::vec4(0.0f));
                       color(targets.albedo.view(), glm::vec4(0.0f));
                   }
                   if (domeBlur) // a < 0: no surface
                       color(targets.dome.view(), glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));
                   // kept when hair tests against it or the dome blur reads it
                   const VkRenderingAttachmentInfo depth =
                       render::clearedDepth(targets.depth.view(), hasHair || domeBlur);
                   VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                   info.renderArea = {{0, 0}, {targets.width, targets.height}};
                   info.layerCount = 1;
                   info.colorAttachmentCount = uint32_t(colors.size());
                   info.pColorAttachments = colors.data();
                   info.pDepthAttachment = &depth;
                   c.fn().cmdBeginRendering(cmd, &info);
                   render::setViewport(cmd, targets.width, targets.height);
                   VkPipeline bound = VK_NULL_HANDLE;
                   for (const Draw& d : draws) {
                       if (d.mesh->indexCount == 0) continue; // e.g. a cloth torn to pieces
                       const VkPipeline p = pipes.forwardFor(debug, domeBlur, d.mirrored, d.twoSided);
                       if (p != bound) {
                           vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound = p);
                           vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                                   pipes.sceneLayout, 0, 1, &frameSet, 0, nullptr);
                       }
                       vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes.sceneLayout, 1,
                                               1, &d.material, 0, nullptr);
                       vkCmdPushConstants(cmd, pipes.sceneLayout,
                                          VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                          0, sizeof(uint32_t), &d.instance);
                       drawMesh(cmd, *d.mesh);
                   }
                   c.fn().cmdEndRendering(cmd);
               }});

    // The dome's shadows blurred (rows, then columns), times the diffuse light they darken,
    // added to the colour.
    const render::DomeBlurPush domeBlurPush{
        glm::vec4(scene.environment().domeBlur, camera.zNear, camera.zFar,
                  scene.environment().domeBlurDepthTolerance)};
    if (domeBlur) {
        const int rRows = g.addResource("dome_rows", &targets.domeRows);
        g.addPass({"dome_blur_x", {{rDomeLight, Use::Sampled}, {rDepth, Use::Sampled}},
                   {{rRows, Use::ColorWrite}}, [&](VkCommandBuffer cmd) {
                       fullscreen(cmd, targets.domeRows.view(), VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                  pipes.domeBlurRows.get(), pipes.domeBlurLayout, domeRowsSet,
                                  &domeBlurPush, sizeof(domeBlurPush));
                   }});
        g.addPass({"dome_blur", {{rDomeLight, Use::Sampled}, {rRows, Use::Sampled}},
                   {{rHdr, Use::ColorWrite}}, [&](VkCommandBuffer cmd) {
                       fullscreen(cmd, targets.hdr.view(), VK_ATTACHMENT_LOAD_OP_LOAD,
                                  pipes.domeBlur.get(), pipes.domeBlurLayout, domeBlurSet,
                                  &domeBlurPush, sizeof(domeBlurPush));
                   }});
    }

    if (hasHair)
        hair->addPasses(g, {rShadow, rDepth, rHdr, debug ? rDebug : nullptr, &targets.hdr,
                            &targets.depth,
                            {&targets.position, &targets.normal, &targets.surface, &targets.albedo},
                            frameSet,
                            [&](VkCommandBuffer cmd, VkImageView view, uint32_t size,
                                const glm::mat4& viewProj) {
                                drawCasters(cmd, view, size, viewProj, false);
                            }});

    const VkPipeline outPipeline = pipes.outputPipeline(ldr->desc().format);
    g.addPass({"output", {{rHdr, Use::Sampled}}, {{rLdr, Use::ColorWrite}}, [&](VkCommandBuffer cmd) {
                   fullscreen(cmd, ldr->view(), VK_ATTACHMENT_LOAD_OP_DONT_CARE, outPipeline,
                              pipes.outputLayout, outputSet, nullptr, 0);
               }});

    // Readback copies: colour (ldr), linear (hdr), debug images.
    std::vector<std::pair<int, vk::Image*>> copies;
    if (outputs & OutputColor) copies.push_back({rLdr, ldr});
    if (outputs & OutputLinear) copies.push_back({rHdr, &targets.hdr});
    if (debug) {
        vk::Image* images[4] = {&targets.position, &targets.normal, &targets.surface, &targets.albedo};
        for (int i = 0; i < 4; ++i) copies.push_back({rDebug[i], images[i]});
    }
    if (!copies.empty()) {
        std::vector<ResourceUse> reads;
        for (auto& [r, im] : copies) reads.push_back({r, Use::TransferRead});
        g.addPass({"readback", reads, {}, [&, copies](VkCommandBuffer cmd) {
                       for (auto& [r, im] : copies) {
                           vk::Buffer& dst = targets.readbackFor(*ctx, im);
                           VkBufferImageCopy region{};
                           region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                           region.imageExtent = {targets.width, targets.height, 1};
                           vkCmdCopyImageToBuffer(cmd, im->get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                                  dst.get(), 1, &region);
                       }
                   },
                   true});
    }
    if (present)
        g.addPass({"present", {{rLdr, Use::Present}}, {}, [](VkCommandBuffer) {}, true});

    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkResetCommandBuffer(slot.cmd, 0));
    VK_CHECK(vkBeginCommandBuffer(slot.cmd, &begin));
    slot.timestamps->reset(slot.cmd);
    slot.stats = FrameStats{};
    slot.stats.frameIndex = frameCounter;
    slot.stats.reused = std::move(reused);
    slot.stats.meshUploads = data.meshUploads;
    slot.stats.uploadBytes = data.uploadBytes;
    slot.stats.environmentBakes = environmentBaked ? 1 : 0;
    slot.stats.environmentBakeMs = environmentBakeMs;
    g.execute(c, slot.cmd, slot.timestamps.get(), slot.stats);
    // The present pseudo-pass only transitions; it is not a pass users should time.
    if (present && !slot.stats.passes.empty() && slot.stats.passes.back().name == "present")
        slot.stats.passes.pop_back();
    VK_CHECK(vkEndCommandBuffer(slot.cmd));
}

} // namespace weft
