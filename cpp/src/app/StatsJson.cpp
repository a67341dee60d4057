#include "app/StatsJson.h"

#include <sstream>

namespace weft {
namespace {
std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (static_cast<unsigned char>(c) >= 0x20) out += c;
    }
    return out + "\"";
}
std::string ms(double v) {
    if (v < 0) return "null";
    std::ostringstream s;
    s << v;
    return s.str();
}
} // namespace

std::string statsToJson(const FrameStats& stats, const std::string& device) {
    std::ostringstream o;
    o << "{\"device\": " << quoted(device) << ", \"frame_index\": " << stats.frameIndex
      << ", \"cpu_ms\": " << ms(stats.cpuMs) << ", \"gpu_ms\": " << ms(stats.gpuMs)
      << ", \"passes\": [";
    for (size_t i = 0; i < stats.passes.size(); ++i)
        o << (i ? ", " : "") << "{\"name\": " << quoted(stats.passes[i].name)
          << ", \"cpu_ms\": " << ms(stats.passes[i].cpuMs)
          << ", \"gpu_ms\": " << ms(stats.passes[i].gpuMs) << "}";
    o << "], \"culled\": [";
    for (size_t i = 0; i < stats.culled.size(); ++i) o << (i ? ", " : "") << quoted(stats.culled[i]);
    o << "], \"reused\": [";
    for (size_t i = 0; i < stats.reused.size(); ++i) o << (i ? ", " : "") << quoted(stats.reused[i]);
    o << "]}";
    return o.str();
}
} // namespace weft
