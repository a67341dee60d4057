#include "core/ThreadPool.h"

#include <weft/Error.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <system_error>

#include <unistd.h>

#if defined(__x86_64__) || defined(_M_X64)
#include <immintrin.h>
#define WEFT_PAUSE() _mm_pause()
#else
#define WEFT_PAUSE() std::this_thread::yield()
#endif

namespace weft {

namespace {
// About a microsecond of pause instructions: the usual gap between jobs of one cloth sweep.
constexpr int kSpinsBeforeYield = 64;
int hardwareThreads() { return int(std::max(1u, std::thread::hardware_concurrency())); }
} // namespace

void checkThreads(int threads) {
    if (threads < 0 || threads > kMaxPoolThreads)
        throw InvalidArgument("threads must be 0 (all cores) or 1.." +
                              std::to_string(kMaxPoolThreads) + ", got " + std::to_string(threads));
}

ThreadPool::ThreadPool(int threads) {
    const int hw = hardwareThreads();
    if (threads > kMaxPoolThreads) checkThreads(threads);
    mSize = std::max(1, threads > 0 ? threads : std::min(hw, kMaxPoolThreads));
    mClaimed = std::make_unique<std::atomic<unsigned>[]>(size_t(mSize));
    for (int c = 0; c < mSize; ++c) mClaimed[size_t(c)].store(0, std::memory_order_relaxed);
    try {
        for (int i = 1; i < mSize; ++i) mWorkers.emplace_back([this, i] { workerLoop(i); });
    } catch (const std::system_error& e) {
        // The destructor will not run: stop and join the workers started so far here, or
        // their std::thread objects would abort the process when the vector is destroyed.
        const size_t started = mWorkers.size();
        stopWorkers();
        throw Error("cannot start " + std::to_string(mSize - 1) + " worker threads (started " +
                    std::to_string(started) + "): " + e.what());
    }
}

ThreadPool::~ThreadPool() { stopWorkers(); }

void ThreadPool::stopWorkers() {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mStop = true;
    }
    mWake.notify_all();
    for (auto& t : mWorkers) t.join();
    mWorkers.clear();
}

void ThreadPool::runChunks(int first, unsigned generation) {
    for (int k = 0; k < mSize; ++k) {
        const int c = (first + k) % mSize;
        // Every chunk of a job is claimed before the next job starts, so a free chunk of job g
        // reads exactly g - 1; a thread still holding an older generation can claim nothing.
        unsigned expected = generation - 1;
        if (!mClaimed[size_t(c)].compare_exchange_strong(expected, generation,
                                                         std::memory_order_acq_rel))
            continue;
        // Claimed: the caller waits for this chunk, so body and counts are this job's. Slots
        // beyond the job's chunk count are claimed like the others and hold nothing.
        const int count = mCount.load(std::memory_order_relaxed);
        const int chunks = mChunks.load(std::memory_order_relaxed);
        if (c < chunks && !mFailed.load(std::memory_order_relaxed)) {
            const int begin = int(int64_t(count) * c / chunks);
            const int end = int(int64_t(count) * (c + 1) / chunks);
            try {
                if (end > begin) (*mBody.load(std::memory_order_relaxed))(begin, end);
            } catch (...) {
                std::lock_guard<std::mutex> lock(mErrorMutex);
                if (!mError) mError = std::current_exception();
                mFailed.store(true, std::memory_order_relaxed);
            }
        }
        mDone.fetch_add(1, std::memory_order_acq_rel);
    }
}

void ThreadPool::workerLoop(int index) {
    using Clock = std::chrono::steady_clock;
    unsigned seen = 0;
    for (;;) {
        // Wait for up to ~0.2 ms, then sleep until the next job. After a short spin the wait
        // yields the core: on a loaded machine this thread may share one with the caller,
        // which then runs instead of waiting for the scheduler to preempt the spinning.
        const auto spinUntil = Clock::now() + std::chrono::microseconds(200);
        int spins = 0;
        while (mGeneration.load(std::memory_order_acquire) == seen && !mStop.load()) {
            if (++spins < kSpinsBeforeYield)
                WEFT_PAUSE();
            else
                std::this_thread::yield();
            if ((spins & 63) == 0 && Clock::now() > spinUntil) {
                std::unique_lock<std::mutex> lock(mMutex);
                mSleeping.fetch_add(1);
                mWake.wait(lock, [&] { return mStop.load() || mGeneration.load() != seen; });
                mSleeping.fetch_sub(1);
            }
        }
        if (mStop.load()) return;
        seen = mGeneration.load(std::memory_order_acquire);
        runChunks(index, seen);
    }
}

void ThreadPool::parallelFor(int n, const std::function<void(int, int)>& body, int minParallel,
                             int chunks) {
    if (n <= 0) return;
    chunks = chunks <= 0 ? mSize : std::min(chunks, mSize);
    if (chunks == 1 || n < minParallel) {
        body(0, n);
        return;
    }
    std::unique_lock<std::mutex> job(mJob, std::try_to_lock);
    if (!job.owns_lock()) { // another thread's job (or ours, nested) holds the workers
        body(0, n);
        return;
    }
    mBody.store(&body, std::memory_order_relaxed);
    mCount.store(n, std::memory_order_relaxed);
    mChunks.store(chunks, std::memory_order_relaxed);
    mFailed.store(false, std::memory_order_relaxed);
    mDone.store(0, std::memory_order_relaxed);
    const unsigned generation = mGeneration.load(std::memory_order_relaxed) + 1;
    mGeneration.store(generation); // publishes the job (sequentially consistent with mSleeping)
    if (mSleeping.load() > 0) {
        std::lock_guard<std::mutex> lock(mMutex); // a worker between its check and its wait
        mWake.notify_all();
    }
    runChunks(0, generation);
    // Only chunks a worker has started are left: wait for them, yielding the core after a
    // short spin in case that worker shares it.
    for (int spins = 1; mDone.load(std::memory_order_acquire) != mSize; ++spins) {
        if (spins < kSpinsBeforeYield)
            WEFT_PAUSE();
        else
            std::this_thread::yield();
    }
    if (mFailed.load(std::memory_order_relaxed)) {
        std::exception_ptr error;
        {
            std::lock_guard<std::mutex> lock(mErrorMutex);
            std::swap(error, mError);
        }
        std::rethrow_exception(error);
    }
}

void ThreadPool::parallelForDynamic(int n, int grain, const std::function<void(int, int)>& body,
                                    int chunks) {
    if (n <= 0) return;
    grain = std::max(grain, 1);
    const int participants = std::min(chunks <= 0 ? mSize : chunks, (n + grain - 1) / grain);
    if (participants <= 1) {
        body(0, n);
        return;
    }
    std::atomic<int> next{0};
    std::atomic<bool> failed{false};
    parallelFor(
        participants,
        [&](int p0, int p1) {
            for (int p = p0; p < p1; ++p) {
                for (int b; !failed.load(std::memory_order_relaxed) &&
                            (b = next.fetch_add(grain, std::memory_order_relaxed)) < n;) {
                    try {
                        body(b, std::min(n, b + grain));
                    } catch (...) {
                        failed = true; // the others stop taking items; parallelFor rethrows
                        throw;
                    }
                }
            }
        },
        1, participants);
}

ThreadPool& enginePool() {
    // Deliberately never destroyed: a body may run during static destruction (a Python object
    // freed at exit), and joining threads there can deadlock. A child process made by fork()
    // (Python's multiprocessing) inherits the pool but not its threads: it starts its own.
    static std::mutex mutex;
    static ThreadPool* pool = nullptr;
    static pid_t owner = 0;
    std::lock_guard<std::mutex> lock(mutex);
    if (pool == nullptr || owner != ::getpid()) {
        for (int threads = std::min(hardwareThreads(), kMaxPoolThreads);; threads /= 2) {
            try {
                pool = new ThreadPool(threads);
                break;
            } catch (const Error&) {
                if (threads <= 1) throw;
            }
        }
        owner = ::getpid();
    }
    return *pool;
}

PoolShare::PoolShare(int threads) {
    if (threads > kMaxPoolThreads) checkThreads(threads);
    const int size = enginePool().size();
    mChunks = threads <= 0 ? size : std::min(threads, size);
}

} // namespace weft
