#include "btf/BtfParallel.h"

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

} // namespace weft
