// One frame's GPU data and descriptor sets (the first half of Renderer::Impl::recordFrame): the
// frame slot's buffers (uniforms, instances, lights, shadow layers, dome lights, the probe
// faces' uniforms) and the sets every pass binds.
#include "render/PassSetup.h"
#include "render/RendererImpl.h"

namespace weft {

using render::ensureBuffer;
using render::kFrameSets;
using render::Use;

VkDeviceSize Renderer::Impl::probeFaceStride() const {
    const VkDeviceSize align = ctx->properties().limits.minUniformBufferOffsetAlignment;
    return (sizeof(render::GpuFrame) + align - 1) / align * align;
}

namespace {

// The frame's uniforms seen from a cube capture's face at `position` (`size` texels per side):
// the dome shaded inline (no blur pass for captures) and no bounce light (captures show the
// receivers, which have none, or feed a reflection, which takes the light the frame has).
render::GpuFrame captureFace(const render::GpuFrame& frame, int face, const glm::vec3& position,
                             uint32_t size) {
    render::GpuFrame f = frame;
    f.viewProj = render::probeFaceViewProj(face, position, 0.02f, 1000.0f);
    f.inverseViewProj = glm::inverse(f.viewProj);
    f.cameraPos = glm::vec4(position, 1.0f);
    f.options.z = 0.0f;
    f.sky.z = 0.0f;
    const float texel = 1.0f / float(size);
    f.viewport = glm::vec4(texel, texel, 0.0f, 0.0f);
    return f;
}

} // namespace

void Renderer::Impl::uploadFrame(FrameSlot& slot, const render::FrameData& data, bool captureProbe,
                                 bool captureBounce) {
    vk::Context& c = *ctx;
    const render::GpuFrame& frame = data.frame;
    const std::vector<render::GpuInstance>& instances = data.instances;
    const std::vector<render::GpuLight>& lights = data.lights;
    const std::vector<render::GpuShadowLayer>& layers = data.shadowLayers;
    const std::vector<render::GpuDomeLight>& domeLights = dome.lights();
    ensureBuffer(c, slot.ubo, sizeof(frame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    ensureBuffer(c, slot.instances, instances.size() * sizeof(render::GpuInstance),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ensureBuffer(c, slot.lights, lights.size() * sizeof(render::GpuLight),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    slot.ubo.write(&frame, sizeof(frame));
    // The capture's faces: the frame's uniforms seen from the probe, at aligned offsets.
    const VkDeviceSize faceStride = probeFaceStride();
    if (captureProbe) {
        ensureBuffer(c, slot.probeUbo, 6 * faceStride, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        std::vector<uint8_t> faces(6 * faceStride, 0);
        for (int f = 0; f < 6; ++f) {
            const render::GpuFrame face =
                captureFace(frame, f, probe.position(), probe.cube().desc().width);
            std::memcpy(faces.data() + f * faceStride, &face, sizeof(face));
        }
        slot.probeUbo.write(faces.data(), faces.size());
    }
    if (captureBounce) {
        const uint32_t perRound = 6 * bounce.count(), n = perRound * render::BounceProbes::kRounds;
        ensureBuffer(c, slot.bounceUbo, n * faceStride, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        std::vector<uint8_t> faces(n * faceStride, 0);
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t k = i % perRound;
            render::GpuFrame face = captureFace(frame, int(k % 6), bounce.position(k / 6),
                                                render::BounceProbes::kFaceSize);
            // after the first round the receivers get the casters' light (caster_bounce.glsl)
            if (i >= perRound) face.sky.z = 1.0f;
            std::memcpy(faces.data() + i * faceStride, &face, sizeof(face));
        }
        slot.bounceUbo.write(faces.data(), faces.size());
    }
    if (!instances.empty())
        slot.instances.write(instances.data(), instances.size() * sizeof(render::GpuInstance));
    if (!lights.empty()) slot.lights.write(lights.data(), lights.size() * sizeof(render::GpuLight));
    ensureBuffer(c, slot.shadowLayers, layers.size() * sizeof(render::GpuShadowLayer),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!layers.empty())
        slot.shadowLayers.write(layers.data(), layers.size() * sizeof(render::GpuShadowLayer));
    ensureBuffer(c, slot.domeLights, domeLights.size() * sizeof(render::GpuDomeLight),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!domeLights.empty())
        slot.domeLights.write(domeLights.data(), domeLights.size() * sizeof(render::GpuDomeLight));
}

render::FrameSets Renderer::Impl::bindFrame(FrameSlot& slot, const Scene& scene,
                                            const render::FrameData& data, bool captureProbe,
                                            bool captureBounce, bool domeBlur) {
    vk::Context& c = *ctx;
    const render::GpuFrame& frame = data.frame;
    VK_CHECK(vkResetDescriptorPool(c.device(), slot.pool, 0));
    // The frame set, six probe-face sets while capturing, six per bounce capture while taking
    // those, the output set, the dome's gather and blur sets, the bounce projection's.
    VkDescriptorSetLayout layouts[kFrameSets + 5];
    uint32_t setCount = 0;
    layouts[setCount++] = pipes.frameSetLayout;
    if (captureProbe)
        for (uint32_t f = 0; f < 6; ++f) layouts[setCount++] = pipes.frameSetLayout;
    const uint32_t bounceIndex = setCount;
    const uint32_t bounceFaces =
        captureBounce ? 6 * bounce.count() * render::BounceProbes::kRounds : 0;
    for (uint32_t f = 0; f < bounceFaces; ++f) layouts[setCount++] = pipes.frameSetLayout;
    const uint32_t outputIndex = setCount;
    layouts[setCount++] = pipes.outputSetLayout;
    layouts[setCount++] = pipes.domeBlurSetLayout;
    layouts[setCount++] = pipes.domeBlurSetLayout;
    layouts[setCount++] = pipes.domeBlurSetLayout;
    layouts[setCount++] = pipes.bounceShSetLayout;
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = slot.pool;
    alloc.descriptorSetCount = setCount;
    alloc.pSetLayouts = layouts;
    VkDescriptorSet sets[kFrameSets + 5];
    VK_CHECK(vkAllocateDescriptorSets(c.device(), &alloc, sets));
    render::FrameSets result;
    result.frame = sets[0];
    for (uint32_t f = 0; captureProbe && f < 6; ++f) result.faces[f] = sets[1 + f];
    result.output = sets[outputIndex];
    result.domeGather = sets[outputIndex + 1];
    result.domeRows = sets[outputIndex + 2];
    result.domeBlur = sets[outputIndex + 3];
    result.bounceSh = sets[outputIndex + 4];
    for (uint32_t f = 0; f < bounceFaces; ++f) result.bounceFaces[f] = sets[bounceIndex + f];
    const VkDescriptorSet outputSet = result.output;
    const VkDeviceSize faceStride = probeFaceStride();
    vk::Image& shadowImage = data.shadowViews.empty() ? dummyShadow : shadowMaps;
    vk::Image& domeImage = dome.active() ? dome.maps() : dummyShadow;
    // Without bounce light the shaders' SH binding holds a white texel they never read.
    const VkImageView noBounce = cache->textureView(TexturePtr());
    // A frame set: the frame's data with uniforms `ubo`, the reflection capture `probeView` and
    // the bounce captures' SH9 `bounceView` and the casters' radiance `radianceView`, and with
    // `withFaces` (the frame's own set) the captures' faces (the captures see a dummy there:
    // they are being drawn).
    auto writeFrameSet = [&](VkDescriptorSet set, VkDescriptorBufferInfo uboInfo,
                             VkImageView probeView, VkImageView bounceView, bool withFaces,
                             VkImageView radianceView) {
        VkDescriptorBufferInfo instInfo{slot.instances.get(), 0, VK_WHOLE_SIZE};
        VkDescriptorBufferInfo lightInfo{slot.lights.get(), 0, VK_WHOLE_SIZE};
        VkDescriptorImageInfo shadowInfo{pipes.nearestSampler, shadowImage.view(),
                                         render::useState(Use::Sampled, true).layout};
        VkDescriptorBufferInfo layerInfo{slot.shadowLayers.get(), 0, VK_WHOLE_SIZE};
        VkDescriptorImageInfo cookieInfos[render::kMaxCookies];
        for (int i = 0; i < render::kMaxCookies; ++i) // unused slots hold white
            cookieInfos[i] = {pipes.cookieSampler,
                              cache->textureView(size_t(i) < data.cookies.size()
                                                     ? data.cookies[size_t(i)]
                                                     : TexturePtr()),
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkDescriptorImageInfo environmentInfo{pipes.environmentSampler,
                                              environment.view(scene.environment()),
                                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkDescriptorBufferInfo domeInfo{slot.domeLights.get(), 0, VK_WHOLE_SIZE};
        VkDescriptorImageInfo domeMapInfo{pipes.nearestSampler, domeImage.view(),
                                          render::useState(Use::Sampled, true).layout};
        VkDescriptorImageInfo probeInfo{pipes.environmentSampler, probeView,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkDescriptorImageInfo backgroundInfo{pipes.cookieSampler,
                                             cache->textureView(scene.backgroundImage()),
                                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkDescriptorImageInfo sphereInfos[2] = {
            {pipes.environmentSampler, environment.sphereIrradiance(),
             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {pipes.environmentSampler, environment.sphereGlossy(),
             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
        VkDescriptorImageInfo radianceInfo{pipes.environmentSampler, environment.radianceView(),
                                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkDescriptorImageInfo bounceInfo{pipes.nearestSampler, bounceView,
                                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        const VkDescriptorImageInfo facesInfo =
            withFaces ? VkDescriptorImageInfo{pipes.environmentSampler, bounce.faces().view(),
                                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}
                      : VkDescriptorImageInfo{pipes.nearestSampler, dummyShadow.view(),
                                              render::useState(Use::Sampled, true).layout};
        VkDescriptorImageInfo radianceSh{pipes.nearestSampler, radianceView,
                                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        const VkDescriptorImageInfo coatInfo{pipes.cookieSampler, coatAlbedo.view(),
                                             render::useState(Use::Sampled, false).layout};
        const VkDescriptorImageInfo depthsInfo{
            pipes.nearestSampler, withFaces ? bounce.depth().view() : dummyShadow.view(),
            render::useState(Use::Sampled, true).layout};
        // Binding i of frame.glsl / environment.glsl: a buffer or images (count > 1: an array).
        struct Entry {
            VkDescriptorType type;
            const VkDescriptorBufferInfo* buffer;
            const VkDescriptorImageInfo* images;
            uint32_t count;
        };
        constexpr VkDescriptorType ubo = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                                   ssbo = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                   image = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        const Entry entries[] = {{ubo, &uboInfo, nullptr, 1},
                                 {ssbo, &instInfo, nullptr, 1},
                                 {ssbo, &lightInfo, nullptr, 1},
                                 {image, nullptr, &shadowInfo, 1},
                                 {ssbo, &layerInfo, nullptr, 1},
                                 {image, nullptr, cookieInfos, render::kMaxCookies},
                                 {image, nullptr, &environmentInfo, 1},
                                 {ssbo, &domeInfo, nullptr, 1},
                                 {image, nullptr, &domeMapInfo, 1},
                                 {image, nullptr, &probeInfo, 1},
                                 {image, nullptr, &backgroundInfo, 1},
                                 {image, nullptr, &sphereInfos[0], 1},
                                 {image, nullptr, &sphereInfos[1], 1},
                                 {image, nullptr, &radianceInfo, 1},
                                 {image, nullptr, &bounceInfo, 1},
                                 {image, nullptr, &facesInfo, 1},
                                 {image, nullptr, &radianceSh, 1},
                                 {image, nullptr, &depthsInfo, 1},
                                 {image, nullptr, &coatInfo, 1}};
        constexpr uint32_t kBindings = sizeof(entries) / sizeof(entries[0]);
        VkWriteDescriptorSet writes[kBindings];
        for (uint32_t i = 0; i < kBindings; ++i) {
            writes[i] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[i].dstSet = set;
            writes[i].dstBinding = i;
            writes[i].descriptorCount = entries[i].count;
            writes[i].descriptorType = entries[i].type;
            writes[i].pBufferInfo = entries[i].buffer;
            writes[i].pImageInfo = entries[i].images;
        }
        vkUpdateDescriptorSets(c.device(), kBindings, writes, 0, nullptr);
    };
    writeFrameSet(result.frame, {slot.ubo.get(), 0, sizeof(frame)},
                  probe.instance() >= 0 ? probe.cube().view() : environment.black(),
                  bounce.count() > 0 ? bounce.sh().view() : noBounce, bounce.count() > 0,
                  bounce.count() > 0 ? bounce.radiance().view() : noBounce);
    if (captureProbe) // the faces see the capture as black: it is being drawn
        for (uint32_t f = 0; f < 6; ++f)
            writeFrameSet(sets[1 + f], {slot.probeUbo.get(), f * faceStride, sizeof(frame)},
                          environment.black(), noBounce, false, noBounce);
    // diffuse light: no reflection capture; the second round's receivers get the casters' light
    // of the first (whose radiance pass uses the second round's first set)
    for (uint32_t f = 0; f < bounceFaces; ++f) {
        const bool second = f >= bounceFaces / render::BounceProbes::kRounds;
        writeFrameSet(result.bounceFaces[f], {slot.bounceUbo.get(), f * faceStride, sizeof(frame)},
                      environment.black(), second ? bounce.shFirst().view() : noBounce, false,
                      second ? bounce.radianceFirst().view() : noBounce);
    }
    if (captureBounce) { // the projection: the captures, their depths, the environment, geometry
        VkDescriptorImageInfo infos[4] = {
            {pipes.nearestSampler, bounce.faces().view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {pipes.environmentSampler, environment.view(scene.environment()),
             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {pipes.nearestSampler, bounce.depth().view(),
             render::useState(Use::Sampled, true).layout},
            {pipes.nearestSampler, bounce.geometry().view(),
             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
        VkWriteDescriptorSet w[4];
        for (uint32_t i = 0; i < 4; ++i) {
            w[i] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w[i].dstSet = result.bounceSh;
            w[i].dstBinding = i;
            w[i].descriptorCount = 1;
            w[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            w[i].pImageInfo = &infos[i];
        }
        vkUpdateDescriptorSets(c.device(), 4, w, 0, nullptr);
    }
    VkDescriptorImageInfo hdrInfo{pipes.nearestSampler, targets.hdr.view(),
                                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet outputWrite{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    outputWrite.dstSet = outputSet;
    outputWrite.dstBinding = 0;
    outputWrite.descriptorCount = 1;
    outputWrite.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    outputWrite.pImageInfo = &hdrInfo;
    vkUpdateDescriptorSets(c.device(), 1, &outputWrite, 0, nullptr);
    if (domeBlur) {
        // binding 0 the dome output, 2 its aux (read by the gather pass), 1 what the pass blurs:
        // the depth (gather), the gathered visibility (rows), the rows' result (columns)
        targets.ensureDome(c);
        const VkImageLayout colorRead = render::useState(Use::Sampled, false).layout;
        const VkDescriptorImageInfo dome{pipes.nearestSampler, targets.dome.view(), colorRead};
        const VkDescriptorImageInfo aux{pipes.nearestSampler, targets.domeAux.view(), colorRead};
        const VkDescriptorImageInfo input[3] = {
            {pipes.nearestSampler, targets.depth.layerView(0),
             render::useState(Use::Sampled, true).layout},
            {pipes.nearestSampler, targets.domeVisibility.view(), colorRead},
            {pipes.nearestSampler, targets.domeRows.view(), colorRead}};
        const VkDescriptorSet sets[3] = {result.domeGather, result.domeRows, result.domeBlur};
        VkWriteDescriptorSet w[9];
        for (uint32_t i = 0; i < 9; ++i) {
            const uint32_t binding = i % 3;
            w[i] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w[i].dstSet = sets[i / 3];
            w[i].dstBinding = binding;
            w[i].descriptorCount = 1;
            w[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            w[i].pImageInfo = binding == 0 ? &dome : binding == 2 ? &aux : &input[i / 3];
        }
        vkUpdateDescriptorSets(c.device(), 9, w, 0, nullptr);
    }
    return result;
}

} // namespace weft
