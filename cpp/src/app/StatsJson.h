#pragma once
#include <string>

#include <weft/FrameStats.h>

namespace weft {
/// Frame statistics as a JSON object (device, frame index, CPU/GPU ms, passes, culled passes).
std::string statsToJson(const FrameStats& stats, const std::string& device);
} // namespace weft
