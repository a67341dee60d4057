// Fork-join over std::thread. Work is handed out through an atomic counter, so any subset of
// the threads (down to the caller alone) completes it: that is what makes a failed thread start
// harmless. The general ThreadPool is not used because its constructor cannot survive a thread
// that fails to start (its workers would wait on a condition variable being destroyed).
#include "btf/BtfParallel.h"

#include <weft/Error.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace weft {

namespace {

int resolveThreads(int threads, int n) {
    checkBtfThreads(threads);
    const int hw = int(std::max(1u, std::thread::hardware_concurrency()));
    return std::max(1, std::min({threads > 0 ? threads : hw, n, kMaxBtfThreads}));
}

// Runs work(failed) on `count` threads, the caller being one of them; `failed` turns true once
// a thread has thrown, so the others stop taking work.
void runOnThreads(int count, const std::function<void(const std::atomic<bool>&)>& work) {
    std::mutex errorMutex;
    std::exception_ptr error;
    std::atomic<bool> failed{false};
    auto guarded = [&] {
        try {
            work(failed);
        } catch (...) {
            failed = true;
            std::lock_guard<std::mutex> lock(errorMutex);
            if (!error) error = std::current_exception();
        }
    };
    std::vector<std::thread> started;
    started.reserve(size_t(count - 1));
    for (int i = 1; i < count; ++i) {
        try {
            started.emplace_back(guarded);
        } catch (const std::system_error&) {
            break; // thread limit or no memory for a stack: the started ones share the work
        }
    }
    guarded();
    for (std::thread& t : started) t.join();
    if (error) std::rethrow_exception(error);
}

} // namespace

void checkBtfThreads(int threads) {
    if (threads < 0 || threads > kMaxBtfThreads)
        throw InvalidArgument("threads must be 0 (all cores) or 1.." +
                              std::to_string(kMaxBtfThreads) + ", got " +
                              std::to_string(threads));
}

void btfParallelFor(int n, int threads, const std::function<void(int, int)>& body) {
    const int count = resolveThreads(threads, std::max(n, 1));
    if (n <= 0) return;
    if (count == 1) {
        body(0, n);
        return;
    }
    std::atomic<int> next{0};
    runOnThreads(count, [&](const std::atomic<bool>& failed) {
        for (int c; !failed && (c = next.fetch_add(1, std::memory_order_relaxed)) < count;) {
            const int begin = int(int64_t(n) * c / count), end = int(int64_t(n) * (c + 1) / count);
            if (end > begin) body(begin, end);
        }
    });
}

void btfParallelForDynamic(int n, int threads, int grain,
                           const std::function<void(int, int)>& body) {
    grain = std::max(grain, 1);
    const int count = resolveThreads(threads, std::max((n + grain - 1) / grain, 1));
    if (n <= 0) return;
    if (count == 1) {
        body(0, n);
        return;
    }
    std::atomic<int> next{0};
    runOnThreads(count, [&](const std::atomic<bool>& failed) {
        for (int b; !failed && (b = next.fetch_add(grain, std::memory_order_relaxed)) < n;)
            body(b, std::min(n, b + grain));
    });
}

} // namespace weft
