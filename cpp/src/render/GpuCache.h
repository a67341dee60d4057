#pragma once
// GPU copies of scene meshes and textures, uploaded once and kept while their CPU objects live.
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include <weft/Scene.h>

#include "vk/Resources.h"

namespace weft::render {

struct MeshGpu {
    std::weak_ptr<const Mesh> source;
    vk::Buffer vertices; // interleaved position, normal, uv (32 bytes)
    vk::Buffer indices;  // uint32
    uint32_t indexCount = 0;
};

struct TextureGpu {
    std::weak_ptr<const Texture> source;
    vk::Image image;
    VkDescriptorSet set = VK_NULL_HANDLE;
    size_t pool = 0;
};

class GpuCache {
public:
    GpuCache(vk::Context& ctx, VkDescriptorSetLayout materialLayout, VkSampler sampler);
    ~GpuCache();

    const MeshGpu& mesh(const MeshPtr& mesh);
    /// Material descriptor set (set 1) for a base-colour texture; null gives white.
    VkDescriptorSet texture(const TexturePtr& texture);
    /// The image view of a texture (uploaded on first use); null gives white.
    VkImageView textureView(const TexturePtr& texture);
    /// Drops GPU copies whose CPU objects are gone (deferred until the GPU is done).
    void evictExpired();

    size_t meshCount() const { return mMeshes.size(); }
    size_t textureCount() const { return mTextures.size(); }

private:
    void upload(const vk::Buffer& dst, const void* data, VkDeviceSize bytes);
    TextureGpu makeTexture(const ImageU8& rgba, bool srgb, bool mipmaps);
    TextureGpu& entry(const TexturePtr& texture);
    VkDescriptorSet allocateSet(size_t& poolIndex);
    void freeSet(VkDescriptorSet set, size_t pool);

    vk::Context& mCtx;
    VkDescriptorSetLayout mLayout;
    VkSampler mSampler;
    std::vector<vk::DescriptorPool> mPools;
    std::unordered_map<const Mesh*, MeshGpu> mMeshes;
    std::unordered_map<uint64_t, TextureGpu> mTextures;
    TextureGpu mWhite;
};

} // namespace weft::render
