#include "app/StatsJson.h"

#include <nlohmann/json.hpp>

namespace weft {
namespace {

// ordered_json keeps the keys in the order a reader expects (device first), not sorted.
using Json = nlohmann::ordered_json;

Json ms(double v) { return v < 0 ? Json(nullptr) : Json(v); }

Json toJson(const FrameStats& stats, const std::string& device) {
    Json passes = Json::array();
    for (const PassStats& p : stats.passes)
        passes.push_back({{"name", p.name}, {"cpu_ms", ms(p.cpuMs)}, {"gpu_ms", ms(p.gpuMs)}});
    return {
        {"device", device},          {"frame_index", stats.frameIndex}, {"cpu_ms", ms(stats.cpuMs)},
        {"gpu_ms", ms(stats.gpuMs)}, {"passes", std::move(passes)},     {"culled", stats.culled},
        {"reused", stats.reused}};
}

// Names come from the device driver and from pass names; a byte sequence that is not UTF-8
// must not make the stats unwritable, so it is replaced rather than thrown on.
std::string dump(const Json& j) { return j.dump(-1, ' ', false, Json::error_handler_t::replace); }

} // namespace

std::string statsToJson(const FrameStats& stats, const std::string& device) {
    return dump(toJson(stats, device));
}

std::string statsToJson(const std::vector<FrameStats>& frames, const std::string& device) {
    std::string out = "[";
    for (size_t i = 0; i < frames.size(); ++i)
        out += (i ? ",\n" : "\n") + dump(toJson(frames[i], device));
    return out + "\n]\n";
}

} // namespace weft
