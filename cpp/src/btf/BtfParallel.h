#pragma once
// Runs body(begin, end) over [0, n) on private threads (`threads`, 0 = all cores); each call
// owns its threads, so concurrent fits never share workers. When the system refuses to start a
// thread (std::system_error: a process or memory limit) the work is done by the threads that did
// start, the caller included; nothing waits for a thread that never ran. An exception thrown by
// body on any thread is rethrown to the caller once every thread has finished.
#include <functional>

namespace weft {

/// Largest `threads` a BTF function accepts; beyond it a request is a mistake, not a machine.
constexpr int kMaxBtfThreads = 256;

/// Throws InvalidArgument unless 0 <= threads <= kMaxBtfThreads.
void checkBtfThreads(int threads);

/// Splits [0, n) into one contiguous chunk per thread (chunks depend only on n and `threads`).
/// Throws InvalidArgument for an invalid `threads` (checkBtfThreads).
void btfParallelFor(int n, int threads, const std::function<void(int, int)>& body);

/// Like btfParallelFor, but the threads take `grain` items at a time from a shared counter until
/// none is left: for work whose cost varies per item (iterative fits) or a machine where a
/// worker does not get its core, where fixed halves leave one thread waiting for the other.
void btfParallelForDynamic(int n, int threads, int grain,
                           const std::function<void(int, int)>& body);

} // namespace weft
