#include <weft/HairGeometry.h>

#include <cmath>

#include <weft/Error.h>

namespace weft {

namespace {

constexpr float kTinySquared = 1e-24f;

glm::vec3 normalizedOr(const glm::vec3& v, const glm::vec3& fallback) {
    const float len2 = glm::dot(v, v);
    return len2 > kTinySquared ? v / std::sqrt(len2) : fallback;
}

} // namespace

std::vector<glm::vec3> strandTangents(const HairStrands& strands) {
    strands.validate();
    const std::vector<uint64_t> offsets = strands.offsets();
    const std::vector<glm::vec3>& p = strands.points;
    std::vector<glm::vec3> out(p.size());
    for (size_t s = 0; s + 1 < offsets.size(); ++s) {
        const size_t first = size_t(offsets[s]), last = size_t(offsets[s + 1]) - 1;
        const glm::vec3 whole = normalizedOr(p[last] - p[first], glm::vec3(0.0f, 1.0f, 0.0f));
        for (size_t i = first; i <= last; ++i) {
            const size_t prev = i > first ? i - 1 : i, next = i < last ? i + 1 : i;
            out[i] = normalizedOr(p[next] - p[prev], whole);
        }
    }
    return out;
}

std::vector<glm::vec3> strandRibbons(const HairStrands& strands, const glm::vec3& eye,
                                     float widthScale) {
    if (!std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z))
        throw InvalidArgument("ribbons: eye must be finite");
    if (!(std::isfinite(widthScale) && widthScale >= 0.0f))
        throw InvalidArgument("ribbons: width scale must be finite and >= 0");
    const std::vector<glm::vec3> tangents = strandTangents(strands);
    const std::vector<glm::vec3>& p = strands.points;
    std::vector<glm::vec3> out(2 * p.size());
    for (size_t i = 0; i < p.size(); ++i) {
        const glm::vec3& t = tangents[i];
        const glm::vec3 up = std::abs(t.y) < 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 fallback = glm::normalize(glm::cross(t, up));
        const glm::vec3 side = normalizedOr(glm::cross(t, eye - p[i]), fallback);
        const float thickness =
            strands.thickness.empty() ? strands.defaultThickness : strands.thickness[i];
        const glm::vec3 half = side * (0.5f * widthScale * thickness);
        out[2 * i] = p[i] - half;
        out[2 * i + 1] = p[i] + half;
    }
    return out;
}

std::vector<uint32_t> ribbonIndices(const HairStrands& strands) {
    strands.validate();
    if (2 * strands.pointCount() > UINT32_MAX)
        throw InvalidArgument("ribbons: too many points for 32-bit indices");
    const std::vector<uint64_t> offsets = strands.offsets();
    std::vector<uint32_t> out;
    out.reserve(6 * (strands.pointCount() - strands.strandCount()));
    for (size_t s = 0; s + 1 < offsets.size(); ++s)
        for (uint64_t i = offsets[s]; i + 1 < offsets[s + 1]; ++i) {
            const uint32_t a = uint32_t(2 * i), b = a + 1, c = a + 2, d = a + 3;
            out.insert(out.end(), {a, b, c, b, d, c});
        }
    return out;
}

} // namespace weft
