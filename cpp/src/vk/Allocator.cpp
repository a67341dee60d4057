#include "vk/Allocator.h"

#include <atomic>
#include <cstdlib>
#include <string>

namespace weft::vk {

namespace {

// Test hook: WEFT_VK_FAIL_ALLOCATION=N makes the N-th device-memory allocation of the process
// fail as if the device were out of memory (once), so tests can check that every caller turns
// it into weft::Error and that the renderer works again afterwards. Read once, at the first
// allocation; unset, it costs one relaxed atomic increment per block.
bool injectedFailure() {
    static const long failAt = [] {
        const char* v = std::getenv("WEFT_VK_FAIL_ALLOCATION");
        return v ? std::atol(v) : 0L;
    }();
    static std::atomic<long> count{0};
    return failAt > 0 && count.fetch_add(1, std::memory_order_relaxed) + 1 == failAt;
}

} // namespace

Allocator::Allocator(VkPhysicalDevice physical, VkDevice device, VkDeviceSize blockSize)
    : mDevice(device), mBlockSize(blockSize) {
    vkGetPhysicalDeviceMemoryProperties(physical, &mProps);
}

Allocator::~Allocator() {
    for (Block& b : mBlocks) {
        if (b.memory == VK_NULL_HANDLE) continue;
        if (b.mapped) vkUnmapMemory(mDevice, b.memory);
        vkFreeMemory(mDevice, b.memory, nullptr);
    }
}

uint32_t Allocator::findType(uint32_t typeBits, MemoryUsage usage) const {
    VkMemoryPropertyFlags required = 0, preferred = 0;
    switch (usage) {
    case MemoryUsage::GpuOnly: preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
    case MemoryUsage::Upload:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        break;
    case MemoryUsage::Readback:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
        break;
    }
    int best = -1;
    for (uint32_t i = 0; i < mProps.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        const VkMemoryPropertyFlags f = mProps.memoryTypes[i].propertyFlags;
        if ((f & required) != required) continue;
        if ((f & preferred) == preferred) return i;
        if (best < 0) best = int(i);
    }
    if (best < 0) throw Error("no Vulkan memory type fits the request");
    return uint32_t(best);
}

Allocation Allocator::allocate(const VkMemoryRequirements& req, MemoryUsage usage, bool linear) {
    const uint32_t type = findType(req.memoryTypeBits, usage);
    const bool hostVisible =
        (mProps.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) != 0;
    std::lock_guard<std::mutex> lock(mMutex);
    auto finish = [&](int index, VkDeviceSize offset) {
        Block& b = mBlocks[size_t(index)];
        Allocation a;
        a.memory = b.memory;
        a.offset = offset;
        a.size = req.size;
        a.block = index;
        a.mapped = b.mapped ? static_cast<char*>(b.mapped) + offset : nullptr;
        return a;
    };
    const bool dedicated = req.size > mBlockSize / 2;
    if (!dedicated) {
        for (size_t i = 0; i < mBlocks.size(); ++i) {
            Block& b = mBlocks[i];
            if (b.memory == VK_NULL_HANDLE || b.dedicated || b.typeIndex != type ||
                b.linear != linear)
                continue;
            if (auto offset = b.ranges->allocate(req.size, req.alignment))
                return finish(int(i), *offset);
        }
    }
    Block block;
    block.typeIndex = type;
    block.linear = linear;
    block.dedicated = dedicated;
    const VkDeviceSize size = dedicated ? req.size : mBlockSize;
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = size;
    info.memoryTypeIndex = type;
    VkResult r = injectedFailure() ? VK_ERROR_OUT_OF_DEVICE_MEMORY
                                   : vkAllocateMemory(mDevice, &info, nullptr, &block.memory);
    if (r != VK_SUCCESS)
        throw Error("out of GPU memory allocating " + std::to_string(size >> 20) + " MiB (" +
                    resultName(r) + ")");
    if (hostVisible)
        VK_CHECK(vkMapMemory(mDevice, block.memory, 0, VK_WHOLE_SIZE, 0, &block.mapped));
    block.ranges = std::make_unique<RangeAllocator>(size);
    auto offset = block.ranges->allocate(req.size, req.alignment);
    int index = -1;
    for (size_t i = 0; i < mBlocks.size(); ++i)
        if (mBlocks[i].memory == VK_NULL_HANDLE) index = int(i);
    if (index < 0) {
        mBlocks.push_back(std::move(block));
        index = int(mBlocks.size() - 1);
    } else {
        mBlocks[size_t(index)] = std::move(block);
    }
    return finish(index, *offset);
}

void Allocator::free(const Allocation& a) {
    if (!a) return;
    std::lock_guard<std::mutex> lock(mMutex);
    Block& b = mBlocks.at(size_t(a.block));
    b.ranges->free(a.offset);
    // Dedicated blocks go back at once; shared blocks stay for reuse.
    if (b.dedicated && b.ranges->empty()) {
        if (b.mapped) vkUnmapMemory(mDevice, b.memory);
        vkFreeMemory(mDevice, b.memory, nullptr);
        b = Block{};
    }
}

Allocator::Stats Allocator::stats() const {
    std::lock_guard<std::mutex> lock(mMutex);
    Stats s;
    for (const Block& b : mBlocks) {
        if (b.memory == VK_NULL_HANDLE) continue;
        ++s.blocks;
        s.reserved += b.ranges->capacity();
        s.used += b.ranges->used();
    }
    return s;
}

} // namespace weft::vk
