// The shared IBL thread pool.
#include "IblParallel.h"

#include <mutex>

#include "core/ThreadPool.h"

namespace weft {

void iblParallelFor(int n, const std::function<void(int, int)>& body, int minParallel) {
    static std::mutex mutex;
    static ThreadPool pool;
    std::lock_guard<std::mutex> lock(mutex);
    pool.parallelFor(n, body, minParallel);
}

} // namespace weft
