#include <gtest/gtest.h>

#include <random>
#include <vector>

#include <weft/Error.h>

#include "vk/RangeAllocator.h"

using weft::vk::RangeAllocator;

TEST(RangeAllocator, AlignsAndFillsCapacity) {
    RangeAllocator a(1024);
    auto x = a.allocate(100, 1);
    auto y = a.allocate(10, 256);
    ASSERT_TRUE(x && y);
    EXPECT_EQ(*x, 0u);
    EXPECT_EQ(*y, 256u);
    EXPECT_EQ(a.used(), 110u);
    // The padding between 100 and 256 is still usable.
    auto z = a.allocate(150, 2);
    ASSERT_TRUE(z);
    EXPECT_EQ(*z, 100u);
    EXPECT_FALSE(a.allocate(1024, 1));
}

TEST(RangeAllocator, FreeCoalescesBackToOneRange) {
    RangeAllocator a(4096);
    std::vector<uint64_t> offsets;
    for (int i = 0; i < 16; ++i) offsets.push_back(*a.allocate(256, 256));
    EXPECT_FALSE(a.allocate(1, 1));
    for (int i : {3, 1, 2, 0, 15, 8, 9, 10, 11, 4, 5, 6, 7, 12, 14, 13}) a.free(offsets[size_t(i)]);
    EXPECT_TRUE(a.empty());
    EXPECT_EQ(a.freeRangeCount(), 1u);
    EXPECT_EQ(*a.allocate(4096, 4096), 0u);
}

TEST(RangeAllocator, RandomisedNoOverlap) {
    RangeAllocator a(1 << 20);
    std::mt19937 rng(7);
    std::vector<std::pair<uint64_t, uint64_t>> live;
    for (int step = 0; step < 5000; ++step) {
        if (!live.empty() && rng() % 3 == 0) {
            size_t i = rng() % live.size();
            a.free(live[i].first);
            live.erase(live.begin() + long(i));
            continue;
        }
        const uint64_t size = 1 + rng() % 5000, align = 1ull << (rng() % 9);
        if (auto off = a.allocate(size, align)) {
            EXPECT_EQ(*off % align, 0u);
            EXPECT_LE(*off + size, a.capacity());
            for (auto& [o, s] : live) ASSERT_TRUE(*off + size <= o || o + s <= *off);
            live.push_back({*off, size});
        }
    }
    uint64_t used = 0;
    for (auto& l : live) used += l.second;
    EXPECT_EQ(a.used(), used);
}

TEST(RangeAllocator, RejectsBadRequests) {
    RangeAllocator a(64);
    EXPECT_THROW(a.allocate(0, 1), weft::Error);
    EXPECT_THROW(a.allocate(8, 3), weft::Error);
    EXPECT_THROW(a.free(12), weft::Error);
}
