#pragma once
// Runs body(begin, end) over [0, n) on a private pool of `threads` (0 = all cores); each call
// owns its pool, so concurrent fits never share workers.
#include <functional>

namespace weft {

void btfParallelFor(int n, int threads, const std::function<void(int, int)>& body);

/// Like btfParallelFor, but the threads take `grain` items at a time from a shared counter until
/// none is left: for work whose cost varies per item (iterative fits) or a machine where a
/// worker does not get its core, where fixed halves leave one thread waiting for the other.
void btfParallelForDynamic(int n, int threads, int grain,
                           const std::function<void(int, int)>& body);

} // namespace weft
