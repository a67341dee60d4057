#include <weft/HairGenerator.h>

#include <cmath>
#include <string>

#include <glm/gtc/constants.hpp>

#include <weft/Error.h>

#include "core/ThreadPool.h"
#include "hair/HairRandom.h"

namespace weft {

namespace {

bool finitePositive(float v) { return std::isfinite(v) && v > 0.0f; }

// The strand's turning axis: perpendicular to the normal and to -Y (any perpendicular when the
// normal is vertical).
glm::vec3 droopAxis(const glm::vec3& n) {
    glm::vec3 axis = glm::cross(n, glm::vec3(0.0f, -1.0f, 0.0f));
    if (glm::dot(axis, axis) < 1e-12f) axis = glm::cross(n, glm::vec3(1.0f, 0.0f, 0.0f));
    return glm::normalize(axis);
}

// `v` (perpendicular to the unit `axis`) turned by `angle` about `axis`.
glm::vec3 turn(const glm::vec3& v, const glm::vec3& axis, float angle) {
    return std::cos(angle) * v + std::sin(angle) * glm::cross(axis, v);
}

} // namespace

void HairStyle::validate() const {
    if (strands == 0) throw InvalidArgument("hair style: strands must be >= 1");
    if (points < 2ull * strands || points > 65536ull * strands)
        throw InvalidArgument("hair style: points must give every strand 2 to 65,536 points (" +
                              std::to_string(points) + " points for " + std::to_string(strands) +
                              " strands)");
    if (points > UINT32_MAX) throw InvalidArgument("hair style: more than 2^32 - 1 points");
    if (!finitePositive(length)) throw InvalidArgument("hair style: length must be > 0");
    if (!(lengthJitter >= 0.0f && lengthJitter < 1.0f))
        throw InvalidArgument("hair style: length jitter must be in [0, 1)");
    if (!(std::isfinite(waveAmplitude) && waveAmplitude >= 0.0f))
        throw InvalidArgument("hair style: wave amplitude must be finite and >= 0");
    if (!(std::isfinite(waveFrequency) && waveFrequency >= 0.0f))
        throw InvalidArgument("hair style: wave frequency must be finite and >= 0");
    if (!(std::isfinite(curlRadius) && curlRadius >= 0.0f))
        throw InvalidArgument("hair style: curl radius must be finite and >= 0");
    if (!(droop >= 0.0f && droop <= 1.0f))
        throw InvalidArgument("hair style: droop must be in [0, 1]");
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(scalpCenter[i]))
            throw InvalidArgument("hair style: scalp centre must be finite");
        if (!finitePositive(scalpRadii[i]))
            throw InvalidArgument("hair style: scalp radii must be > 0");
    }
    if (!(scalpCutoff >= -1.0f && scalpCutoff < 1.0f))
        throw InvalidArgument("hair style: scalp cutoff must be in [-1, 1)");
}

HairStrands generateHair(const HairStyle& style) {
    style.validate();
    const uint32_t n = style.strands;
    const uint64_t base = style.points / n, extra = style.points % n;
    HairStrands h;
    h.segments.resize(n);
    for (uint32_t s = 0; s < n; ++s) h.segments[s] = uint16_t(base + (s < extra ? 1 : 0) - 1);
    const std::vector<uint64_t> offsets = h.offsets();
    h.points.resize(size_t(style.points));
    h.info = "weft generated hair";

    PoolShare(style.threads)
        .parallelFor(
            int(n),
            [&](int begin, int end) {
                for (int s = begin; s < end; ++s) {
                    const uint32_t id = uint32_t(s);
                    // Root: uniform in height over the cap and in azimuth, scaled onto the
                    // ellipsoid.
                    const float y = style.scalpCutoff +
                                    (1.0f - style.scalpCutoff) * hair::random01(style.seed, id, 0);
                    const float azimuth = glm::two_pi<float>() * hair::random01(style.seed, id, 1);
                    const float ring = std::sqrt(std::max(0.0f, 1.0f - y * y));
                    const glm::vec3 unit(ring * std::cos(azimuth), y, ring * std::sin(azimuth));
                    const glm::vec3 root = style.scalpCenter + unit * style.scalpRadii;
                    const glm::vec3 normal = glm::normalize(unit / style.scalpRadii);
                    const float length =
                        style.length *
                        (1.0f +
                         style.lengthJitter * (2.0f * hair::random01(style.seed, id, 2) - 1.0f));
                    const glm::vec3 axis = droopAxis(normal);
                    // The angle the direction turns through by the tip: droop * angle(normal, -Y).
                    const float bend = style.droop * std::acos(glm::clamp(-normal.y, -1.0f, 1.0f));
                    const float phase = glm::two_pi<float>() * hair::random01(style.seed, id, 3);

                    const uint64_t first = offsets[size_t(s)],
                                   count = offsets[size_t(s) + 1] - first;
                    const float ds = length / float(count - 1);
                    glm::vec3 centre = root;
                    for (uint64_t k = 0; k < count; ++k) {
                        const float arc = ds * float(k);
                        if (k > 0) { // midpoint rule along the turning direction
                            const float mid = (arc - 0.5f * ds) / length;
                            centre += ds * turn(normal, axis, bend * mid);
                        }
                        const glm::vec3 dir = turn(normal, axis, bend * arc / length);
                        const glm::vec3 side = glm::cross(dir, axis);
                        glm::vec3 offset(0.0f);
                        const float w = glm::two_pi<float>() * style.waveFrequency * arc;
                        if (style.kind == HairStyleKind::Wavy) {
                            offset = style.waveAmplitude * (std::sin(w + phase) - std::sin(phase)) *
                                     side;
                        } else if (style.kind == HairStyleKind::Curly) {
                            offset =
                                style.curlRadius * ((std::cos(w + phase) - std::cos(phase)) * axis +
                                                    (std::sin(w + phase) - std::sin(phase)) * side);
                        }
                        h.points[size_t(first + k)] = centre + offset;
                    }
                }
            },
            64);
    return h;
}

} // namespace weft
