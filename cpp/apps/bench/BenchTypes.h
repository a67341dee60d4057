#pragma once
// What weft-bench measures and reports: one row per workload (a scene at a size with a
// configuration), its frame times and per-pass GPU times, and the seed's published fps for the
// same workload where the seeds have one (SPEC §4.7, §5.5).
#include <map>
#include <string>
#include <vector>

namespace weft::bench {

struct BenchOptions {
    bool quick = false;  // small sizes, one timed frame: proves the set runs (CI)
    int frames = 3;      // timed frames per row, after one warm-up frame
    bool fur23m = false; // the 22,977,900-point fur (1.3 GB of strand buffers)
    std::vector<std::string> sets{"demo", "hair", "dome"};
    std::string imageDir; // non-empty: save the last timed frame of every row as a PNG here
};

struct BenchRow {
    std::string set;      // demo, hair, dome
    std::string workload; // e.g. "hair 160,000 vertices"
    std::string config;   // e.g. "B+S", "16 dome lights, maps re-rendered"
    int width = 0, height = 0;
    long long vertices = 0;
    int frames = 0;
    double wallMs = 0.0; // median wall time of render() per frame (colour read back)
    double gpuMs = -1.0; // median sum of the passes' GPU timestamps (negative: unmeasured)
    std::map<std::string, double> passGpuMs; // median per pass name (passes of one name summed)
    std::vector<std::string> passOrder;      // the names in the order they first ran
    double seedFps = 0.0;                    // the seed's published fps for this workload (0: none)
    std::string seedSource;
};

struct DeviceReport {
    std::string name, type, driver, apiVersion;
    bool validation = false;          // validation layers were on for the run
    bool validationAvailable = false; // VK_LAYER_KHRONOS_validation can be loaded
    std::vector<std::string> others;  // the devices not chosen, "name (type)"
};

} // namespace weft::bench
