#include "btf/BtfParallel.h"

#include <algorithm>
#include <atomic>

#include "core/ThreadPool.h"

namespace weft {

void btfParallelFor(int n, int threads, const std::function<void(int, int)>& body) {
    if (n <= 0) return;
    if (threads == 1 || n == 1) {
        body(0, n);
        return;
    }
    ThreadPool pool(threads);
    pool.parallelFor(n, body, 1);
}

void btfParallelForDynamic(int n, int threads, int grain,
                           const std::function<void(int, int)>& body) {
    if (n <= 0) return;
    grain = std::max(grain, 1);
    if (threads == 1 || n <= grain) {
        body(0, n);
        return;
    }
    ThreadPool pool(threads);
    std::atomic<int> next{0};
    pool.parallelFor(pool.size(), [&](int, int) {
        for (int b; (b = next.fetch_add(grain, std::memory_order_relaxed)) < n;)
            body(b, std::min(n, b + grain));
    }, 1);
}

} // namespace weft
