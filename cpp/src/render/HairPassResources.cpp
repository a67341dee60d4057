// HairPasses' images and descriptor sets: the placeholders bound where nothing was drawn, the
// deep opacity, OIT and sample images sized to the frame, and each frame slot's sets.
#include <algorithm>

#include "render/HairPasses.h"
#include "render/PassSetup.h"
#include "render/RenderTargets.h"
#include "render/ScenePipelines.h"

namespace weft::render {

namespace {

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

} // namespace weft::render
