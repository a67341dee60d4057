#include "vk/RangeAllocator.h"

#include <iterator>

#include <weft/Error.h>

namespace weft::vk {

RangeAllocator::RangeAllocator(uint64_t capacity) : mCapacity(capacity) {
    if (capacity > 0) mFree.emplace(0, capacity);
}

std::optional<uint64_t> RangeAllocator::allocate(uint64_t size, uint64_t alignment) {
    if (size == 0 || alignment == 0 || (alignment & (alignment - 1)) != 0)
        throw Error("RangeAllocator: size must be > 0 and alignment a power of two");
    for (auto it = mFree.begin(); it != mFree.end(); ++it) {
        const uint64_t start = it->first;
        const uint64_t freeSize = it->second;
        const uint64_t aligned = (start + alignment - 1) & ~(alignment - 1);
        const uint64_t padding = aligned - start;
        if (padding > freeSize || freeSize - padding < size) continue;
        // The padding before `aligned` stays free; the allocation owns [aligned, aligned+size).
        const uint64_t tailStart = aligned + size;
        const uint64_t tailSize = start + freeSize - tailStart;
        mFree.erase(it);
        if (padding > 0) mFree.emplace(start, padding);
        if (tailSize > 0) mFree.emplace(tailStart, tailSize);
        mAllocated.emplace(aligned, size);
        mUsed += size;
        return aligned;
    }
    return std::nullopt;
}

void RangeAllocator::free(uint64_t offset) {
    auto found = mAllocated.find(offset);
    if (found == mAllocated.end()) throw Error("RangeAllocator: freeing an unknown range");
    uint64_t start = offset;
    uint64_t size = found->second;
    mAllocated.erase(found);
    mUsed -= size;
    // Merge with the following free range, then with the preceding one.
    auto next = mFree.lower_bound(start);
    if (next != mFree.end() && next->first == start + size) {
        size += next->second;
        next = mFree.erase(next);
    }
    if (next != mFree.begin()) {
        auto prev = std::prev(next);
        if (prev->first + prev->second == start) {
            prev->second += size;
            return;
        }
    }
    mFree.emplace(start, size);
}

} // namespace weft::vk
