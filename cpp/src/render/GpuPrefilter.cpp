// The GGX chain on the GPU: the plan's clamped source mip levels the samples read (faces padded
// for seamless taps) and the exactly summed points of every level in one texel buffer, the
// samples in a storage buffer, one compute dispatch per output level
// (glsl/ibl/prefilter_ggx.comp), read back into a CubeMap. Level 0 (the plan's mirror level,
// computed on the CPU) is taken from the plan as it is; `dst` keeps its place unwritten.
#include <weft/IblGpu.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <weft/Error.h>

#include "ibl/CubeTexels.h"
#include "ibl/GgxPlan.h"
#include "ibl/GgxSamples.h"
#include "ibl/IblValidate.h"
#include "vk/ComputePipeline.h"

namespace weft {

namespace {

// Must match glsl/ibl/prefilter_ggx.comp.
struct PrefilterPush {
    int32_t outSize, outOffset, first, count, pointFirst, pointCount;
    float alpha2, invNorm;
};

// A point of the exact sum as the shader reads it: two RGBA texels, direction and radiance x
// solid angle.
struct GpuPoint {
    float dir[4], power[4];
};

// One sample as the shader reads it (std430): the half vector in the texel's frame, the weight
// of the second source level, and the two levels' texel offsets and sizes in the padded source
// (the same level twice, weight 0, when the lod is an integer).
struct GpuSample {
    float h[3], blend;
    int32_t offset0, size0, offset1, size1;
};

// The source chain as the shader reads it: the levels from `first` on (finer ones are read by no
// sample), each face with a one-texel border holding the seamless taps CubeMap::sample makes past
// an edge (the neighbouring face's texel; past a corner, the mean of the corner texel and its two
// neighbours across the edges), so the shader's bilinear taps need no wrapping. Texel (f, i, j),
// i, j in [-1, s], of a level at texel offset o lies at o + (f (s + 2) + j + 1) (s + 2) + i + 1;
// RGBA floats (A unused), one texel per element of a uniform texel buffer.
struct PaddedSource {
    int first = 0;
    std::vector<int64_t> offsets; // texel offset of each level >= first; [levels]: total texels
};

PaddedSource paddedSource(const CubeMap& chain, int first) {
    PaddedSource p{first, std::vector<int64_t>(size_t(chain.levels()) + 1, 0)};
    for (int l = first; l < chain.levels(); ++l) {
        const int64_t w = chain.levelSize(l) + 2;
        p.offsets[size_t(l) + 1] = p.offsets[size_t(l)] + 6 * w * w;
    }
    return p;
}

void writePadded(const CubeMap& chain, const PaddedSource& padded, float* out) {
    for (int l = padded.first; l < chain.levels(); ++l) {
        const int s = chain.levelSize(l), p = s + 2;
        for (int f = 0; f < 6; ++f)
            for (int j = -1; j <= s; ++j) {
                float* row = out + (padded.offsets[size_t(l)] + int64_t(f * p + j + 1) * p) * 4;
                for (int i = -1; i <= s; ++i) {
                    float* o = row + size_t(i + 1) * 4;
                    const int ci = std::clamp(i, 0, s - 1), cj = std::clamp(j, 0, s - 1);
                    const float* t = chain.texelWrapped(f, i, j, l);
                    for (int k = 0; k < 3; ++k) o[k] = t[k];
                    if (ci != i && cj != j) { // same expression as CubeMap::sample
                        const float* a = chain.texel(f, ci, cj, l);
                        const float* b = chain.texelWrapped(f, i, cj, l);
                        const float* d = chain.texelWrapped(f, ci, j, l);
                        for (int k = 0; k < 3; ++k) o[k] = (a[k] + b[k] + d[k]) / 3.0f;
                    }
                    o[3] = 0.0f;
                }
            }
    }
}

// A lookup at `lod` as CubeMap::sampleLod makes it: level l0, or l0 and l1 = l0 + 1 blended.
struct LodLookup {
    glm::vec3 h;
    int l0, l1;
    float blend;
};

LodLookup lodLookup(const glm::vec3& h, float lod, int levels) {
    lod = std::clamp(std::isfinite(lod) ? lod : 0.0f, 0.0f, float(levels - 1));
    const int l0 = int(std::floor(lod));
    const float f = lod - float(l0);
    if (f <= 0.0f || l0 + 1 >= levels) return {h, l0, l0, 0.0f};
    return {h, l0, l0 + 1, f};
}

VkDescriptorSet bindBuffers(vk::Context& ctx, vk::DescriptorPool& pool,
                            VkDescriptorSetLayout layout, VkBufferView source,
                            const vk::Buffer* const (&buffers)[3]) {
    VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2}};
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.maxSets = 1;
    info.poolSizeCount = 2;
    info.pPoolSizes = sizes;
    VkDescriptorPool handle;
    VK_CHECK(vkCreateDescriptorPool(ctx.device(), &info, nullptr, &handle));
    pool = vk::DescriptorPool(&ctx, handle, vkDestroyDescriptorPool);
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &layout;
    VkDescriptorSet set;
    VK_CHECK(vkAllocateDescriptorSets(ctx.device(), &alloc, &set));
    VkDescriptorBufferInfo infos[3];
    VkWriteDescriptorSet writes[3];
    for (uint32_t k = 0; k < 3; ++k) {
        infos[k] = {buffers[k]->get(), 0, VK_WHOLE_SIZE};
        writes[k] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[k].dstSet = set;
        writes[k].dstBinding = k;
        writes[k].descriptorCount = 1;
        writes[k].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[k].pBufferInfo = &infos[k];
    }
    writes[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    writes[0].pBufferInfo = nullptr;
    writes[0].pTexelBufferView = &source;
    vkUpdateDescriptorSets(ctx.device(), 3, writes, 0, nullptr);
    return set;
}

} // namespace

CubeMap prefilterGgxGpu(const CubeMap& radiance, int size, int levels, int samples,
                        double* dispatchMs) {
    requireGgxArguments(radiance, size, levels, samples);
    if (samples > kMaxGpuGgxSamples) // the shader loops over a level's samples once per texel
        throw InvalidArgument("GGX prefilter on the GPU: at most " +
                              std::to_string(kMaxGpuGgxSamples) + " samples (got " +
                              std::to_string(samples) + "); use prefilterGgx for more");
    CubeMap out(size);
    out.buildMips(); // allocates every level; the dispatches overwrite those kept
    out.keepLevels(levels);
    const GgxPlan plan = ggxPlan(radiance, size, levels, samples);
    const CubeMap& chain = plan.clamped;

    // The samples whose reflected direction lies below the horizon (n.l = 2 h.z^2 - 1 <= 0 for
    // every texel) are dropped; those near 0 stay, the shader tests n.l per texel as the CPU does.
    std::vector<std::vector<LodLookup>> lookups(static_cast<size_t>(levels));
    int firstRead = std::max(chain.levels() - 1, 0);
    for (int m = 1; m < levels; ++m) {
        auto& level = lookups[size_t(m)];
        for (const GgxSample& g : plan.level[size_t(m)].samples)
            if (2.0f * g.h.z * g.h.z - 1.0f > -1e-3f)
                level.push_back(lodLookup(g.h, g.lod, chain.levels()));
        for (const LodLookup& k : level) firstRead = std::min(firstRead, k.l0);
    }
    const PaddedSource padded = paddedSource(chain, firstRead);

    auto shared = vk::Context::shared();
    vk::Context& ctx = *shared;
    const int64_t srcTexels = padded.offsets.back();
    std::vector<GpuSample> table;
    std::vector<GpuPoint> pointTable;
    std::vector<PrefilterPush> pushes;
    int32_t dstOffset = int32_t(out.floatCount(0));
    for (int m = 1; m < levels; ++m) {
        const GgxLevelPlan& p = plan.level[size_t(m)];
        const int s = out.levelSize(m);
        PrefilterPush push{s,
                           dstOffset,
                           int32_t(table.size()),
                           0,
                           int32_t(srcTexels + 2 * int64_t(pointTable.size())),
                           int32_t(p.points.size()),
                           p.alpha * p.alpha,
                           p.invNorm};
        dstOffset += int32_t(out.floatCount(m));
        for (const LodLookup& k : lookups[size_t(m)])
            table.push_back({{k.h.x, k.h.y, k.h.z},
                             k.blend,
                             int32_t(padded.offsets[size_t(k.l0)]),
                             chain.levelSize(k.l0),
                             int32_t(padded.offsets[size_t(k.l1)]),
                             chain.levelSize(k.l1)});
        for (const GgxPoint& q : p.points)
            pointTable.push_back(
                {{q.dir.x, q.dir.y, q.dir.z, 0.0f}, {q.power.x, q.power.y, q.power.z, 0.0f}});
        push.count = int32_t(table.size()) - push.first;
        pushes.push_back(push);
    }

    size_t dstFloats = 0;
    for (int l = 0; l < out.levels(); ++l) dstFloats += out.floatCount(l);
    const int64_t allTexels = srcTexels + 2 * int64_t(pointTable.size());
    if (allTexels > int64_t(ctx.properties().limits.maxTexelBufferElements) ||
        allTexels > int64_t(INT32_MAX))
        throw InvalidArgument("GGX prefilter on the GPU: the source levels read and the points (" +
                              std::to_string(allTexels) + " texels) exceed the device's texel " +
                              "buffer limit; use a smaller source or prefilterGgx");

    vk::Buffer src(&ctx, size_t(std::max<int64_t>(allTexels, 1)) * 4 * sizeof(float),
                   VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, vk::MemoryUsage::Upload);
    vk::Buffer dst(&ctx, dstFloats * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                   vk::MemoryUsage::Readback);
    vk::Buffer sampleBuffer(&ctx, std::max<size_t>(table.size(), 1) * sizeof(GpuSample),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::Upload);
    writePadded(chain, padded, static_cast<float*>(src.mapped()));
    if (!table.empty()) sampleBuffer.write(table.data(), table.size() * sizeof(GpuSample));
    if (!pointTable.empty())
        std::memcpy(static_cast<float*>(src.mapped()) + srcTexels * 4, pointTable.data(),
                    pointTable.size() * sizeof(GpuPoint));

    const vk::ComputeProgram& program =
        vk::cachedComputeProgram(ctx, "ibl/prefilter_ggx.comp",
                                 {{0, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
                                  {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                  {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
                                 sizeof(PrefilterPush));
    const VkPipelineLayout layout = program.layout;
    const VkPipeline pipeline = program.pipeline;
    const VkDescriptorSetLayout setLayout = program.setLayout;
    VkBufferViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    viewInfo.buffer = src.get();
    viewInfo.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    viewInfo.range = VK_WHOLE_SIZE;
    VkBufferView viewHandle;
    VK_CHECK(vkCreateBufferView(ctx.device(), &viewInfo, nullptr, &viewHandle));
    const vk::Handle<VkBufferView> view(&ctx, viewHandle, vkDestroyBufferView);
    vk::DescriptorPool pool;
    const VkDescriptorSet set =
        bindBuffers(ctx, pool, setLayout, view, {&src, &dst, &sampleBuffer});

    const auto start = std::chrono::steady_clock::now();
    ctx.immediate([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0,
                                nullptr);
        for (const PrefilterPush& push : pushes) {
            vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            vkCmdDispatch(cmd, uint32_t((6 * push.outSize * push.outSize + 63) / 64), 1, 1);
        }
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                             0, 1, &barrier, 0, nullptr, 0, nullptr);
    });
    if (dispatchMs) {
        const auto elapsed = std::chrono::steady_clock::now() - start;
        *dispatchMs = std::chrono::duration<double, std::milli>(elapsed).count();
    }
    std::memcpy(out.data(0), plan.mirror.data(), out.floatCount(0) * sizeof(float));
    size_t offset = out.floatCount(0);
    for (int m = 1; m < levels; ++m) {
        std::memcpy(out.data(m), static_cast<const float*>(dst.mapped()) + offset,
                    out.floatCount(m) * sizeof(float));
        offset += out.floatCount(m);
    }
    return out;
}

} // namespace weft
