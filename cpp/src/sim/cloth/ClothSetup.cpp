// Building a cloth: parameter checks, the particle grid, constraints sorted into
// conflict-free batches (graph colouring of the regular grid), tethers, inverse masses.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "core/Validate.h"
#include "sim/cloth/ClothImpl.h"

namespace weft {

namespace {

using namespace cloth_limits;

std::string num(float v) { return std::to_string(v); }

void requireRange(float v, float lo, float hi, const char* what, const char* unit) {
    if (!(std::isfinite(v) && v >= lo && v <= hi))
        throw InvalidArgument(std::string(what) + " must be in [" + num(lo) + ", " + num(hi) +
                              "] " + unit + " (got " + num(v) + ")");
}

void requireMagnitude(const glm::vec3& v, float hi, const char* what, const char* unit) {
    requireFinite(v, what);
    if (glm::length(glm::dvec3(v)) > double(hi))
        throw InvalidArgument(std::string(what) + " must have magnitude at most " + num(hi) + " " +
                              unit);
}

} // namespace

void ClothParams::validate() const {
    if (nx < 1 || ny < 1 || int64_t(nx) * ny < 2 || nx > 4096 || ny > 4096)
        throw InvalidArgument("cloth grid must have 1..4096 particles per side and at least 2 "
                              "in all (got " +
                              std::to_string(nx) + "x" + std::to_string(ny) + ")");
    requireRange(size.x, kMinSize, kMaxSize, "cloth size_x", "m");
    requireRange(size.y, kMinSize, kMaxSize, "cloth size_y", "m");
    requireFinite(origin, "cloth origin");
    for (int c = 0; c < 3; ++c)
        if (std::abs(origin[c]) > kMaxCoordinate)
            throw InvalidArgument("cloth origin coordinates must be within +-" +
                                  num(kMaxCoordinate) + " m");
    requireFinite(axisU, "cloth axis_u");
    requireFinite(axisV, "cloth axis_v");
    if (glm::length(axisU) < 1e-6f || glm::length(axisV) < 1e-6f ||
        glm::length(glm::cross(glm::normalize(axisU), glm::normalize(axisV))) < 1e-3f)
        throw InvalidArgument("cloth axes must be non-zero and not parallel");
    requireRange(mass, kMinMass, kMaxMass, "cloth mass", "kg");
    if (bendDistance < 2 || bendDistance > 64)
        throw InvalidArgument("bend_distance must be in [2, 64] (seed: 2, 4 or 6)");
    requireFinite(damping, "damping");
    if (damping < 0.0f || damping > 1.0f) throw InvalidArgument("damping must be in [0, 1]");
    requireMagnitude(gravity, kMaxAcceleration, "gravity", "m/s^2");
    if (iterations < 1 || iterations > 1000)
        throw InvalidArgument("iterations must be in [1, 1000]");
    if (substeps < 1 || substeps > 1000) throw InvalidArgument("substeps must be in [1, 1000]");
    requireRange(complianceStretch, 0.0f, kMaxCompliance, "compliance_stretch", "m/N");
    requireRange(complianceShear, 0.0f, kMaxCompliance, "compliance_shear", "m/N");
    requireRange(complianceBend, 0.0f, kMaxCompliance, "compliance_bend", "m/N");
    requireRange(thickness, 0.0f, kMaxThickness, "thickness", "m");
    requireRange(selfThickness, 0.0f, kMaxThickness, "self_thickness", "m");
    requireRange(tearStrain, 0.0f, kMaxTearStrain, "tear_strain", "");
    requireRange(sleepThreshold, 0.0f, kMaxSleepSpeed, "sleep_threshold", "m/s");
    if (sleepSteps < 1) throw InvalidArgument("sleep_steps must be >= 1");
    if (threads < 0 || threads > 256) throw InvalidArgument("threads must be in [0, 256]");
}

void Wind::validate() const {
    requireFinite(direction, "wind direction");
    if (glm::length(glm::dvec3(direction)) < 1e-12)
        throw InvalidArgument("wind direction must not be zero");
    requireRange(strength, -kMaxAcceleration, kMaxAcceleration, "wind strength", "m/s^2");
}

namespace {
struct Offset {
    int dx, dy;
    ConstraintFamily family;
};
} // namespace

void Cloth::Impl::build() {
    const ClothParams& p = params;
    n = p.nx * p.ny;
    const glm::vec3 u = glm::normalize(p.axisU), v = glm::normalize(p.axisV);
    // Rest positions relative to the origin, in double (rest lengths come from them), so
    // neither the distance from the world origin nor the scale rounds them away.
    // Near the world origin (within a few cloth sizes) world coordinates lose nothing and
    // the step publishes no copy; farther out the frame moves to the origin.
    const double extent = double(std::max(p.size.x, p.size.y));
    const double far = std::max(
        {std::abs(double(p.origin.x)), std::abs(double(p.origin.y)), std::abs(double(p.origin.z))});
    frame = far > 4.0 * extent ? glm::dvec3(p.origin) : glm::dvec3(0.0);
    const glm::dvec3 start = glm::dvec3(p.origin) - frame;
    std::vector<glm::dvec3> restD(static_cast<size_t>(n));
    rest.resize(size_t(n));
    for (int j = 0; j < p.ny; ++j)
        for (int i = 0; i < p.nx; ++i) {
            const double fu = p.nx > 1 ? double(i) / double(p.nx - 1) : 0.0;
            const double fv = p.ny > 1 ? double(j) / double(p.ny - 1) : 0.0;
            const glm::dvec3 r = start + glm::dvec3(u) * (double(p.size.x) * fu) +
                                 glm::dvec3(v) * (double(p.size.y) * fv);
            restD[size_t(j * p.nx + i)] = r;
            rest[size_t(j * p.nx + i)] = glm::vec3(r);
        }
    baseInvMass.assign(size_t(n), float(n) / p.mass);
    pinned.assign(size_t(n), 0);
    hole.assign(size_t(n), 0);
    normals.assign(size_t(n), glm::vec4(glm::normalize(glm::cross(v, u)), 0.0f));
    particles.resize(size_t(n));
    previous.resize(size_t(n));
    for (int k = 0; k < n; ++k) {
        particles[size_t(k)] = {rest[size_t(k)], baseInvMass[size_t(k)]};
        previous[size_t(k)].x = rest[size_t(k)];
    }

    const int k = p.bendDistance;
    std::vector<Offset> offsets = {
        {1, 0, ConstraintFamily::Stretch}, {0, 1, ConstraintFamily::Stretch},
        {1, 1, ConstraintFamily::Shear},   {1, -1, ConstraintFamily::Shear},
        {k, k, ConstraintFamily::Bend},    {k, -k, ConstraintFamily::Bend}};
    if (p.extraAxial) {
        offsets.push_back({k, 0, ConstraintFamily::Bend});
        offsets.push_back({0, k, ConstraintFamily::Bend});
    }
    constraints.clear();
    family.clear();
    batches.clear();
    for (const Offset& o : offsets) {
        for (int parity = 0; parity < 2; ++parity) {
            cloth::Batch batch{o.family, int(constraints.size()), 0, o.dx, o.dy};
            for (int j = 0; j < p.ny; ++j)
                for (int i = 0; i < p.nx; ++i) {
                    const int i2 = i + o.dx, j2 = j + o.dy;
                    if (i2 < 0 || i2 >= p.nx || j2 < 0 || j2 >= p.ny) continue;
                    const int colour = (o.dx != 0 ? i / std::abs(o.dx) : j / std::abs(o.dy)) % 2;
                    if (colour != parity) continue;
                    const int a = j * p.nx + i, b = j2 * p.nx + i2;
                    constraints.push_back(
                        {a, b, float(glm::length(restD[size_t(b)] - restD[size_t(a)]))});
                    family.push_back(uint8_t(o.family));
                }
            batch.end = int(constraints.size());
            if (batch.end > batch.begin) batches.push_back(std::move(batch));
        }
    }
    endA.resize(constraints.size());
    restLength.resize(constraints.size());
    for (size_t c = 0; c < constraints.size(); ++c) {
        endA[c] = constraints[c].a;
        restLength[c] = constraints[c].rest;
    }
    active.assign(constraints.size(), 1);
    faceAlive.assign(size_t(2) * size_t(std::max(p.nx - 1, 0)) * size_t(std::max(p.ny - 1, 0)), 1);
    torn = false;
    lambda.assign(constraints.size(), 0.0f);
    // WEFT_CLOTH_AOS=1 keeps the record layout (for A/B timings and the identity tests)
    const char* aos = std::getenv("WEFT_CLOTH_AOS");
    useSoa = cloth::hasSoaKernels() && !(aos && *aos && *aos != '0');
    if (useSoa) {
        const int m = 2 * k; // dx in {0, 1, k}: the colour of column i is that of i mod m
        soaSegment = (p.nx + m - 1) / m;
        const int stride = p.ny * soaSegment; // slots per class
        soaSlots = m * stride;
        soaSlot.resize(size_t(n));
        for (int j = 0; j < p.ny; ++j)
            for (int i = 0; i < p.nx; ++i)
                soaSlot[size_t(j * p.nx + i)] = (i % m) * stride + j * soaSegment + i / m;
        soaStride = (size_t(soaSlots) + cloth::kSoaPad + 15) / 16 * 16;
        soa.assign(4 * soaStride, 0.0f);
        denseRest.assign(batches.size() * size_t(soaSlots) + cloth::kSoaPad, -1.0f);
        denseLambda.assign(denseRest.size(), 0.0f);
        batchSegments.clear();
        for (cloth::Batch& b : batches) {
            b.parity = (b.dx != 0 ? constraints[size_t(b.begin)].a % p.nx / b.dx
                                  : constraints[size_t(b.begin)].a / p.nx / std::abs(b.dy)) %
                       2;
            b.rowBegin = std::max(0, -b.dy);
            b.rowEnd = std::min(p.ny, p.ny - b.dy);
            b.segmentsBegin = int(batchSegments.size());
            for (int c = 0; c < m; ++c) {
                if (b.dx != 0 && (c / b.dx) % 2 != b.parity) continue;
                const int cb = (c + b.dx) % m, shift = (c + b.dx) / m;
                batchSegments.push_back(
                    {c * stride, (cb - c) * stride + b.dy * soaSegment + shift});
            }
            b.segmentsEnd = int(batchSegments.size());
        }
    }
    denseStale = true;
}

void Cloth::Impl::syncDense() {
    if (!useSoa) return;
    std::fill(denseRest.begin(), denseRest.end(), -1.0f);
    for (size_t b = 0; b < batches.size(); ++b)
        for (int c = batches[b].begin; c < batches[b].end; ++c)
            if (active[size_t(c)])
                denseRest[b * size_t(soaSlots) +
                          size_t(soaSlot[size_t(constraints[size_t(c)].a)])] =
                    constraints[size_t(c)].rest;
    const cloth::SoaParticles s = soaParticles();
    std::fill(s.w, s.w + soaStride, 0.0f); // unused slots: fixed
    for (int q = 0; q < n; ++q) s.w[soaSlot[size_t(q)]] = particles[size_t(q)].w;
    tetherAnchorSoa.assign(size_t(tetherSlots) * size_t(soaSlots), 0);
    tetherLengthSoa.assign(size_t(tetherSlots) * size_t(soaSlots),
                           std::numeric_limits<float>::infinity());
    tetherTable.clear();
    bool small = true;
    for (int s2 = 0; s2 < tetherSlots; ++s2)
        for (int q = 0; q < n; ++q) {
            const size_t from = size_t(s2) * size_t(n) + size_t(q);
            const size_t to = size_t(s2) * size_t(soaSlots) + size_t(soaSlot[size_t(q)]);
            const int anchor = soaSlot[size_t(tetherAnchor[from])];
            tetherAnchorSoa[to] = anchor;
            tetherLengthSoa[to] = tetherLength[from];
            if (!small || tetherLength[from] == std::numeric_limits<float>::infinity()) continue;
            if (std::find(tetherTable.begin(), tetherTable.end(), anchor) == tetherTable.end()) {
                if (tetherTable.size() < size_t(cloth::kTetherTable))
                    tetherTable.push_back(anchor);
                else
                    small = false;
            }
        }
    if (!small) tetherTable.clear();
    if (!tetherTable.empty()) {
        // slots without a tether (length +inf) keep anchor index 0: never pulled
        for (size_t t = 0; t < tetherAnchorSoa.size(); ++t)
            tetherAnchorSoa[t] =
                tetherLengthSoa[t] == std::numeric_limits<float>::infinity()
                    ? 0
                    : int(std::find(tetherTable.begin(), tetherTable.end(), tetherAnchorSoa[t]) -
                          tetherTable.begin());
    }
    denseStale = false;
}

void Cloth::Impl::applyInverseMasses() {
    for (int k = 0; k < n; ++k) {
        const bool fixed = pinned[size_t(k)] || hole[size_t(k)];
        particles[size_t(k)].w = fixed ? 0.0f : baseInvMass[size_t(k)];
    }
    for (int g : grabbed) particles[size_t(g)].w = 0.0f;
    // Constraints touching a hole are gone (the mesh leaves them out too), and torn ones.
    updateActive();
    rebuildTethers();
    publish(); // the records carry w
}

void Cloth::Impl::rebuildTethers() {
    denseStale = true;
    // Every free particle is tied to its nearest anchors (pinned or grabbed particles) at their
    // rest distance: an inextensible cloth never gets farther from any anchor than that, so
    // the tethers only remove stretch the constraints have not resolved yet. Tying to one
    // anchor only would pull the cloth apart where the nearest anchor changes.
    constexpr size_t kMaxAnchors = 4;
    tetherSlots = 0;
    tetherAnchor.clear();
    tetherLength.clear();
    if (!params.tethers) return;
    std::vector<int> anchors;
    for (int k = 0; k < n; ++k)
        if (!hole[size_t(k)] && particles[size_t(k)].w == 0.0f) anchors.push_back(k);
    if (anchors.empty()) return;
    // Holes or tears: straight rest distances may cross empty space (too short a tether) or
    // tie a piece to an anchor it is no longer attached to; measure along the cloth instead.
    if (std::find(active.begin(), active.end(), uint8_t(0)) != active.end()) {
        tethersAlongCloth(anchors);
        return;
    }
    tetherSlots = int(std::min(kMaxAnchors, anchors.size()));
    tetherAnchor.resize(size_t(tetherSlots) * size_t(n));
    tetherLength.assign(size_t(tetherSlots) * size_t(n), std::numeric_limits<float>::infinity());
    for (int k = 0; k < n; ++k)
        for (int s = 0; s < tetherSlots; ++s) tetherAnchor[size_t(s) * size_t(n) + size_t(k)] = k;
    std::vector<std::pair<float, int>> nearest;
    for (int k = 0; k < n; ++k) {
        if (particles[size_t(k)].w == 0.0f) continue;
        nearest.clear();
        for (int a : anchors)
            nearest.push_back({glm::length(rest[size_t(k)] - rest[size_t(a)]), a});
        std::partial_sort(nearest.begin(), nearest.begin() + tetherSlots, nearest.end());
        for (int s = 0; s < tetherSlots; ++s) {
            tetherAnchor[size_t(s) * size_t(n) + size_t(k)] = nearest[size_t(s)].second;
            tetherLength[size_t(s) * size_t(n) + size_t(k)] = nearest[size_t(s)].first;
        }
    }
}

} // namespace weft
