#pragma once
// What a frame did: the passes that ran and what each cost.
#include <cstdint>
#include <string>
#include <vector>

namespace weft {

struct PassStats {
    std::string name;
    double cpuMs = 0.0;  // recording time on the CPU
    double gpuMs = -1.0; // from timestamp queries; negative when the device cannot measure it
};

struct FrameStats {
    uint64_t frameIndex = 0;
    std::vector<PassStats> passes;   // in execution order, culled passes absent
    std::vector<std::string> culled; // passes the frame graph removed because nobody read them
    std::vector<std::string> reused; // passes skipped because their output is still valid
    double cpuMs = 0.0;              // whole frame on the CPU (record + submit + wait + readback)
    double gpuMs = -1.0;             // sum of the passes' GPU times, negative if unmeasured
    int meshUploads = 0;             // dynamic meshes (cloth) re-uploaded for this frame
    uint64_t uploadBytes = 0;        // bytes they took
    int environmentBakes = 0;       // 1 when the environment was filtered + uploaded for this frame
    double environmentBakeMs = 0.0; // CPU time of that (filtering, or a cache hit, and upload)
};

} // namespace weft
