#pragma once
// The IBL tools run on the engine pool (core/ThreadPool.h) with every core. A body calling
// iblParallelFor again runs that call on its own thread.
#include <functional>

#include "core/ThreadPool.h"

namespace weft {

/// Calls body(begin, end) over [0, n) on the engine pool (inline when n < minParallel).
inline void iblParallelFor(int n, const std::function<void(int, int)>& body, int minParallel = 2) {
    enginePool().parallelFor(n, body, minParallel);
}

} // namespace weft
