#pragma once
// GPU copies of scene meshes and textures, uploaded once and kept while their CPU objects live.
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <unordered_map>
#include <vector>

#include <weft/Scene.h>

#include "vk/Resources.h"

namespace weft::render {

/// Interleaved vertex: position, normal, uv, tangent (xyz + handedness w), 48 bytes.
constexpr uint32_t kVertexStride = 48;

struct MeshGpu {
    std::weak_ptr<const Mesh> source;
    vk::Buffer vertices; // kVertexStride bytes per vertex
    vk::Buffer indices;  // uint32
    uint32_t indexCount = 0;
    uint64_t contentId = 0; // unique per upload: equal ids mean equal geometry
};

struct TextureGpu {
    std::weak_ptr<const Texture> source;
    vk::Image image;
};

/// A deformable mesh's (a cloth's) surface as last uploaded.
struct DeformableGpu {
    std::weak_ptr<const DeformableMesh> source;
    uint64_t version = 0;
    MeshGpu mesh;
};

/// The descriptor set (set 1) of a material's textures: base colour, normal map, specular map.
struct MaterialSetGpu {
    static constexpr int kTextures = 4;              // base colour, normal, specular, ambient
    std::weak_ptr<const Texture> sources[kTextures]; // empty where the material has none
    bool used[kTextures] = {false, false, false, false};
    VkDescriptorSet set = VK_NULL_HANDLE;
    size_t pool = 0;
};

class GpuCache {
public:
    GpuCache(vk::Context& ctx, VkDescriptorSetLayout materialLayout, VkSampler sampler);
    ~GpuCache();

    const MeshGpu& mesh(const MeshPtr& mesh);
    /// A deformable mesh's (a cloth's) current surface (positions, normals, UVs, tangents, the
    /// triangles left by holes and tears). Rebuilt into new host-visible buffers (the old ones
    /// are retired after the frames that use them) only when its meshVersion() changed;
    /// `uploadedBytes` grows by what was written.
    const MeshGpu& deformable(const std::shared_ptr<const DeformableMesh>& source,
                              uint64_t& uploadedBytes);
    /// Material descriptor set (set 1): base colour (none: white), normal map (none: flat),
    /// specular map (none: white), ambient map (none: white, unused).
    VkDescriptorSet materialSet(const Material& material);
    /// The image view of a texture (uploaded on first use); null gives white.
    VkImageView textureView(const TexturePtr& texture) {
        return entry(texture, mWhite).image.view();
    }
    /// Drops GPU copies whose CPU objects are gone (deferred until the GPU is done).
    void evictExpired();

    size_t meshCount() const { return mMeshes.size(); }
    size_t textureCount() const { return mTextures.size(); }

private:
    TextureGpu makeTexture(const ImageU8& rgba, bool srgb, bool mipmaps);
    TextureGpu& entry(const TexturePtr& texture, const TextureGpu& fallback);
    VkDescriptorSet allocateSet(size_t& poolIndex);
    void freeSet(VkDescriptorSet set, size_t pool);

    vk::Context& mCtx;
    VkDescriptorSetLayout mLayout;
    VkSampler mSampler;
    std::vector<vk::DescriptorPool> mPools;
    std::unordered_map<const Mesh*, MeshGpu> mMeshes;
    std::unordered_map<const DeformableMesh*, DeformableGpu> mDeformables;
    std::unordered_map<uint64_t, TextureGpu> mTextures;
    std::map<std::array<uint64_t, MaterialSetGpu::kTextures>, MaterialSetGpu>
        mMaterialSets; // by texture ids
    TextureGpu mWhite, mFlatNormal;
};

} // namespace weft::render
