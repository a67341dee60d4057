#include <weft/HairStrands.h>

#include <cmath>

#include <weft/Error.h>

namespace weft {

namespace {

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void requirePerPoint(size_t size, size_t points, const char* what) {
    if (size != 0 && size != points)
        throw InvalidArgument(std::string("hair ") + what + " has " + std::to_string(size) +
                              " entries for " + std::to_string(points) + " points");
}

} // namespace

size_t HairStrands::strandCount() const {
    if (!segments.empty()) return segments.size();
    return points.size() / (size_t(defaultSegments) + 1);
}

std::vector<uint64_t> HairStrands::offsets() const {
    const size_t n = strandCount();
    std::vector<uint64_t> out(n + 1, 0);
    for (size_t s = 0; s < n; ++s)
        out[s + 1] = out[s] + uint64_t(segments.empty() ? defaultSegments : segments[s]) + 1;
    return out;
}

void HairStrands::validate() const {
    if (points.empty()) throw InvalidArgument("hair strands need at least one point");
    if (segments.empty()) {
        const uint64_t per = uint64_t(defaultSegments) + 1;
        if (points.size() % per != 0)
            throw InvalidArgument("hair: " + std::to_string(points.size()) +
                                  " points are not a whole number of strands of " +
                                  std::to_string(per) + " points (default segments)");
    } else {
        uint64_t sum = 0;
        for (uint16_t s : segments) sum += uint64_t(s) + 1;
        if (sum != points.size())
            throw InvalidArgument("hair: the segments add up to " + std::to_string(sum) +
                                  " points but there are " + std::to_string(points.size()));
    }
    requirePerPoint(thickness.size(), points.size(), "thickness");
    requirePerPoint(transparency.size(), points.size(), "transparency");
    requirePerPoint(colors.size(), points.size(), "colours");
    for (const glm::vec3& p : points)
        if (!finite3(p)) throw InvalidArgument("hair points must be finite (got NaN or inf)");
    for (float t : thickness)
        if (!(t >= 0.0f) || !std::isfinite(t))
            throw InvalidArgument("hair thickness must be finite and >= 0");
    for (float a : transparency)
        if (!(a >= 0.0f && a <= 1.0f)) throw InvalidArgument("hair transparency must be in [0, 1]");
    for (const glm::vec3& c : colors)
        if (!finite3(c) || c.x < 0.0f || c.y < 0.0f || c.z < 0.0f)
            throw InvalidArgument("hair colours must be finite and >= 0");
    if (!(defaultThickness >= 0.0f) || !std::isfinite(defaultThickness))
        throw InvalidArgument("hair default thickness must be finite and >= 0");
    if (!(defaultTransparency >= 0.0f && defaultTransparency <= 1.0f))
        throw InvalidArgument("hair default transparency must be in [0, 1]");
    if (!finite3(defaultColor) || defaultColor.x < 0.0f || defaultColor.y < 0.0f ||
        defaultColor.z < 0.0f)
        throw InvalidArgument("hair default colour must be finite and >= 0");
    if (info.size() > 88) throw InvalidArgument("hair info text is longer than 88 characters");
}

} // namespace weft
