#pragma once
// GPU copies of hair strands (per-point position, tangent, thickness, opacity, colour, strand id
// and index buffers for lines and ribbons), uploaded once and kept while the strands live.
#include <memory>
#include <unordered_map>

#include <weft/Scene.h>

#include "vk/Resources.h"

namespace weft::render {

struct HairGpu {
    std::weak_ptr<const HairStrands> source;
    vk::Buffer vertices; // GpuHairVertex per point (storage buffer)
    vk::Buffer lines;    // 2 indices per segment; an index is 2 * point + side
    vk::Buffer ribbons;  // 6 indices per segment (two triangles), made on first use
    uint32_t lineIndexCount = 0;
    uint32_t ribbonIndexCount = 0;
    bool transparent = false; // some point has transparency > 0
    float maxThickness =
        0.0f; // the thickest point's (a ribbon's width per RenderSettings::hairWidth)
};

class HairGpuCache {
public:
    explicit HairGpuCache(vk::Context& ctx) : mCtx(ctx) {}
    HairGpu& get(const HairStrandsPtr& strands, bool ribbons);
    /// Drops GPU copies whose strands are gone (destruction deferred until the GPU is done).
    void evictExpired();

private:
    vk::Buffer upload(const void* data, VkDeviceSize bytes, VkBufferUsageFlags usage);

    vk::Context& mCtx;
    std::unordered_map<const HairStrands*, HairGpu> mEntries;
};

} // namespace weft::render
