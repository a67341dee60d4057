#pragma once
// Runs body(begin, end) over [0, n) on a private pool of `threads` (0 = all cores); each call
// owns its pool, so concurrent fits never share workers.
#include <functional>

namespace weft {

void btfParallelFor(int n, int threads, const std::function<void(int, int)>& body);

} // namespace weft
