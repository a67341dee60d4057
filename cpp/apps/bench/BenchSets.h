#pragma once
// The benchmark sets: the seed-000 demo scene (per-pass GPU ms), seed 002's hair and fur frame
// table (B / B+S / B+S+T) and seed 001's dome table (0 / 16 / 64 shadow lights).
#include <vector>

#include "BenchTypes.h"

namespace weft::bench {
/// Runs the sets named in `options.sets`, in order; throws InvalidArgument for an unknown name.
std::vector<BenchRow> runSets(const BenchOptions& options);
} // namespace weft::bench
