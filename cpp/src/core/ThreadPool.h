#pragma once
// A small fork-join pool: parallelFor splits [0, n) into one contiguous chunk per thread and
// returns when all are done. Chunks depend only on n and the thread count, so callers whose
// iterations are independent get the same result for any number of threads. Each thread runs
// its own chunk (cache locality across jobs), and any thread that is done takes chunks nobody
// has started: on a loaded machine the caller does not wait for a worker that is not running.
// Workers spin for a short while between jobs (a cloth step issues dozens of them) and then
// sleep.
//
// The engine runs all its CPU work on one pool, enginePool() (issue 15: a pool per cloth, one
// for IBL, private threads per BTF call and per hair generator oversubscribed the cores when
// used together). A caller's `threads` setting becomes the number of chunks its jobs are split
// into, at most the pool's size: PoolShare.
#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace weft {

/// Most threads a pool may have (the cloth and BTF limits are the same).
constexpr int kMaxPoolThreads = 256;

/// Throws InvalidArgument unless 0 <= threads <= kMaxPoolThreads (0: all cores).
void checkThreads(int threads);

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
    /// Calls body(begin, end) over [0, n) in `chunks` contiguous chunks (0 or more than size():
    /// size()); runs inline when n < minParallel or chunks is 1. Safe to call from several
    /// threads at once, and from inside a body: a call that finds the pool busy runs body(0, n)
    /// on its own thread instead of waiting (no deadlock, same result for independent
    /// iterations). An exception thrown by body on any thread is rethrown here once every
    /// chunk has finished (the first one thrown; chunks not yet started are skipped).
    void parallelFor(int n, const std::function<void(int, int)>& body, int minParallel = 2048,
                     int chunks = 0);
    /// Like parallelFor, but up to `chunks` threads take `grain` items at a time from a shared
    /// counter until none is left: for items whose cost varies (iterative fits), or a machine
    /// where a worker does not get its core and fixed chunks would leave the others waiting.
    void parallelForDynamic(int n, int grain, const std::function<void(int, int)>& body,
                            int chunks = 0);

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
    std::atomic<int> mChunks{1};
    std::mutex mErrorMutex;
    std::exception_ptr mError;
    std::atomic<bool> mFailed{false};
    std::atomic<unsigned> mGeneration{0};
    // Generation that last claimed each chunk: a chunk of job g is free while it reads g - 1.
    std::unique_ptr<std::atomic<unsigned>[]> mClaimed;
    std::atomic<int> mDone{0};
    std::atomic<int> mSleeping{0};
    std::atomic<bool> mStop{false};
};

/// The engine's pool: one thread per core (the caller counts as one), started on first use and
/// shared by the cloth, the BTF fits, the IBL filters and the hair generators. Where the system
/// refuses to start its threads, the pool has fewer (down to the caller alone): slower, never
/// stuck.
ThreadPool& enginePool();

/// One user's share of the engine pool: its jobs are split into min(threads, pool size) chunks
/// (threads <= 0: the pool's size). Throws InvalidArgument above kMaxPoolThreads.
class PoolShare {
public:
    explicit PoolShare(int threads = 0);
    /// The chunks a job is split into.
    int chunks() const { return mChunks; }
    void parallelFor(int n, const std::function<void(int, int)>& body,
                     int minParallel = 2048) const {
        enginePool().parallelFor(n, body, minParallel, mChunks);
    }
    void parallelForDynamic(int n, int grain, const std::function<void(int, int)>& body) const {
        enginePool().parallelForDynamic(n, grain, body, mChunks);
    }

private:
    int mChunks;
};

} // namespace weft
