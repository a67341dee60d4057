// Dome of shadow lights: layouts, Voronoi-cell intensities and the seed's eq. 2.22 / 2.23.
#include <weft/ShadowDome.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <weft/Error.h>

#include "CubeTexels.h"
#include "IblParallel.h"
#include "IblValidate.h"

namespace weft {

namespace {

constexpr double kPi = 3.14159265358979323846;

glm::vec3 shade(const std::vector<DomeLight>& lights, const glm::vec3& normal,
                const std::vector<uint8_t>& visible, bool wantVisible) {
    if (visible.size() != lights.size())
        throw InvalidArgument("visibility must have one entry per dome light (" +
                              std::to_string(lights.size()) + "), got " +
                              std::to_string(visible.size()));
    requireFinite(normal, "normal");
    const glm::vec3 n = glm::normalize(normal);
    glm::vec3 sum(0.0f);
    for (size_t i = 0; i < lights.size(); ++i)
        if ((visible[i] != 0) == wantVisible)
            sum += lights[i].intensity * std::max(0.0f, glm::dot(n, lights[i].direction));
    return sum;
}

} // namespace

std::vector<glm::vec3> ShadowDome::directions(int count, DomeLayout layout) {
    if (count < 8 || count > 4096 || count % 8 != 0)
        throw InvalidArgument("dome light count must be a multiple of 8 in [8, 4096], got " +
                              std::to_string(count));
    std::vector<glm::vec3> dirs;
    if (layout == DomeLayout::Fibonacci) {
        const double golden = kPi * (3.0 - std::sqrt(5.0));
        for (int k = 0; k < count; ++k) {
            const double y = 1.0 - (k + 0.5) / count, r = std::sqrt(1.0 - y * y);
            dirs.emplace_back(float(r * std::cos(k * golden)), float(y),
                              float(r * std::sin(k * golden)));
        }
    } else {
        const int rings = count / 8;
        for (int ring = 0; ring < rings; ++ring) {
            const double y = 1.0 - (ring + 0.5) / rings, r = std::sqrt(1.0 - y * y);
            for (int k = 0; k < 8; ++k) {
                const double phi = 2.0 * kPi * (k + 0.5 * (ring % 2)) / 8.0;
                dirs.emplace_back(float(r * std::cos(phi)), float(y), float(r * std::sin(phi)));
            }
        }
    }
    return dirs;
}

ShadowDome::ShadowDome(const CubeMap& radiance, int count, DomeLayout layout, int sourceSize) {
    requireCube(radiance, "radiance cube map");
    requireCount(sourceSize, 1024, "source size");
    const auto dirs = directions(count, layout);
    requireAffordable(6.0 * sourceSize * sourceSize * count, "dome intensities");
    const CubeTexels t = cubeTexels(reducedCube(radiance, sourceSize));
    std::vector<int> owner(t.size(), -1);
    iblParallelFor(
        int(t.size()),
        [&](int begin, int end) {
            for (int k = begin; k < end; ++k) {
                if (t.y[size_t(k)] <= 0.0f) continue;
                float best = -2.0f;
                for (int i = 0; i < count; ++i) {
                    const glm::vec3& d = dirs[size_t(i)];
                    const float c =
                        d.x * t.x[size_t(k)] + d.y * t.y[size_t(k)] + d.z * t.z[size_t(k)];
                    if (c > best) {
                        best = c;
                        owner[size_t(k)] = i;
                    }
                }
            }
        },
        1024);
    std::vector<glm::dvec3> sum(size_t(count), glm::dvec3(0.0)),
        moment(size_t(count), glm::dvec3(0.0));
    std::vector<glm::dvec3> spreadMoment(size_t(count), glm::dvec3(0.0));
    std::vector<double> omega(size_t(count), 0.0), power(size_t(count), 0.0),
        spreadPower(size_t(count), 0.0);
    for (size_t k = 0; k < t.size(); ++k) {
        if (owner[k] < 0) continue;
        const size_t i = size_t(owner[k]);
        const glm::dvec3 rgb(t.r[k], t.g[k], t.b[k]);
        sum[i] += rgb;
        omega[i] += t.dw[k];
        // luminance-weighted moment of the directions: its direction is where the cell's light
        // comes from on average (a sun in the cell pulls the light onto itself; the fixed cell
        // centre would put the shadow up to a cell's radius off), its length the spread
        const double lum = std::max(0.0, 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b);
        const glm::dvec3 dir(t.x[k], t.y[k], t.z[k]);
        moment[i] += lum * dir;
        power[i] += lum;
        // the spread weighted by L^2 dw: a sun sharing its cell with sky keeps its own (sharp)
        // size, a smooth cell its full extent
        const double w2 = t.dw[k] > 0.0f ? lum * lum / double(t.dw[k]) : 0.0;
        spreadMoment[i] += w2 * dir;
        spreadPower[i] += w2;
    }
    for (int i = 0; i < count; ++i) {
        DomeLight l;
        l.direction = dirs[size_t(i)];
        l.intensity = glm::vec3(sum[size_t(i)]);
        l.solidAngle = float(omega[size_t(i)]);
        // A black cell keeps its layout direction and the radius of a cone of its solid angle.
        double cosRadius = 1.0 - omega[size_t(i)] / (2.0 * kPi);
        const double len = glm::length(moment[size_t(i)]);
        if (power[size_t(i)] > 0.0 && len > 1e-12 * power[size_t(i)]) {
            const glm::dvec3 d = moment[size_t(i)] / len;
            if (d.y > 1e-4) l.direction = glm::vec3(d);
            // A uniform cone of half-angle a has mean cosine (1 + cos a) / 2 about its axis:
            // the cone with this cell's mean cosine about V_i.
            cosRadius = 2.0 * glm::dot(spreadMoment[size_t(i)], d) / spreadPower[size_t(i)] - 1.0;
        }
        l.angularRadius = float(std::acos(std::clamp(cosRadius, -1.0, 1.0)));
        mLights.push_back(l);
    }
}

glm::vec3 ShadowDome::diffuseVisible(const glm::vec3& normal,
                                     const std::vector<uint8_t>& visible) const {
    return shade(mLights, normal, visible, true);
}

glm::vec3 ShadowDome::diffuseSubtract(const glm::vec3& normal, const glm::vec3& irradiance,
                                      const std::vector<uint8_t>& visible) const {
    requireFinite(irradiance, "irradiance");
    return irradiance - shade(mLights, normal, visible, false);
}

std::vector<int> ShadowDome::refreshSet(long long frame, int perFrame) const {
    if (perFrame < 1) throw InvalidArgument("lights refreshed per frame must be >= 1");
    if (frame < 0) throw InvalidArgument("frame index must be >= 0");
    const int n = size();
    perFrame = std::min(perFrame, n);
    const long long rounds = (n + perFrame - 1) / perFrame;
    const long long start = (frame % rounds) * perFrame;
    std::vector<int> out;
    for (long long k = start; k < start + perFrame && k < n; ++k) out.push_back(int(k));
    return out;
}

} // namespace weft
