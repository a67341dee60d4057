#pragma once
// The IBL tools share one thread pool; a mutex serialises callers from different threads (the
// pool runs one job at a time). Bodies must not call iblParallelFor themselves.
#include <functional>

namespace weft {

/// Calls body(begin, end) over [0, n) on the shared pool (inline when n < minParallel).
void iblParallelFor(int n, const std::function<void(int, int)>& body, int minParallel = 2);

} // namespace weft
