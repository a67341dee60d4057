#pragma once
// Device-memory sub-allocator: large blocks per memory type (buffers and images in separate
// blocks, so bufferImageGranularity never matters), carved up by RangeAllocator. Host-visible
// blocks stay mapped. Big requests get a block of their own.
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "vk/RangeAllocator.h"
#include "vk/Vk.h"

namespace weft::vk {

struct Allocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;
    void* mapped = nullptr; // host pointer to `offset` when the memory is host-visible
    int block = -1;
    explicit operator bool() const { return memory != VK_NULL_HANDLE; }
};

enum class MemoryUsage {
    GpuOnly,  // device-local
    Upload,   // host-visible, coherent (staging, per-frame uniforms)
    Readback, // host-visible, preferably cached
};

class Allocator {
public:
    Allocator(VkPhysicalDevice physical, VkDevice device, VkDeviceSize blockSize = 64ull << 20);
    ~Allocator();

    Allocation allocate(const VkMemoryRequirements& req, MemoryUsage usage, bool linear);
    void free(const Allocation& allocation);

    struct Stats {
        size_t blocks = 0;
        VkDeviceSize reserved = 0;
        VkDeviceSize used = 0;
    };
    Stats stats() const;

private:
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;
        uint32_t typeIndex = 0;
        bool linear = true;
        bool dedicated = false;
        void* mapped = nullptr;
        std::unique_ptr<RangeAllocator> ranges;
    };
    uint32_t findType(uint32_t typeBits, MemoryUsage usage) const;

    VkDevice mDevice;
    VkPhysicalDeviceMemoryProperties mProps{};
    VkDeviceSize mBlockSize;
    mutable std::mutex mMutex;
    std::vector<Block> mBlocks; // freed blocks keep their slot with memory == VK_NULL_HANDLE
};

} // namespace weft::vk
