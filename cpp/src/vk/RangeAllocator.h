#pragma once
// First-fit allocator of [offset, offset+size) ranges inside one block, with coalescing frees.
// Pure bookkeeping (no Vulkan), so it is unit-tested on its own.
#include <cstdint>
#include <map>
#include <optional>

namespace weft::vk {

class RangeAllocator {
public:
    explicit RangeAllocator(uint64_t capacity);

    /// Returns the offset of a free range of `size` bytes aligned to `alignment` (a power of
    /// two), or nothing when no free range is large enough.
    std::optional<uint64_t> allocate(uint64_t size, uint64_t alignment);
    /// Returns a range obtained from allocate(). Freeing an unknown range throws weft::Error.
    void free(uint64_t offset);

    uint64_t capacity() const { return mCapacity; }
    uint64_t used() const { return mUsed; }
    bool empty() const { return mAllocated.empty(); }
    size_t freeRangeCount() const { return mFree.size(); }

private:
    uint64_t mCapacity;
    uint64_t mUsed = 0;
    std::map<uint64_t, uint64_t> mFree;      // offset -> size, disjoint and never adjacent
    std::map<uint64_t, uint64_t> mAllocated; // offset -> size (including alignment padding)
};

} // namespace weft::vk
