#pragma once
// weft-bench's report: the same rows as JSON (for tools) and Markdown (for BENCHMARKS.md).
#include <string>
#include <vector>

#include "BenchTypes.h"

namespace weft::bench {

struct MachineReport {
    std::string cpu, loadAverage, date;
    int cores = 0;
};
/// The CPU model, hardware threads, /proc/loadavg and the UTC time now.
MachineReport machineReport();

std::string reportJson(const BenchOptions& o, const DeviceReport& device,
                       const MachineReport& before, const MachineReport& after,
                       const std::vector<BenchRow>& rows,
                       const std::vector<std::string>& validation);
std::string reportMarkdown(const BenchOptions& o, const DeviceReport& device,
                           const MachineReport& before, const MachineReport& after,
                           const std::vector<BenchRow>& rows,
                           const std::vector<std::string>& validation);

} // namespace weft::bench
