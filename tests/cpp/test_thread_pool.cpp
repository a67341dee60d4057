// The engine's thread pool (core/ThreadPool.h): every index once, chunk counts, exceptions
// and the pool shared by every subsystem.
#include <gtest/gtest.h>

#include <weft/Error.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "core/ThreadPool.h"

TEST(ThreadPool, EveryIndexExactlyOnce) {
    for (int threads : {1, 2, 3, 7}) {
        weft::ThreadPool pool(threads);
        for (int n : {1, 5, 100, 5000, 100003}) {
            std::vector<std::atomic<int>> hits(static_cast<size_t>(n));
            for (auto& h : hits) h = 0;
            pool.parallelFor(
                n,
                [&](int b, int e) {
                    for (int i = b; i < e; ++i) hits[size_t(i)]++;
                },
                1);
            for (int i = 0; i < n; ++i) ASSERT_EQ(hits[size_t(i)].load(), 1) << threads << " " << n;
        }
    }
}

TEST(ThreadPool, ManyQuickJobsEachRunOnce) {
    // Back-to-back jobs, some with fewer items than threads: a worker that wakes late must not
    // run a chunk of a job that is over, nor miss one of the next.
    for (int threads : {2, 3, 7}) {
        weft::ThreadPool pool(threads);
        std::vector<std::atomic<int>> hits(64);
        for (int job = 0; job < 20000; ++job) {
            const int n = 1 + job % 64;
            for (int i = 0; i < n; ++i) hits[size_t(i)] = 0;
            pool.parallelFor(
                n,
                [&](int b, int e) {
                    for (int i = b; i < e; ++i) hits[size_t(i)]++;
                },
                1);
            for (int i = 0; i < n; ++i)
                ASSERT_EQ(hits[size_t(i)].load(), 1) << threads << " " << job;
        }
    }
}

TEST(ThreadPool, ChunksSplitTheJobAsAsked) {
    weft::ThreadPool pool(4);
    for (int chunks : {1, 2, 3, 4, 9}) {
        std::mutex m;
        std::set<std::pair<int, int>> ranges;
        pool.parallelFor(
            10,
            [&](int b, int e) {
                std::lock_guard<std::mutex> lock(m);
                ranges.insert({b, e});
            },
            1, chunks);
        const int expected = std::min(chunks, 4);
        ASSERT_EQ(int(ranges.size()), expected) << chunks;
        int k = 0;
        for (const auto& r : ranges) { // contiguous, depending only on n and the chunk count
            EXPECT_EQ(r.first, 10 * k / expected);
            EXPECT_EQ(r.second, 10 * (k + 1) / expected);
            ++k;
        }
    }
}

TEST(ThreadPool, ExceptionOnAWorkerReachesTheCaller) {
    weft::ThreadPool pool(3);
    for (int round = 0; round < 50; ++round) {
        const int bad = round % 3; // the caller's chunk (0) or a worker's
        EXPECT_THROW(pool.parallelFor(
                         300,
                         [&](int b, int) {
                             if (b / 100 == bad) throw std::runtime_error("chunk failed");
                         },
                         1),
                     std::runtime_error);
        // the pool keeps working afterwards
        std::atomic<int> sum{0};
        pool.parallelFor(
            300, [&](int b, int e) { sum += e - b; }, 1);
        ASSERT_EQ(sum.load(), 300);
    }
}

TEST(ThreadPool, DynamicTakesEveryItemOnceAndRethrows) {
    weft::ThreadPool pool(3);
    for (int n : {1, 7, 1000}) {
        for (int grain : {1, 3, 64}) {
            std::vector<std::atomic<int>> hits(static_cast<size_t>(n));
            for (auto& h : hits) h = 0;
            pool.parallelForDynamic(n, grain, [&](int b, int e) {
                EXPECT_LE(e - b, grain);
                for (int i = b; i < e; ++i) hits[size_t(i)]++;
            });
            for (int i = 0; i < n; ++i) ASSERT_EQ(hits[size_t(i)].load(), 1) << n << " " << grain;
        }
    }
    EXPECT_THROW(pool.parallelForDynamic(1000, 5,
                                         [&](int b, int) {
                                             if (b >= 500)
                                                 throw weft::InvalidArgument("item failed");
                                         }),
                 weft::InvalidArgument);
}

TEST(EnginePool, SharedByEveryUserAndBounded) {
    weft::ThreadPool& pool = weft::enginePool();
    EXPECT_EQ(&pool, &weft::enginePool());
    EXPECT_EQ(pool.size(), int(std::max(1u, std::min(std::thread::hardware_concurrency(), 256u))));
    EXPECT_EQ(weft::PoolShare(0).chunks(), pool.size());
    EXPECT_EQ(weft::PoolShare(1).chunks(), 1);
    EXPECT_EQ(weft::PoolShare(256).chunks(), pool.size()); // more than the cores: capped
    EXPECT_THROW(weft::PoolShare(257), weft::InvalidArgument);
    EXPECT_THROW(weft::checkThreads(-1), weft::InvalidArgument);
    // one chunk runs on the caller's thread
    const std::thread::id caller = std::this_thread::get_id();
    weft::PoolShare(1).parallelFor(
        100000, [&](int, int) { EXPECT_EQ(std::this_thread::get_id(), caller); }, 1);
}

TEST(EnginePool, ConcurrentCallersEachGetEveryIndexOnce) {
    // Two threads using the pool at once (a cloth step beside a BTF fit): one runs its job on
    // the workers, the other on its own thread; neither waits for the other nor loses an item.
    std::vector<std::thread> callers;
    std::atomic<int> failures{0};
    for (int t = 0; t < 3; ++t) {
        callers.emplace_back([&] {
            std::vector<std::atomic<int>> hits(4096);
            for (int job = 0; job < 300; ++job) {
                for (auto& h : hits) h = 0;
                weft::enginePool().parallelFor(
                    4096,
                    [&](int b, int e) {
                        for (int i = b; i < e; ++i) hits[size_t(i)]++;
                    },
                    1);
                for (auto& h : hits) failures += h.load() != 1;
            }
        });
    }
    for (auto& c : callers) c.join();
    EXPECT_EQ(failures.load(), 0);
}
