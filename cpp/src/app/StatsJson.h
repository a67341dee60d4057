#pragma once
#include <string>
#include <vector>

#include <weft/FrameStats.h>

namespace weft {
/// Frame statistics as a JSON object (device, frame index, CPU/GPU ms, passes, culled passes),
/// written by nlohmann-json: strings escaped (control characters as \u00XX), bytes that are not
/// UTF-8 replaced by U+FFFD, unmeasured times (negative) as null.
std::string statsToJson(const FrameStats& stats, const std::string& device);
/// Several frames' statistics as a JSON array of such objects, one per line.
std::string statsToJson(const std::vector<FrameStats>& frames, const std::string& device);
} // namespace weft
