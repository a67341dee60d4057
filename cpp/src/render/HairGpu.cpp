#include "render/HairGpu.h"

#include <algorithm>

#include <weft/HairGeometry.h>

#include "render/HairGpuTypes.h"

namespace weft::render {

vk::Buffer HairGpuCache::upload(const void* data, VkDeviceSize bytes, VkBufferUsageFlags usage) {
    vk::Buffer dst(&mCtx, bytes, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                   vk::MemoryUsage::GpuOnly);
    vk::uploadBuffer(mCtx, dst, data, bytes);
    return dst;
}

HairGpu& HairGpuCache::get(const HairStrandsPtr& strands, bool ribbons) {
    auto it = mEntries.find(strands.get());
    if (it == mEntries.end() || it->second.source.lock() != strands) {
        const HairStrands& h = *strands;
        const std::vector<glm::vec3> tangents = strandTangents(h);
        const std::vector<uint64_t> offsets = h.offsets();
        std::vector<GpuHairVertex> vertices(h.pointCount());
        std::vector<uint32_t> lines;
        lines.reserve(2 * (h.pointCount() - (offsets.size() - 1)));
        HairGpu gpu;
        gpu.source = strands;
        for (size_t s = 0; s + 1 < offsets.size(); ++s) {
            for (uint64_t i = offsets[s]; i < offsets[s + 1]; ++i) {
                const float thickness = h.thickness.empty() ? h.defaultThickness : h.thickness[i];
                const float transparency =
                    h.transparency.empty() ? h.defaultTransparency : h.transparency[i];
                gpu.transparent |= transparency > 0.0f;
                gpu.maxThickness = std::max(gpu.maxThickness, thickness);
                vertices[i] = {glm::vec4(h.points[i], thickness),
                               glm::vec4(tangents[i], 1.0f - transparency),
                               h.colors.empty() ? h.defaultColor : h.colors[i], uint32_t(s)};
                if (i + 1 < offsets[s + 1]) {
                    lines.push_back(uint32_t(2 * i));
                    lines.push_back(uint32_t(2 * (i + 1)));
                }
            }
        }
        gpu.vertices = upload(vertices.data(), vertices.size() * sizeof(GpuHairVertex),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        gpu.lineIndexCount = uint32_t(lines.size());
        if (!lines.empty())
            gpu.lines = upload(lines.data(), lines.size() * sizeof(uint32_t),
                               VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        it = mEntries.insert_or_assign(strands.get(), std::move(gpu)).first;
    }
    HairGpu& gpu = it->second;
    if (ribbons && !gpu.ribbons && gpu.lineIndexCount > 0) {
        const std::vector<uint32_t> indices = ribbonIndices(*strands);
        gpu.ribbonIndexCount = uint32_t(indices.size());
        gpu.ribbons = upload(indices.data(), indices.size() * sizeof(uint32_t),
                             VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    }
    return gpu;
}

void HairGpuCache::evictExpired() {
    for (auto it = mEntries.begin(); it != mEntries.end();)
        it = it->second.source.expired() ? mEntries.erase(it) : std::next(it);
}

} // namespace weft::render
