#pragma once
// One-shot compute work over storage buffers, as the offline GPU tools (IBL filters) do it: a
// pipeline whose set 0 holds storage buffers at bindings 0..n-1 plus push constants, one
// descriptor set for a given list of buffers, and a submission that waits and leaves the shader
// writes visible to the host (read back through a mapped Readback buffer).
#include <functional>
#include <vector>

#include "vk/Resources.h"

namespace weft::vk {

struct StorageCompute {
    DescriptorSetLayout setLayout;
    PipelineLayout layout;
    Pipeline pipeline;
    DescriptorPool pool;
    VkDescriptorSet set = VK_NULL_HANDLE; // buffers[k] at binding k (whole buffer)
};

/// The pipeline of the embedded shader `shader` (path relative to glsl/) with `buffers` bound as
/// storage buffers 0..n-1 of set 0 and `pushConstantBytes` of push constants.
StorageCompute createStorageCompute(Context& ctx, const char* shader,
                                    const std::vector<const Buffer*>& buffers,
                                    uint32_t pushConstantBytes);

/// Records the pipeline and its set bound, then `record` (push constants, dispatches), then a
/// compute-write -> host-read barrier; submits, waits, and returns the wall milliseconds from
/// the start of recording to the end of the wait.
double runStorageCompute(Context& ctx, const StorageCompute& compute,
                         const std::function<void(VkCommandBuffer)>& record);

/// Makes the shader writes of the dispatches recorded so far visible to the reads and writes of
/// the next ones (a dispatch that adds to what the previous one wrote).
void computeToComputeBarrier(VkCommandBuffer cmd);

} // namespace weft::vk
