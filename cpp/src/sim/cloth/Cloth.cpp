// weft::Cloth public API: argument checks and state changes around the solver.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/Validate.h"
#include "sim/cloth/ClothImpl.h"

namespace weft {

namespace {

void checkPoints(const std::vector<glm::vec3>& v, size_t expected, const char* what) {
    if (v.size() != expected)
        throw InvalidArgument(std::string(what) + " must have " + std::to_string(expected) +
                              " rows (got " + std::to_string(v.size()) + ")");
    for (const glm::vec3& p : v) requireFinite(p, what);
}

void checkIndices(const std::vector<int>& idx, int n, const char* what) {
    for (int i : idx)
        if (i < 0 || i >= n)
            throw InvalidArgument(std::string(what) + ": particle index " + std::to_string(i) +
                                  " out of range [0, " + std::to_string(n) + ")");
}

} // namespace

Cloth::Cloth(const ClothParams& params) : mImpl(std::make_unique<Impl>()) {
    params.validate();
    mImpl->params = params;
    mImpl->pool = std::make_unique<ThreadPool>(params.threads);
    mImpl->build();
    mImpl->applyInverseMasses();
}

Cloth::~Cloth() = default;

bool Cloth::soaKernelsAvailable() { return cloth::hasSoaKernels(); }
Cloth::Cloth(Cloth&&) noexcept = default;
Cloth& Cloth::operator=(Cloth&&) noexcept = default;

const ClothParams& Cloth::params() const { return mImpl->params; }

void Cloth::setParams(const ClothParams& p) {
    p.validate();
    const ClothParams& o = mImpl->params;
    if (p.nx != o.nx || p.ny != o.ny || p.size != o.size || p.origin != o.origin ||
        p.axisU != o.axisU || p.axisV != o.axisV || p.mass != o.mass ||
        p.bendDistance != o.bendDistance || p.extraAxial != o.extraAxial)
        throw InvalidArgument("grid size, dimensions, axes, mass and neighbour pattern are fixed "
                              "when a cloth is made; create a new Cloth to change them");
    const bool tethersChanged = p.tethers != o.tethers;
    const bool threadsChanged = p.threads != o.threads;
    mImpl->params = p;
    if (threadsChanged) mImpl->pool = std::make_unique<ThreadPool>(p.threads);
    if (tethersChanged) mImpl->rebuildTethers();
    wake();
}

int Cloth::particleCount() const { return mImpl->n; }
int Cloth::constraintCount() const { return int(mImpl->constraints.size()); }
const float* Cloth::particleData() const { return &mImpl->particles[0].x.x; }
const float* Cloth::normalData() const { return &mImpl->currentNormals()[0].x; }

void Cloth::step(float dt) {
    if (!(std::isfinite(dt) && dt > 0.0f && dt <= 1.0f))
        throw InvalidArgument("time step must be in (0, 1] seconds (got " + std::to_string(dt) + ")");
    Impl& m = *mImpl;
    if (m.asleep) return;
    const float h = dt / float(m.params.substeps);
    const float damping = std::pow(m.params.damping, h * 60.0f);
    for (int s = 0; s < m.params.substeps; ++s) m.substep(h, damping);
    m.lastH = h;
    m.normalsStale = true;
    m.afterStep(dt);
    ++m.steps;
    ++m.meshVersion;
}

int Cloth::advance(float realDt, float rate, int maxSteps) {
    if (!(std::isfinite(realDt) && realDt >= 0.0f))
        throw InvalidArgument("advance: real_dt must be finite and >= 0");
    if (!(std::isfinite(rate) && rate >= 1.0f && rate <= 10000.0f))
        throw InvalidArgument("advance: rate must be in [1, 10000] Hz");
    if (maxSteps < 1) throw InvalidArgument("advance: max_steps must be >= 1");
    Impl& m = *mImpl;
    m.accumulator += double(realDt);
    int count = int(std::floor(m.accumulator * rate));
    if (count > maxSteps) { // too far behind: drop the backlog instead of spiralling
        count = maxSteps;
        m.accumulator = 0.0;
    } else {
        m.accumulator -= double(count) / rate;
    }
    for (int s = 0; s < count; ++s) step(1.0f / rate);
    return count;
}

void Cloth::projectConstraints() {
    Impl& m = *mImpl;
    std::fill(m.lambda.begin(), m.lambda.end(), 0.0f);
    m.relax(1.0f / 60.0f);
    ++m.meshVersion;
}

void Cloth::setPositions(const std::vector<glm::vec3>& positions, bool keepVelocity) {
    Impl& m = *mImpl;
    checkPoints(positions, size_t(m.n), "positions");
    ++m.meshVersion;
    for (int k = 0; k < m.n; ++k) {
        const glm::vec3 v = m.particles[size_t(k)].x - m.previous[size_t(k)].x;
        m.particles[size_t(k)].x = positions[size_t(k)];
        m.previous[size_t(k)].x = keepVelocity ? positions[size_t(k)] - v : positions[size_t(k)];
    }
    m.hasPendingVelocity = false;
    wake();
}

void Cloth::setVelocities(const std::vector<glm::vec3>& velocities) {
    Impl& m = *mImpl;
    checkPoints(velocities, size_t(m.n), "velocities");
    m.pendingVelocity = velocities;
    m.hasPendingVelocity = true;
    wake();
}

std::vector<glm::vec3> Cloth::velocities() const {
    const Impl& m = *mImpl;
    if (m.hasPendingVelocity) return m.pendingVelocity;
    std::vector<glm::vec3> v(size_t(m.n));
    for (int k = 0; k < m.n; ++k)
        v[size_t(k)] = (m.particles[size_t(k)].x - m.previous[size_t(k)].x) / m.lastH;
    return v;
}

void Cloth::reset() {
    Impl& m = *mImpl;
    for (int k = 0; k < m.n; ++k) {
        m.particles[size_t(k)].x = m.rest[size_t(k)];
        m.previous[size_t(k)].x = m.rest[size_t(k)];
    }
    std::fill(m.active.begin(), m.active.end(), uint8_t(1));
    m.grabbed.clear();
    m.grabTargets.clear();
    m.hasPendingVelocity = false;
    m.accumulator = 0.0;
    ++m.meshVersion;
    m.applyInverseMasses();
    wake();
}

void Cloth::pin(const std::vector<int>& particles) {
    checkIndices(particles, mImpl->n, "pin");
    for (int k : particles) mImpl->pinned[size_t(k)] = 1;
    mImpl->applyInverseMasses();
    wake();
}

void Cloth::unpin(const std::vector<int>& particles) {
    checkIndices(particles, mImpl->n, "unpin");
    for (int k : particles) mImpl->pinned[size_t(k)] = 0;
    mImpl->applyInverseMasses();
    wake();
}

void Cloth::grab(const std::vector<int>& particles, const std::vector<glm::vec3>& targets) {
    checkIndices(particles, mImpl->n, "grab");
    if (particles.empty()) throw InvalidArgument("grab: no particles given");
    checkPoints(targets, particles.size(), "grab targets");
    mImpl->grabbed = particles;
    mImpl->grabTargets = targets;
    mImpl->applyInverseMasses();
    wake();
}

void Cloth::moveGrab(const std::vector<glm::vec3>& targets) {
    if (mImpl->grabbed.empty()) throw InvalidArgument("move_grab: nothing is grabbed");
    checkPoints(targets, mImpl->grabbed.size(), "grab targets");
    mImpl->grabTargets = targets;
    wake();
}

void Cloth::release() {
    mImpl->grabbed.clear();
    mImpl->grabTargets.clear();
    mImpl->applyInverseMasses();
    wake();
}

int Cloth::pick(const glm::vec3& origin, const glm::vec3& direction, float maxDistance) const {
    requireFinite(origin, "ray origin");
    requireFinite(direction, "ray direction");
    if (glm::length(direction) < 1e-12f) throw InvalidArgument("ray direction must not be zero");
    requirePositive(maxDistance, "max_distance");
    const glm::vec3 d = glm::normalize(direction);
    int best = -1;
    float bestT = std::numeric_limits<float>::max();
    for (int k = 0; k < mImpl->n; ++k) {
        if (mImpl->hole[size_t(k)]) continue;
        const glm::vec3 rel = mImpl->particles[size_t(k)].x - origin;
        const float t = glm::dot(rel, d);
        if (t < 0.0f) continue;
        if (glm::length(rel - t * d) <= maxDistance && t < bestT) {
            bestT = t;
            best = k;
        }
    }
    return best;
}

void Cloth::setHoles(const std::vector<uint8_t>& mask) {
    Impl& m = *mImpl;
    if (mask.size() != size_t(m.n))
        throw InvalidArgument("hole mask must have ny x nx = " + std::to_string(m.n) + " entries");
    for (int k = 0; k < m.n; ++k) m.hole[size_t(k)] = mask[size_t(k)] ? 1 : 0;
    ++m.meshVersion;
    // Constraints come back only where both ends are cloth again (torn ones stay torn).
    for (size_t c = 0; c < m.constraints.size(); ++c)
        if (!m.hole[size_t(m.constraints[c].a)] && !m.hole[size_t(m.constraints[c].b)] &&
            m.params.tearStrain == 0.0f)
            m.active[c] = 1;
    m.applyInverseMasses();
    wake();
}

bool Cloth::isHole(int particle) const {
    checkIndices({particle}, mImpl->n, "is_hole");
    return mImpl->hole[size_t(particle)] != 0;
}

void Cloth::setWind(const Wind& wind) {
    requireFinite(wind.direction, "wind direction");
    requireFinite(wind.strength, "wind strength");
    if (wind.strength != 0.0f && glm::length(wind.direction) < 1e-12f)
        throw InvalidArgument("wind direction must not be zero");
    mImpl->wind = wind;
    wake();
}

const Wind& Cloth::wind() const { return mImpl->wind; }

int Cloth::addCollider(const Collider& collider) {
    collider.validate();
    mImpl->colliders.push_back(collider);
    wake();
    return int(mImpl->colliders.size() - 1);
}

void Cloth::setCollider(int id, const Collider& collider) {
    if (id < 0 || id >= int(mImpl->colliders.size()))
        throw InvalidArgument("collider id " + std::to_string(id) + " does not exist");
    collider.validate();
    mImpl->colliders[size_t(id)] = collider;
    wake();
}

void Cloth::clearColliders() {
    mImpl->colliders.clear();
    wake();
}

int Cloth::colliderCount() const { return int(mImpl->colliders.size()); }

ClothStats Cloth::stats() const {
    const Impl& m = *mImpl;
    ClothStats s;
    double sum = 0.0;
    for (size_t c = 0; c < m.constraints.size(); ++c) {
        if (!m.active[c]) continue;
        const cloth::Constraint& k = m.constraints[c];
        const float len = glm::length(m.particles[size_t(k.b)].x - m.particles[size_t(k.a)].x);
        const float strain = std::abs(len - k.rest) / k.rest;
        sum += strain;
        s.maxStrain = std::max(s.maxStrain, strain);
        ++s.activeConstraints;
    }
    s.meanStrain = s.activeConstraints ? float(sum / s.activeConstraints) : 0.0f;
    return s;
}

void Cloth::constraints(std::vector<int>& a, std::vector<int>& b, std::vector<float>& rest,
                        std::vector<uint8_t>& family, std::vector<uint8_t>& active) const {
    const Impl& m = *mImpl;
    a.clear();
    b.clear();
    rest.clear();
    for (const cloth::Constraint& c : m.constraints) {
        a.push_back(c.a);
        b.push_back(c.b);
        rest.push_back(c.rest);
    }
    family = m.family;
    active = m.active;
}

double Cloth::kineticEnergy() const {
    const Impl& m = *mImpl;
    double e = 0.0;
    const double mass = double(m.params.mass) / m.n;
    for (int k = 0; k < m.n; ++k) {
        if (m.hole[size_t(k)]) continue;
        const glm::vec3 v = (m.particles[size_t(k)].x - m.previous[size_t(k)].x) / m.lastH;
        e += 0.5 * mass * double(glm::dot(v, v));
    }
    return e;
}

bool Cloth::sleeping() const { return mImpl->asleep; }

void Cloth::wake() {
    mImpl->asleep = false;
    mImpl->quietSteps = 0;
}

uint64_t Cloth::stepCount() const { return mImpl->steps; }
uint64_t Cloth::meshVersion() const { return mImpl->meshVersion; }

} // namespace weft
