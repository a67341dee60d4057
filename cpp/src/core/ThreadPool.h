#pragma once
// A small fork-join pool: parallelFor splits [0, n) into one contiguous chunk per worker and
// returns when all are done. Chunks depend only on n and the thread count, so callers whose
// iterations are independent get the same result for any number of threads. Workers spin for
// a short while between jobs (a cloth step issues dozens of them) and then sleep.
#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace weft {

class ThreadPool {
public:
    /// threads <= 0: hardware concurrency. The calling thread runs one chunk itself.
    explicit ThreadPool(int threads = 0);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int size() const { return mSize; }
    /// Calls body(begin, end) over [0, n) in chunks; runs inline when n < minParallel.
    void parallelFor(int n, const std::function<void(int, int)>& body, int minParallel = 2048);

private:
    void workerLoop(int index);

    int mSize;
    std::vector<std::thread> mWorkers;
    std::mutex mMutex;
    std::condition_variable mWake;
    const std::function<void(int, int)>* mBody = nullptr;
    int mCount = 0;
    std::atomic<unsigned> mGeneration{0};
    std::atomic<int> mPending{0};
    std::atomic<bool> mStop{false};
};

} // namespace weft
