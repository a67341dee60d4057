#include "render/HairPasses.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "render/HairShadingGpu.h"
#include "render/PassSetup.h"
#include "render/RenderTargets.h"
#include "render/ScenePipelines.h"

namespace weft::render {

namespace {

constexpr VkShaderStageFlags kStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

void ensureBuffer(vk::Context& ctx, vk::Buffer& buffer, VkDeviceSize bytes,
                  VkBufferUsageFlags usage) {
    bytes = std::max<VkDeviceSize>(bytes, 256);
    if (buffer && buffer.size() >= bytes) return;
    buffer = vk::Buffer(&ctx, bytes * 3 / 2, usage, vk::MemoryUsage::Upload);
}

vk::Image makeImage(vk::Context& ctx, uint32_t w, uint32_t h, uint32_t layers, VkFormat format,
                    VkImageUsageFlags usage) {
    vk::ImageDesc d;
    d.width = w;
    d.height = h;
    d.layers = layers;
    d.format = format;
    d.usage = usage | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    return vk::Image(&ctx, d);
}

} // namespace

HairPasses::HairPasses(vk::Context& ctx, const ScenePipelines& scene)
    : mCtx(ctx), mScene(scene), mPipes(ctx, scene), mCache(ctx) {
    // 1x1 arrays (an array view per DOM slot) bound where nothing was rendered: as the DOM
    // opacity when no light has a DOM (cleared), as the meshes' depth when no mesh casts (far).
    auto cleared = [&](float value) {
        vk::Image image =
            makeImage(ctx, 1, 1, kMaxHairDoms, kDomOpacityFormat, VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        ctx.immediate([&](VkCommandBuffer cmd) {
            vk::transition(ctx, cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
            VkClearColorValue c{{value, value, value, 1.0f}};
            VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, kMaxHairDoms};
            vkCmdClearColorImage(cmd, image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &c, 1,
                                 &range);
            const UseState s = useState(Use::Sampled, false);
            vk::transition(ctx, cmd, image, s.layout, s.stage, s.access);
        });
        return image;
    };
    mDummyDom = cleared(0.0f);
    mNoMeshes = cleared(1.0f);
}

HairPasses::~HairPasses() = default;

// An orthographic view per shadow-casting directional light around the shadow-casting hair,
// in the basis of reference/hair_shadow.py's LightGrid (rows right, up, forward).
void HairPasses::fitDoms(const Scene& scene, const RenderSettings& settings) {
    mDoms.clear();
    mLastDoms.assign(scene.lights().size(), HairDomInfo{});
    if (!settings.hairDeepOpacity) return;
    std::vector<glm::vec3> corners;
    for (const HairInstance& h : scene.hairs()) {
        if (!h.castShadows) continue;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 c((i & 1) ? h.hi.x : h.lo.x, (i & 2) ? h.hi.y : h.lo.y,
                              (i & 4) ? h.hi.z : h.lo.z);
            corners.push_back(glm::vec3(h.transform * glm::vec4(c, 1.0f)));
        }
    }
    if (corners.empty()) return;
    glm::vec3 casterLo, casterHi; // every caster: meshes between the light and the hair shadow it
    scene.bounds(casterLo, casterHi, true);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& c : corners) {
        lo = glm::min(lo, c);
        hi = glm::max(hi, c);
    }
    const glm::vec3 center = 0.5f * (lo + hi);
    for (size_t i = 0; i < scene.lights().size() && mDoms.size() < size_t(kMaxHairDoms); ++i) {
        const auto* light = std::get_if<DirectionalLight>(&scene.lights()[i]);
        if (!light || !light->castShadows) continue;
        const glm::vec3 f = -glm::normalize(light->toLight());
        const glm::vec3 helper = std::abs(f.y) > 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
        const glm::vec3 r = glm::normalize(glm::cross(helper, f));
        const glm::vec3 u = glm::cross(f, r);
        float half = 0.0f, zMin = 1e30f, zMax = -1e30f;
        for (const glm::vec3& c : corners) {
            const glm::vec3 q = c - center;
            half = std::max({half, std::abs(glm::dot(q, r)), std::abs(glm::dot(q, u))});
            zMin = std::min(zMin, glm::dot(q, f));
            zMax = std::max(zMax, glm::dot(q, f));
        }
        const float depth = std::max(zMax - zMin, 1e-4f);
        const float extent = 2.0f * half * 1.02f + 1e-4f;
        const float zNear = zMin - 0.01f * depth - 1e-4f, zFar = zMax + 0.01f * depth + 1e-4f;
        float d = settings.hairDomLayerSize;
        if (d <= 0.0f) d = depth / (settings.hairDomLogSpacing ? 7.0f : 3.0f);
        Dom dom;
        dom.light = int(i);
        HairDomInfo& info = dom.info;
        info.direction = f;
        info.center = center;
        info.extent = extent;
        info.zNear = zNear;
        info.zFar = zFar;
        info.layerSize = d;
        info.logSpacing = settings.hairDomLogSpacing;
        info.size = settings.hairDomSize;
        // Rows: x = 2 r.(p - c) / extent, y = 2 u.(p - c) / extent, z = (f.(p - c) - near) / range.
        glm::mat4 m(0.0f);
        auto row = [&](int k, const glm::vec3& axis, float scale, float offset) {
            for (int j = 0; j < 3; ++j) m[j][k] = axis[j] * scale;
            m[3][k] = -glm::dot(axis, center) * scale + offset;
        };
        row(0, r, 2.0f / extent, 0.0f);
        row(1, u, 2.0f / extent, 0.0f);
        row(2, f, 1.0f / (zFar - zNear), -zNear / (zFar - zNear));
        m[3][3] = 1.0f;
        dom.viewProj = m;
        float meshNear = zNear;
        for (int k = 0; k < 8; ++k) {
            const glm::vec3 c((k & 1) ? casterHi.x : casterLo.x, (k & 2) ? casterHi.y : casterLo.y,
                              (k & 4) ? casterHi.z : casterLo.z);
            meshNear = std::min(meshNear, glm::dot(c - center, f) - 1e-3f);
        }
        row(2, f, 1.0f / (zFar - meshNear), -meshNear / (zFar - meshNear));
        dom.meshViewProj = m;
        dom.layerNdc = d / (zFar - zNear);
        mDoms.push_back(dom);
    }
}

namespace {

// The pixels the strands can cover: each hair's bounds, grown by its widest ribbon, projected,
// plus three pixels for an anti-aliased strip's reach across and past its ends (at most 1.2);
// the whole target where a bound reaches behind the camera.
VkRect2D hairScreenRect(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                        uint32_t width, uint32_t height) {
    const VkRect2D whole{{0, 0}, {width, height}};
    const glm::mat4 viewProj = camera.projection(float(width) / float(height)) * camera.view();
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const HairInstance& h : scene.hairs()) {
        float thickness = h.strands->defaultThickness;
        for (float t : h.strands->thickness) thickness = std::max(thickness, t);
        glm::vec3 worldLo(1e30f), worldHi(-1e30f);
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 c((i & 1) ? h.hi.x : h.lo.x, (i & 2) ? h.hi.y : h.lo.y,
                              (i & 4) ? h.hi.z : h.lo.z);
            const glm::vec3 w(h.transform * glm::vec4(c, 1.0f));
            worldLo = glm::min(worldLo, w);
            worldHi = glm::max(worldHi, w);
        }
        const glm::vec3 grow(settings.hairWidth * thickness);
        worldLo -= grow;
        worldHi += grow;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 c((i & 1) ? worldHi.x : worldLo.x, (i & 2) ? worldHi.y : worldLo.y,
                              (i & 4) ? worldHi.z : worldLo.z);
            const glm::vec4 clip = viewProj * glm::vec4(c, 1.0f);
            if (!(clip.w > 1e-6f)) return whole;
            const glm::vec2 pixel =
                (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(float(width), float(height));
            lo = glm::min(lo, pixel);
            hi = glm::max(hi, pixel);
        }
    }
    const float margin = 3.0f;
    const glm::vec2 size{float(width), float(height)};
    lo = glm::clamp(glm::floor(lo - margin), glm::vec2(0.0f), size - 1.0f);
    hi = glm::clamp(glm::ceil(hi + margin), lo + 1.0f, size);
    return {{int32_t(lo.x), int32_t(lo.y)}, {uint32_t(hi.x - lo.x), uint32_t(hi.y - lo.y)}};
}

} // namespace

std::vector<uint64_t> HairPasses::domKey() const {
    std::vector<uint64_t> key;
    auto add = [&key](const float* v, size_t n) {
        for (size_t i = 0; i < n; ++i) {
            uint32_t bits;
            std::memcpy(&bits, &v[i], sizeof(bits));
            key.push_back(bits);
        }
    };
    for (const Dom& d : mDoms) {
        key.push_back(uint64_t(d.light));
        key.push_back(d.info.size);
        add(&d.viewProj[0][0], 16);
        add(&d.layerNdc, 1);
    }
    for (const HairDraw& d : mDraws) {
        if (!d.castShadows) continue;
        key.push_back(reinterpret_cast<uintptr_t>(d.gpu->vertices.get())); // immutable strands
        add(&d.model[0][0], 16);
    }
    return key;
}

void HairPasses::ensureImages(const RenderSettings& settings, uint32_t width, uint32_t height) {
    if (!mDoms.empty() && (!mDomDepth || mDomSize != settings.hairDomSize)) {
        mDomKey.clear(); // new maps hold nothing
        mDomSize = settings.hairDomSize;
        mDomDepth = makeImage(mCtx, mDomSize, mDomSize, kMaxHairDoms, kDepthFormat,
                              VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
        mDomOpacity = makeImage(mCtx, mDomSize, mDomSize, kMaxHairDoms, kDomOpacityFormat,
                                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
        mDomMeshDepth = makeImage(mCtx, mDomSize, mDomSize, kMaxHairDoms, kDepthFormat,
                                  VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
    }
    if (mSampleDepths &&
        (!mSamples || mSamples.desc().width != width || mSamples.desc().height != height)) {
        vk::ImageDesc d;
        d.width = width;
        d.height = height;
        d.layers = kHairAaSampleLayers;
        d.format = VK_FORMAT_R32_UINT;
        d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        mSamples = vk::Image(&mCtx, d);
    }
    if ((mOit || mAntialias) && (!mAccum || mWidth != width || mHeight != height)) {
        mWidth = width;
        mHeight = height;
        mAccum =
            makeImage(mCtx, width, height, 1, kOitAccumFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
        mWeight = makeImage(mCtx, width, height, 1, kOitWeightFormat,
                            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    }
}

void HairPasses::allocateSets(Slot& slot, uint32_t draws) {
    const uint32_t sets = draws + 3; // per draw + z0 + opacity + composite
    if (!slot.pool || slot.poolSets < sets) {
        slot.poolSets = std::max(sets * 2, 16u);
        const VkDescriptorPoolSize sizes[] = {
            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2 * slot.poolSets},
            {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, slot.poolSets},
            {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 6},
            {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
        VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        info.maxSets = slot.poolSets;
        info.poolSizeCount = 4;
        info.pPoolSizes = sizes;
        VkDescriptorPool p;
        VK_CHECK(vkCreateDescriptorPool(mCtx.device(), &info, nullptr, &p));
        slot.pool = vk::DescriptorPool(&mCtx, p, vkDestroyDescriptorPool);
    } else {
        VK_CHECK(vkResetDescriptorPool(mCtx.device(), slot.pool, 0));
    }
    std::vector<VkDescriptorSetLayout> layouts(draws, mPipes.hairSetLayout);
    layouts.push_back(mPipes.domSetLayout);
    layouts.push_back(mPipes.domSetLayout);
    layouts.push_back(mPipes.oitSetLayout);
    std::vector<VkDescriptorSet> out(layouts.size());
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = slot.pool;
    alloc.descriptorSetCount = uint32_t(layouts.size());
    alloc.pSetLayouts = layouts.data();
    VK_CHECK(vkAllocateDescriptorSets(mCtx.device(), &alloc, out.data()));
    for (uint32_t i = 0; i < draws; ++i) mDraws[i].set = out[i];
    mZ0Set = out[draws];
    mOpacitySet = out[draws + 1];
    mOitSet = out[draws + 2];
}

void HairPasses::writeSets(Slot& slot) {
    std::vector<VkWriteDescriptorSet> writes;
    std::vector<VkDescriptorBufferInfo> buffers;
    buffers.reserve(3 * mDraws.size());
    auto write = [&](VkDescriptorSet set, uint32_t binding, VkDescriptorType type) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = set;
        w.dstBinding = binding;
        w.descriptorCount = 1;
        w.descriptorType = type;
        writes.push_back(w);
        return &writes.back();
    };
    for (const HairDraw& d : mDraws) {
        buffers.push_back({d.gpu->vertices.get(), 0, VK_WHOLE_SIZE});
        buffers.push_back({slot.instances.get(), 0, VK_WHOLE_SIZE});
        buffers.push_back({slot.frame.get(), 0, sizeof(GpuHairFrame)});
        const VkDescriptorBufferInfo* b = &buffers[buffers.size() - 3];
        write(d.set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)->pBufferInfo = b;
        write(d.set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)->pBufferInfo = b + 1;
        write(d.set, 2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)->pBufferInfo = b + 2;
    }
    const VkSampler nearest = mScene.nearestSampler;
    const bool dom = !mDoms.empty();
    const VkImageLayout readOnly = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const VkDescriptorImageInfo images[] = {
        {nearest, dom ? mDomDepth.view() : mDummyDom.view(),
         dom ? useState(Use::Sampled, true).layout : readOnly},
        {nearest, dom ? mDomOpacity.view() : mDummyDom.view(), readOnly},
        {nearest, mAccum ? mAccum.view() : mDummyDom.view(), readOnly},
        {nearest, mWeight ? mWeight.view() : mDummyDom.view(), readOnly},
        {nearest, mMeshesShadowHair ? mDomMeshDepth.view() : mNoMeshes.view(),
         mMeshesShadowHair ? useState(Use::Sampled, true).layout : readOnly}};
    write(mZ0Set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)->pImageInfo = &images[0];
    write(mZ0Set, 1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)->pImageInfo = &images[4];
    write(mOpacitySet, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)->pImageInfo = &images[1];
    write(mOpacitySet, 1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)->pImageInfo = &images[4];
    const VkDescriptorImageInfo samples{VK_NULL_HANDLE, mSamples ? mSamples.view() : VK_NULL_HANDLE,
                                        VK_IMAGE_LAYOUT_GENERAL};
    if (mSampleDepths)
        write(mOpacitySet, 2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE)->pImageInfo = &samples;
    if (mAccum) {
        write(mOitSet, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)->pImageInfo = &images[2];
        write(mOitSet, 1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)->pImageInfo = &images[3];
    }
    vkUpdateDescriptorSets(mCtx.device(), uint32_t(writes.size()), writes.data(), 0, nullptr);
}

void HairPasses::prepare(uint32_t slotIndex, const Scene& scene, const Camera& camera,
                         const RenderSettings& settings, uint32_t width, uint32_t height,
                         const std::vector<int>& gpuLightIndex, uint32_t lightFeatures) {
    mRibbons = settings.hairPrimitive == HairPrimitive::Ribbons;
    // Hair is drawn after the forward pass's MSAA resolve, so it anti-aliases itself with
    // coverage; msaa = 1 asks for no anti-aliasing and keeps one strand per pixel.
    mAntialias = settings.msaa > 1;
    mDraws.clear();
    std::vector<GpuHairInstance> instances;
    bool anyTransparent = false;
    for (const HairInstance& h : scene.hairs()) {
        HairGpu& gpu = mCache.get(h.strands, mRibbons || mAntialias);
        if (gpu.lineIndexCount == 0) continue; // single-point strands only: nothing to draw
        const bool transparent = settings.hairTransparency && gpu.transparent;
        anyTransparent |= transparent;
        mDraws.push_back({&gpu, VK_NULL_HANDLE, uint32_t(instances.size()), h.material.model,
                          nullptr, h.castShadows, transparent, h.transform});
        instances.push_back({h.transform, hair::packHairShading(h.material)});
    }
    mOit = anyTransparent;
    mSampleDepths =
        mAntialias && mPipes.sampleMasks &&
        std::any_of(mDraws.begin(), mDraws.end(), [](const HairDraw& d) { return !d.transparent; });
    fitDoms(scene, settings);
    // the shadow-map path only where a shadowed directional light has no deep opacity map
    for (size_t i = 0; i < scene.lights().size(); ++i) {
        const auto* light = std::get_if<DirectionalLight>(&scene.lights()[i]);
        const auto hasDom = [&](const Dom& d) { return d.light == int(i); };
        if (light && light->castShadows && std::none_of(mDoms.begin(), mDoms.end(), hasDom))
            lightFeatures |= gpu::FEATURE_HAIR_SHADOW_MAPS;
    }
    for (HairDraw& d : mDraws)
        d.shaded = &mPipes.shaded(lightFeatures, d.shading, settings.hairOitWeight);
    mMeshesShadowHair =
        !mDoms.empty() && std::any_of(scene.instances().begin(), scene.instances().end(),
                                      [](const MeshInstance& m) { return m.castShadows; });
    ensureImages(settings, width, height);
    std::vector<uint64_t> key = domKey();
    mReuseDoms = settings.reuseShadowMaps && !mDoms.empty() && key == mDomKey;
    mDomKey = std::move(key);
    for (const Dom& d : mDoms) mLastDoms[size_t(d.light)] = d.info;
    mRect = hairScreenRect(scene, camera, settings, width, height);

    GpuHairFrame f{};
    f.cameraForward =
        glm::vec4(glm::normalize(camera.target - camera.position), settings.hairWidth);
    f.params = glm::ivec4(mRibbons ? 1 : 0, int(settings.hairOitWeight), int(mDoms.size()),
                          settings.hairDomLogSpacing ? 1 : 0);
    f.domLight = glm::ivec4(-1);
    for (size_t i = 0; i < mDoms.size(); ++i) {
        f.domLight[int(i)] = gpuLightIndex[size_t(mDoms[i].light)]; // as the shaders index them
        f.domViewProj[i] = mDoms[i].viewProj;
        f.domMeshViewProj[i] = mDoms[i].meshViewProj;
        f.domLayer[i] = glm::vec4(mDoms[i].layerNdc, 0, 0, 0);
    }
    Slot& slot = mSlots[slotIndex % mSlots.size()];
    ensureBuffer(mCtx, slot.instances, instances.size() * sizeof(GpuHairInstance),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ensureBuffer(mCtx, slot.frame, sizeof(f), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    if (!instances.empty())
        slot.instances.write(instances.data(), instances.size() * sizeof(GpuHairInstance));
    slot.frame.write(&f, sizeof(f));
    allocateSets(slot, uint32_t(mDraws.size()));
    writeSets(slot);
}

void HairPasses::drawDepth(VkCommandBuffer cmd, const glm::mat4& viewProj) const {
    drawFromLight(cmd, mPipes.lightDepth, viewProj, glm::vec4(0.0f));
}

void HairPasses::drawFromLight(VkCommandBuffer cmd, VkPipeline pipeline, const glm::mat4& viewProj,
                               const glm::vec4& params) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    for (const HairDraw& d : mDraws) {
        if (!d.castShadows) continue;
        const struct {
            glm::mat4 mvp;
            glm::vec4 params;
        } push{viewProj * d.model, params};
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipes.layout, 2, 1, &d.set,
                                0, nullptr);
        vkCmdPushConstants(cmd, mPipes.layout, kStages, 0, sizeof(push), &push);
        vkCmdBindIndexBuffer(cmd, d.gpu->lines.get(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, d.gpu->lineIndexCount, 1, 0, 0, 0);
    }
}

void HairPasses::drawCamera(VkCommandBuffer cmd, const Targets& t, const PipelineOf& pipeline,
                            VkDescriptorSet domSet, bool transparent, bool strips) const {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipes.layout, 0, 1, &t.frameSet,
                            0, nullptr);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipes.layout, 3, 1, &domSet, 0,
                            nullptr);
    VkPipeline bound = VK_NULL_HANDLE;
    for (const HairDraw& d : mDraws) {
        if (d.transparent != transparent) continue;
        const VkPipeline p = pipeline(*d.shaded); // the draw's model (all share one layout)
        if (p != bound) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound = p);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipes.layout, 2, 1, &d.set,
                                0, nullptr);
        vkCmdPushConstants(cmd, mPipes.layout, kStages, 0, sizeof(uint32_t), &d.instance);
        const bool ribbons = strips && d.gpu->ribbons;
        vkCmdBindIndexBuffer(cmd, ribbons ? d.gpu->ribbons.get() : d.gpu->lines.get(), 0,
                             VK_INDEX_TYPE_UINT32);
        const uint32_t count = ribbons ? d.gpu->ribbonIndexCount : d.gpu->lineIndexCount;
        vkCmdDrawIndexed(cmd, count, 1, 0, 0, 0);
    }
}

void HairPasses::addPasses(FrameGraph& g, const Targets& t) {
    if (mDraws.empty()) return;
    const int ribbons = mRibbons ? 1 : 0;
    const bool aa = mAntialias && !t.debug; // debug outputs: one strand per pixel, as drawn
    std::vector<ResourceUse> shadingReads = {{t.shadow, Use::Sampled}};
    if (!mDoms.empty()) {
        const int rZ0 = g.addResource("hair_dom_depth", &mDomDepth);
        const int rOpacity = g.addResource("hair_dom_opacity", &mDomOpacity);
        shadingReads.push_back({rOpacity, Use::Sampled});
        // The mesh casters in each DOM's view: hair behind them is in their shadow.
        if (mMeshesShadowHair) {
            const int rMeshes = g.addResource("hair_dom_meshes", &mDomMeshDepth);
            shadingReads.push_back({rMeshes, Use::Sampled});
            g.addPass({"hair_dom_meshes",
                       {},
                       {{rMeshes, Use::DepthWrite}},
                       [this, t](VkCommandBuffer cmd) {
                           for (size_t s = 0; s < mDoms.size(); ++s)
                               t.meshDepth(cmd, mDomMeshDepth.layerView(uint32_t(s)), mDomSize,
                                           mDoms[s].meshViewProj);
                       }});
        }
        if (mReuseDoms) { // the maps hold these views of these strands
            if (t.reused) t.reused->insert(t.reused->end(), {"hair_dom_depth", "hair_dom_opacity"});
        } else {
            g.addPass({"hair_dom_depth", {}, {{rZ0, Use::DepthWrite}}, [this](VkCommandBuffer cmd) {
                           for (size_t s = 0; s < mDoms.size(); ++s) {
                               VkRenderingAttachmentInfo depth =
                                   attachment(mDomDepth.layerView(uint32_t(s)),
                                              VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, true);
                               depth.clearValue.depthStencil = {1.0f, 0};
                               VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                               info.renderArea = {{0, 0}, {mDomSize, mDomSize}};
                               info.layerCount = 1;
                               info.pDepthAttachment = &depth;
                               mCtx.fn().cmdBeginRendering(cmd, &info);
                               setViewport(cmd, mDomSize, mDomSize);
                               drawFromLight(cmd, mPipes.lightDepth, mDoms[s].viewProj,
                                             glm::vec4(0.0f));
                               mCtx.fn().cmdEndRendering(cmd);
                           }
                       }});
            g.addPass({"hair_dom_opacity",
                       {{rZ0, Use::Sampled}},
                       {{rOpacity, Use::ColorWrite}},
                       [this](VkCommandBuffer cmd) {
                           for (size_t s = 0; s < mDoms.size(); ++s) {
                               VkRenderingAttachmentInfo color =
                                   attachment(mDomOpacity.layerView(uint32_t(s)),
                                              VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true);
                               color.clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}};
                               VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                               info.renderArea = {{0, 0}, {mDomSize, mDomSize}};
                               info.layerCount = 1;
                               info.colorAttachmentCount = 1;
                               info.pColorAttachments = &color;
                               mCtx.fn().cmdBeginRendering(cmd, &info);
                               setViewport(cmd, mDomSize, mDomSize);
                               vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                                       mPipes.layout, 3, 1, &mZ0Set, 0, nullptr);
                               drawFromLight(cmd, mPipes.domOpacity, mDoms[s].viewProj,
                                             glm::vec4(float(s), mDoms[s].layerNdc, 0.0f, 0.0f));
                               mCtx.fn().cmdEndRendering(cmd);
                           }
                       }});
        }
    }
    const bool anyOpaque =
        std::any_of(mDraws.begin(), mDraws.end(), [](const HairDraw& d) { return !d.transparent; });
    if (anyOpaque) {
        std::vector<ResourceUse> writes = {{t.hdr, Use::ColorWrite}, {t.depth, Use::DepthWrite}};
        if (t.debug)
            for (int i = 0; i < 4; ++i) writes.push_back({t.debug[i], Use::ColorWrite});
        const bool debug = t.debug != nullptr;
        g.addPass(
            {"hair", shadingReads, writes, [this, t, debug, ribbons, aa](VkCommandBuffer cmd) {
                 std::vector<VkRenderingAttachmentInfo> colors = {attachment(
                     t.hdrImage->view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, false)};
                 if (debug)
                     for (vk::Image* im : t.debugImages)
                         colors.push_back(attachment(
                             im->view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, false));
                 VkRenderingAttachmentInfo depth = attachment(
                     t.depthImage->view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, false);
                 VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                 const vk::ImageDesc& desc = t.hdrImage->desc();
                 info.renderArea = {{0, 0}, {desc.width, desc.height}};
                 info.layerCount = 1;
                 info.colorAttachmentCount = uint32_t(colors.size());
                 info.pColorAttachments = colors.data();
                 info.pDepthAttachment = &depth;
                 mCtx.fn().cmdBeginRendering(cmd, &info);
                 setViewport(cmd, desc.width, desc.height);
                 // anti-aliased: only the pixels strands cover entirely (hair_fringe adds
                 // the rest)
                 const auto pipeline = [aa, debug, ribbons](const HairShadedPipelines& p) {
                     return aa      ? p.aaCore.get()
                            : debug ? p.debug[ribbons].get()
                                    : p.opaque[ribbons].get();
                 };
                 drawCamera(cmd, t, pipeline, mOpacitySet, false, aa || mRibbons);
                 mCtx.fn().cmdEndRendering(cmd);
             }});
    }
    const bool fringe = aa && anyOpaque;
    if (!fringe && !mOit) return;
    const int rAccum = g.addResource("hair_oit_accum", &mAccum);
    const int rWeight = g.addResource("hair_oit_weight", &mWeight);
    // Begins rendering into the accumulation targets (cleared by the first pass that draws
    // into them), depth tested against the meshes and opaque hair.
    auto beginAccumulation = [this, t](VkCommandBuffer cmd, bool clear) {
        VkRenderingAttachmentInfo colors[2] = {
            attachment(mAccum.view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, clear),
            attachment(mWeight.view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, clear)};
        colors[0].clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}}; // a: revealage
        colors[1].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
        VkRenderingAttachmentInfo depth =
            attachment(t.depthImage->view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, false);
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = mRect; // cleared (and composited) where strands can be only
        info.layerCount = 1;
        info.colorAttachmentCount = 2;
        info.pColorAttachments = colors;
        info.pDepthAttachment = &depth;
        mCtx.fn().cmdBeginRendering(cmd, &info);
        setViewport(cmd, mWidth, mHeight);
        vkCmdSetScissor(cmd, 0, 1, &mRect);
    };
    const std::vector<ResourceUse> accumulates = {
        {rAccum, Use::ColorWrite}, {rWeight, Use::ColorWrite}, {t.depth, Use::DepthWrite}};
    if (fringe)
        g.addPass(
            {"hair_fringe", shadingReads, accumulates,
             [this, t, beginAccumulation](VkCommandBuffer cmd) {
                 if (!mPipes.sampleMasks) { // coverage as independent alphas
                     beginAccumulation(cmd, true);
                     drawCamera(
                         cmd, t, [](const HairShadedPipelines& p) { return p.aaFringe[0].get(); },
                         mOpacitySet, false, true);
                     mCtx.fn().cmdEndRendering(cmd);
                     return;
                 }
                 // no depth at any sample point (all ones), no point covered, sums 0
                 vk::transition(mCtx, cmd, mSamples, VK_IMAGE_LAYOUT_GENERAL,
                                VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
                 VkClearColorValue clear{};
                 for (uint32_t layer = 0; layer < mSamples.desc().layers; ++layer) {
                     clear.uint32[0] = layer < kHairAaDepthSamples ? ~0u : 0u;
                     const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, layer, 1};
                     vkCmdClearColorImage(cmd, mSamples.get(), VK_IMAGE_LAYOUT_GENERAL, &clear, 1,
                                          &range);
                 }
                 // pass 0 writes the nearest depths, pass 1 reads them once all are in
                 for (int i = 0; i < 2; ++i) {
                     vk::transition(mCtx, cmd, mSamples, VK_IMAGE_LAYOUT_GENERAL,
                                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
                     beginAccumulation(cmd, i == 0);
                     drawCamera(
                         cmd, t, [i](const HairShadedPipelines& p) { return p.aaFringe[i].get(); },
                         mOpacitySet, false, true);
                     mCtx.fn().cmdEndRendering(cmd);
                 }
             }});
    if (mOit)
        g.addPass({"hair_oit", shadingReads, accumulates,
                   [this, t, ribbons, aa, fringe, beginAccumulation](VkCommandBuffer cmd) {
                       beginAccumulation(cmd, !fringe);
                       drawCamera(
                           cmd, t,
                           [aa, ribbons](const HairShadedPipelines& p) {
                               return aa ? p.aaOit.get() : p.oit[ribbons].get();
                           },
                           mOpacitySet, true, aa || mRibbons);
                       mCtx.fn().cmdEndRendering(cmd);
                   }});
    g.addPass({"hair_composite",
               {{rAccum, Use::Sampled}, {rWeight, Use::Sampled}},
               {{t.hdr, Use::ColorWrite}},
               [this, t](VkCommandBuffer cmd) {
                   VkRenderingAttachmentInfo color = attachment(
                       t.hdrImage->view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, false);
                   VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                   info.renderArea = mRect; // no strand elsewhere: nothing to composite
                   info.layerCount = 1;
                   info.colorAttachmentCount = 1;
                   info.pColorAttachments = &color;
                   mCtx.fn().cmdBeginRendering(cmd, &info);
                   setViewport(cmd, mWidth, mHeight);
                   vkCmdSetScissor(cmd, 0, 1, &mRect);
                   vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipes.composite);
                   vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                           mPipes.compositeLayout, 0, 1, &mOitSet, 0, nullptr);
                   vkCmdDraw(cmd, 3, 1, 0, 0);
                   mCtx.fn().cmdEndRendering(cmd);
               }});
}

HairDomInfo HairPasses::domInfo(int lightIndex) {
    if (lightIndex < 0 || size_t(lightIndex) >= mLastDoms.size() ||
        mLastDoms[size_t(lightIndex)].size == 0)
        throw InvalidArgument("light " + std::to_string(lightIndex) +
                              " had no deep opacity map in the last frame");
    HairDomInfo info = mLastDoms[size_t(lightIndex)];
    int slot = 0;
    while (mDoms[size_t(slot)].light != lightIndex) ++slot;
    const uint32_t size = mDomOpacity.desc().width;
    vk::Buffer buffer(&mCtx, VkDeviceSize(size) * size * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      vk::MemoryUsage::Readback);
    mCtx.immediate([&](VkCommandBuffer cmd) {
        const UseState s = useState(Use::TransferRead, false);
        vk::transition(mCtx, cmd, mDomOpacity, s.layout, s.stage, s.access);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, uint32_t(slot), 1};
        region.imageExtent = {size, size, 1};
        vkCmdCopyImageToBuffer(cmd, mDomOpacity.get(), s.layout, buffer.get(), 1, &region);
    });
    info.texels.resize(size_t(size) * size * 4);
    std::memcpy(info.texels.data(), buffer.mapped(), info.texels.size() * sizeof(float));
    return info;
}

} // namespace weft::render
