#include "render/GpuCache.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

namespace weft::render {

GpuCache::GpuCache(vk::Context& ctx, VkDescriptorSetLayout materialLayout, VkSampler sampler)
    : mCtx(ctx), mLayout(materialLayout), mSampler(sampler) {
    ImageU8 white(1, 1, 4);
    std::fill(white.pixels.begin(), white.pixels.end(), uint8_t(255));
    mWhite = makeTexture(white, true, false);
    ImageU8 flat(1, 1, 4);
    const uint8_t up[4] = {128, 128, 255, 255};
    std::copy(up, up + 4, flat.pixels.begin());
    mFlatNormal = makeTexture(flat, false, false);
}

GpuCache::~GpuCache() {
    for (auto& [key, m] : mMaterialSets) freeSet(m.set, m.pool);
}

namespace {

uint64_t nextContentId() {
    static std::atomic<uint64_t> counter{0};
    return ++counter;
}

// Interleaves a mesh's vertices in the kVertexStride layout.
std::vector<float> packVertices(const Mesh& mesh) {
    const std::vector<glm::vec4> tangents = computeTangents(mesh);
    constexpr size_t kFloats = kVertexStride / sizeof(float);
    std::vector<float> vertices(mesh.vertexCount() * kFloats);
    for (size_t i = 0; i < mesh.vertexCount(); ++i) {
        float* v = &vertices[i * kFloats];
        std::memcpy(v, &mesh.positions[i], 12);
        std::memcpy(v + 3, &mesh.normals[i], 12);
        std::memcpy(v + 6, &mesh.uvs[i], 8);
        std::memcpy(v + 8, &tangents[i], 16);
    }
    return vertices;
}

} // namespace

const MeshGpu& GpuCache::deformable(const std::shared_ptr<const DeformableMesh>& source,
                                    uint64_t& uploadedBytes) {
    DeformableGpu& slot = mDeformables[source.get()];
    if (slot.source.lock() == source && slot.version == source->meshVersion()) return slot.mesh;
    const Mesh mesh = source->surface();
    const std::vector<float> vertices = packVertices(mesh);
    const VkDeviceSize vbytes = vertices.size() * sizeof(float);
    const VkDeviceSize ibytes = std::max<size_t>(mesh.indices.size(), 1) * sizeof(uint32_t);
    MeshGpu gpu;
    gpu.vertices =
        vk::Buffer(&mCtx, vbytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, vk::MemoryUsage::Upload);
    gpu.indices =
        vk::Buffer(&mCtx, ibytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, vk::MemoryUsage::Upload);
    gpu.vertices.write(vertices.data(), vbytes);
    if (!mesh.indices.empty()) gpu.indices.write(mesh.indices.data(), mesh.indices.size() * 4);
    gpu.indexCount = uint32_t(mesh.indices.size());
    gpu.contentId = nextContentId();
    uploadedBytes += vbytes + mesh.indices.size() * 4;
    slot.source = source;
    slot.version = source->meshVersion();
    slot.mesh = std::move(gpu);
    return slot.mesh;
}

const MeshGpu& GpuCache::mesh(const MeshPtr& mesh) {
    auto it = mMeshes.find(mesh.get());
    if (it != mMeshes.end() && !it->second.source.expired() && it->second.source.lock() == mesh)
        return it->second;
    const std::vector<float> vertices = packVertices(*mesh);
    MeshGpu gpu;
    gpu.source = mesh;
    const VkDeviceSize vbytes = vertices.size() * sizeof(float);
    const VkDeviceSize ibytes = mesh->indices.size() * sizeof(uint32_t);
    gpu.vertices = vk::Buffer(&mCtx, vbytes,
                              VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              vk::MemoryUsage::GpuOnly);
    gpu.indices = vk::Buffer(&mCtx, ibytes,
                             VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             vk::MemoryUsage::GpuOnly);
    vk::uploadBuffer(mCtx, gpu.vertices, vertices.data(), vbytes);
    vk::uploadBuffer(mCtx, gpu.indices, mesh->indices.data(), ibytes);
    gpu.indexCount = uint32_t(mesh->indices.size());
    gpu.contentId = nextContentId();
    auto& slot = mMeshes[mesh.get()];
    slot = std::move(gpu);
    return slot;
}

VkDescriptorSet GpuCache::allocateSet(size_t& poolIndex) {
    for (size_t attempt = 0; attempt < 2; ++attempt) {
        if (!mPools.empty()) {
            VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
            info.descriptorPool = mPools.back();
            info.descriptorSetCount = 1;
            info.pSetLayouts = &mLayout;
            VkDescriptorSet set;
            VkResult r = vkAllocateDescriptorSets(mCtx.device(), &info, &set);
            if (r == VK_SUCCESS) {
                poolIndex = mPools.size() - 1;
                return set;
            }
            if (r != VK_ERROR_OUT_OF_POOL_MEMORY && r != VK_ERROR_FRAGMENTED_POOL) VK_CHECK(r);
        }
        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 256};
        VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
        info.maxSets = 256;
        info.poolSizeCount = 1;
        info.pPoolSizes = &size;
        VkDescriptorPool pool;
        VK_CHECK(vkCreateDescriptorPool(mCtx.device(), &info, nullptr, &pool));
        mPools.emplace_back(&mCtx, pool, vkDestroyDescriptorPool);
    }
    throw Error("could not allocate a texture descriptor set");
}

void GpuCache::freeSet(VkDescriptorSet set, size_t pool) {
    if (set == VK_NULL_HANDLE) return;
    VkDevice device = mCtx.device();
    VkDescriptorPool p = mPools.at(pool);
    // Pools are retired after sets (later retire -> later destroy), so `p` is still alive.
    mCtx.retire([device, p, set] { vkFreeDescriptorSets(device, p, 1, &set); });
}

TextureGpu GpuCache::makeTexture(const ImageU8& rgba, bool srgb, bool mipmaps) {
    const VkFormat format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(mCtx.physicalDevice(), format, &fp);
    const VkFormatFeatureFlags blit = VK_FORMAT_FEATURE_BLIT_SRC_BIT |
                                      VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                      VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    uint32_t levels = 1;
    if (mipmaps && (fp.optimalTilingFeatures & blit) == blit)
        levels = 1 + uint32_t(std::floor(std::log2(double(std::max(rgba.width, rgba.height)))));

    TextureGpu t;
    vk::ImageDesc desc;
    desc.width = uint32_t(rgba.width);
    desc.height = uint32_t(rgba.height);
    desc.mipLevels = levels;
    desc.format = format;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                 (levels > 1 ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
    t.image = vk::Image(&mCtx, desc);
    const VkDeviceSize bytes = rgba.pixels.size();
    vk::Buffer staging(&mCtx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUsage::Upload);
    staging.write(rgba.pixels.data(), bytes);

    VkImage image = t.image.get();
    auto barrier = [&](VkCommandBuffer cmd, uint32_t mip, VkImageLayout from, VkImageLayout to,
                       VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                       VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
        VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        b.srcStageMask = srcStage;
        b.srcAccessMask = srcAccess;
        b.dstStageMask = dstStage;
        b.dstAccessMask = dstAccess;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 1, 0, 1};
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = 1;
        dep.pImageMemoryBarriers = &b;
        mCtx.fn().cmdPipelineBarrier2(cmd, &dep);
    };
    mCtx.immediate([&](VkCommandBuffer cmd) {
        for (uint32_t m = 0; m < levels; ++m)
            barrier(cmd, m, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                    VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {desc.width, desc.height, 1};
        vkCmdCopyBufferToImage(cmd, staging.get(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                               &region);
        int32_t w = int32_t(desc.width), h = int32_t(desc.height);
        for (uint32_t m = 1; m < levels; ++m) {
            barrier(cmd, m - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT);
            VkImageBlit blitRegion{};
            blitRegion.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m - 1, 0, 1};
            blitRegion.srcOffsets[1] = {w, h, 1};
            w = std::max(1, w / 2);
            h = std::max(1, h / 2);
            blitRegion.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
            blitRegion.dstOffsets[1] = {w, h, 1};
            vkCmdBlitImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blitRegion, VK_FILTER_LINEAR);
            barrier(cmd, m - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        }
        barrier(cmd, levels - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    });
    t.image.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    t.image.stage = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    t.image.access = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;

    return t;
}

TextureGpu& GpuCache::entry(const TexturePtr& texture, const TextureGpu& fallback) {
    if (!texture) return const_cast<TextureGpu&>(fallback);
    auto it = mTextures.find(texture->id());
    if (it != mTextures.end()) return it->second;
    TextureGpu t = makeTexture(texture->image(), texture->srgb(), texture->mipmaps());
    t.source = texture;
    return mTextures.emplace(texture->id(), std::move(t)).first->second;
}

VkDescriptorSet GpuCache::materialSet(const Material& material) {
    constexpr int n = MaterialSetGpu::kTextures;
    const TexturePtr textures[n] = {material.texture, material.normalMap, material.specularMap,
                                    material.ambientMap};
    const TextureGpu* fallbacks[n] = {&mWhite, &mFlatNormal, &mWhite, &mWhite};
    std::array<uint64_t, n> key{};
    for (int i = 0; i < n; ++i) key[size_t(i)] = textures[i] ? textures[i]->id() : 0;
    auto it = mMaterialSets.find(key);
    if (it != mMaterialSets.end()) return it->second.set;
    MaterialSetGpu m;
    m.set = allocateSet(m.pool);
    VkDescriptorImageInfo infos[n];
    VkWriteDescriptorSet writes[n];
    for (int i = 0; i < n; ++i) {
        m.sources[i] = textures[i];
        m.used[i] = textures[i] != nullptr;
        infos[i] = {mSampler, entry(textures[i], *fallbacks[i]).image.view(),
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        writes[i] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[i].dstSet = m.set;
        writes[i].dstBinding = uint32_t(i);
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        writes[i].pImageInfo = &infos[i];
    }
    vkUpdateDescriptorSets(mCtx.device(), n, writes, 0, nullptr);
    return mMaterialSets.emplace(key, m).first->second.set;
}

void GpuCache::evictExpired() {
    for (auto it = mMeshes.begin(); it != mMeshes.end();)
        it = it->second.source.expired() ? mMeshes.erase(it) : std::next(it);
    for (auto it = mDeformables.begin(); it != mDeformables.end();)
        it = it->second.source.expired() ? mDeformables.erase(it) : std::next(it);
    for (auto it = mMaterialSets.begin(); it != mMaterialSets.end();) {
        const MaterialSetGpu& m = it->second;
        bool expired = false;
        for (int i = 0; i < MaterialSetGpu::kTextures; ++i)
            expired |= m.used[i] && m.sources[i].expired();
        if (expired) {
            freeSet(m.set, m.pool);
            it = mMaterialSets.erase(it);
        } else {
            ++it;
        }
    }
    // Images are retired by their RAII wrappers after the frames that may still sample them.
    for (auto it = mTextures.begin(); it != mTextures.end();)
        it = it->second.source.expired() ? mTextures.erase(it) : std::next(it);
}

} // namespace weft::render
