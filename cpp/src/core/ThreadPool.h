#pragma once
// A small fork-join pool: parallelFor splits [0, n) into one contiguous chunk per thread and
// returns when all are done. Chunks depend only on n and the thread count, so callers whose
// iterations are independent get the same result for any number of threads. Each thread runs
// its own chunk (cache locality across jobs), and any thread that is done takes chunks nobody
// has started: on a loaded machine the caller does not wait for a worker that is not running.
// Workers spin for a short while between jobs (a cloth step issues dozens of them) and then
// sleep.
#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace weft {

/// Most threads a pool may have (the cloth and BTF limits are the same).
constexpr int kMaxPoolThreads = 256;

class ThreadPool {
public:
    /// threads <= 0: hardware concurrency. The calling thread runs chunk 0 itself. Throws
    /// InvalidArgument above kMaxPoolThreads, and weft::Error when the system cannot start the
    /// threads (the ones already started are joined first: no hang, no abort).
    explicit ThreadPool(int threads = 0);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int size() const { return mSize; }
    /// Calls body(begin, end) over [0, n) in chunks; runs inline when n < minParallel. Safe to
    /// call from several threads at once, and from inside a body: a call that finds the pool
    /// busy runs body(0, n) on its own thread instead of waiting (no deadlock, same result for
    /// independent iterations).
    void parallelFor(int n, const std::function<void(int, int)>& body, int minParallel = 2048);

private:
    void workerLoop(int index);
    /// Stops and joins every worker (destructor, and a constructor that could not start all).
    void stopWorkers();
    /// Runs chunk `first` and then any other chunk of job `generation` still unclaimed.
    void runChunks(int first, unsigned generation);

    int mSize;
    std::vector<std::thread> mWorkers;
    std::mutex mMutex;
    std::mutex mJob; // held by the thread whose job the workers run
    std::condition_variable mWake;
    std::atomic<const std::function<void(int, int)>*> mBody{nullptr};
    std::atomic<int> mCount{0};
    std::atomic<unsigned> mGeneration{0};
    // Generation that last claimed each chunk: a chunk of job g is free while it reads g - 1.
    std::unique_ptr<std::atomic<unsigned>[]> mClaimed;
    std::atomic<int> mDone{0};
    std::atomic<int> mSleeping{0};
    std::atomic<bool> mStop{false};
};

} // namespace weft
