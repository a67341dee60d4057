#pragma once
// One-shot compute work over storage buffers, as the offline GPU tools (IBL filters) do it: a
// pipeline whose set 0 holds storage buffers at bindings 0..n-1 plus push constants, one
// descriptor set for a given list of buffers, and a submission that waits and leaves the shader
// writes visible to the host (read back through a mapped Readback buffer).
#include <functional>
#include <vector>

#include "vk/Resources.h"

namespace weft::vk {

/// One storage buffer of a StorageCompute, bound whole, or (dynamicRange > 0) as a window of
/// dynamicRange bytes whose offset is given each time the set is bound: a buffer larger than
/// the device's maxStorageBufferRange processed part by part. The offsets must be multiples of
/// minStorageBufferOffsetAlignment (at most 256) and keep the window inside the buffer.
struct StorageBinding {
    const Buffer* buffer = nullptr;
    VkDeviceSize dynamicRange = 0;
};

struct StorageCompute {
    VkPipelineLayout layout =
        VK_NULL_HANDLE; // of the context's cached program (cachedComputeProgram)
    VkPipeline pipeline = VK_NULL_HANDLE;
    DescriptorPool pool;
    VkDescriptorSet set = VK_NULL_HANDLE; // bindings[k] at binding k
    uint32_t dynamicCount = 0;            // bindings with a dynamic offset
};

/// The pipeline of the embedded shader `shader` (path relative to glsl/) with `bindings` as
/// storage buffers 0..n-1 of set 0 and `pushConstantBytes` of push constants.
StorageCompute createStorageCompute(Context& ctx, const char* shader,
                                    const std::vector<StorageBinding>& bindings,
                                    uint32_t pushConstantBytes);

/// Binds the pipeline and its set, with one offset per dynamic binding (in binding order; none
/// given: all 0).
void bindStorageCompute(VkCommandBuffer cmd, const StorageCompute& compute,
                        const std::vector<uint32_t>& dynamicOffsets = {});

/// Records bindStorageCompute (offsets 0), then `record` (push constants, dispatches, rebinds),
/// then a compute-write -> host-read barrier; submits, waits, and returns the wall milliseconds
/// from the start of recording to the end of the wait.
double runStorageCompute(Context& ctx, const StorageCompute& compute,
                         const std::function<void(VkCommandBuffer)>& record);

/// Makes the shader writes of the dispatches recorded so far visible to the reads and writes of
/// the next ones (a dispatch that adds to what the previous one wrote).
void computeToComputeBarrier(VkCommandBuffer cmd);

} // namespace weft::vk
