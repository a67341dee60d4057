#include "core/ThreadPool.h"

#include <algorithm>
#include <chrono>

#if defined(__x86_64__) || defined(_M_X64)
#include <immintrin.h>
#define WEFT_PAUSE() _mm_pause()
#else
#define WEFT_PAUSE() std::this_thread::yield()
#endif

namespace weft {

ThreadPool::ThreadPool(int threads) {
    const int hw = int(std::max(1u, std::thread::hardware_concurrency()));
    mSize = std::max(1, threads > 0 ? threads : hw);
    for (int i = 1; i < mSize; ++i) mWorkers.emplace_back([this, i] { workerLoop(i); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mStop = true;
    }
    mWake.notify_all();
    for (auto& t : mWorkers) t.join();
}

void ThreadPool::workerLoop(int index) {
    using Clock = std::chrono::steady_clock;
    unsigned seen = 0;
    for (;;) {
        // Spin for up to ~0.2 ms, then sleep until the next job.
        const auto spinUntil = Clock::now() + std::chrono::microseconds(200);
        int spins = 0;
        while (mGeneration.load(std::memory_order_acquire) == seen && !mStop.load()) {
            WEFT_PAUSE();
            if ((++spins & 255) == 0 && Clock::now() > spinUntil) {
                std::unique_lock<std::mutex> lock(mMutex);
                mWake.wait(lock, [&] {
                    return mStop.load() || mGeneration.load(std::memory_order_acquire) != seen;
                });
            }
        }
        if (mStop.load()) return;
        seen = mGeneration.load(std::memory_order_acquire);
        const int count = mCount;
        const int begin = int(int64_t(count) * index / mSize);
        const int end = int(int64_t(count) * (index + 1) / mSize);
        if (end > begin) (*mBody)(begin, end);
        mPending.fetch_sub(1, std::memory_order_acq_rel);
    }
}

void ThreadPool::parallelFor(int n, const std::function<void(int, int)>& body, int minParallel) {
    if (n <= 0) return;
    if (mSize == 1 || n < minParallel) {
        body(0, n);
        return;
    }
    mBody = &body;
    mCount = n;
    mPending.store(int(mWorkers.size()), std::memory_order_relaxed);
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mGeneration.fetch_add(1, std::memory_order_acq_rel);
    }
    mWake.notify_all();
    body(0, int(int64_t(n) / mSize)); // chunk 0 on the calling thread
    while (mPending.load(std::memory_order_acquire) != 0) WEFT_PAUSE();
}

} // namespace weft
