#pragma once
// The BTF functions' `threads` argument on the engine pool (core/ThreadPool.h): `threads` (0 =
// every core) caps how many of the pool's threads work on one call. An exception thrown by body
// on any thread is rethrown to the caller once every thread has finished.
#include <functional>

#include "core/ThreadPool.h"

namespace weft {

/// Splits [0, n) into one contiguous chunk per thread (chunks depend only on n and the number of
/// threads that `threads` allows). Throws InvalidArgument for an invalid `threads`.
inline void btfParallelFor(int n, int threads, const std::function<void(int, int)>& body) {
    checkThreads(threads);
    PoolShare(threads).parallelFor(n, body, 1);
}

/// Like btfParallelFor, but the threads take `grain` items at a time from a shared counter until
/// none is left: for work whose cost varies per item (iterative fits) or a machine where a
/// worker does not get its core, where fixed halves leave one thread waiting for the other.
inline void btfParallelForDynamic(int n, int threads, int grain,
                                  const std::function<void(int, int)>& body) {
    checkThreads(threads);
    PoolShare(threads).parallelForDynamic(n, grain, body);
}

} // namespace weft
