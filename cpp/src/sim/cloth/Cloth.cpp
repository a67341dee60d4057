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

void checkCoordinates(const std::vector<glm::vec3>& v, const char* what) {
    for (const glm::vec3& p : v)
        for (int c = 0; c < 3; ++c)
            if (std::abs(p[c]) > cloth_limits::kMaxCoordinate)
                throw InvalidArgument(std::string(what) + " must be within +-" +
                                      std::to_string(cloth_limits::kMaxCoordinate) + " m");
}

void checkIndices(const std::vector<int>& idx, int n, const char* what) {
    for (int i : idx)
        if (i < 0 || i >= n)
            throw InvalidArgument(std::string(what) + ": particle index " + std::to_string(i) +
                                  " out of range [0, " + std::to_string(n) + ")");
}

} // namespace

using Lock = std::lock_guard<std::recursive_mutex>;

bool Cloth::Impl::publish() {
    if (frame == glm::dvec3(0.0)) return true; // particleData is the records themselves
    world.resize(particles.size());
    bool finite = true;
    for (size_t k = 0; k < particles.size(); ++k) {
        const glm::vec3 x = particles[k].x;
        finite &= std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z);
        world[k] = {toWorld(x), particles[k].w};
    }
    // A grabbed particle that reached its target shows the target exactly (not rounded twice).
    for (size_t q = 0; q < grabbed.size(); ++q)
        if (particles[size_t(grabbed[q])].x == grabTargets[q])
            world[size_t(grabbed[q])].x = grabWorld[q];
    return finite;
}

Cloth::Cloth(const ClothParams& params) : mImpl(std::make_unique<Impl>()) {
    params.validate();
    mImpl->params = params;
    mImpl->pool = std::make_unique<PoolShare>(params.threads);
    mImpl->build();
    mImpl->applyInverseMasses();
    mImpl->publish();
}

Cloth::~Cloth() = default;

bool Cloth::soaKernelsAvailable() { return cloth::hasSoaKernels(); }
Cloth::Cloth(Cloth&&) noexcept = default;
Cloth& Cloth::operator=(Cloth&&) noexcept = default;

ClothParams Cloth::params() const {
    Lock lock(mImpl->lock);
    return mImpl->params;
}

void Cloth::setParams(const ClothParams& p) {
    p.validate();
    Lock lock(mImpl->lock);
    const ClothParams& o = mImpl->params;
    if (p.nx != o.nx || p.ny != o.ny || p.size != o.size || p.origin != o.origin ||
        p.axisU != o.axisU || p.axisV != o.axisV || p.mass != o.mass ||
        p.bendDistance != o.bendDistance || p.extraAxial != o.extraAxial)
        throw InvalidArgument("grid size, dimensions, axes, mass and neighbour pattern are fixed "
                              "when a cloth is made; create a new Cloth to change them");
    const bool tethersChanged = p.tethers != o.tethers;
    const bool threadsChanged = p.threads != o.threads;
    mImpl->params = p;
    if (threadsChanged) mImpl->pool = std::make_unique<PoolShare>(p.threads);
    if (tethersChanged) mImpl->rebuildTethers();
    wake();
}

int Cloth::particleCount() const { return mImpl->n; }
int Cloth::constraintCount() const { return int(mImpl->constraints.size()); }
const float* Cloth::particleData() const {
    const Impl& m = *mImpl;
    return m.frame == glm::dvec3(0.0) ? &m.particles[0].x.x : &m.world[0].x.x;
}
const float* Cloth::normalData() const {
    Lock lock(mImpl->lock);
    return &mImpl->currentNormals()[0].x;
}

void Cloth::step(float dt) {
    if (!(std::isfinite(dt) && dt > 0.0f && dt <= 1.0f))
        throw InvalidArgument("time step must be in (0, 1] seconds (got " + std::to_string(dt) +
                              ")");
    Impl& m = *mImpl;
    Lock lock(m.lock);
    if (m.asleep) return;
    const float h = dt / float(m.params.substeps);
    const float damping = std::pow(m.params.damping, h * 60.0f);
    for (int s = 0; s < m.params.substeps; ++s) m.substep(h, damping);
    m.lastH = h;
    m.normalsStale = true;
    m.afterStep(dt);
    ++m.steps;
    ++m.meshVersion;
    if (!m.publish())
        throw Error("cloth state became non-finite (a bug: accepted input must not do this); "
                    "call reset()");
}

int Cloth::advance(float realDt, float rate, int maxSteps) {
    if (!(std::isfinite(realDt) && realDt >= 0.0f))
        throw InvalidArgument("advance: real_dt must be finite and >= 0");
    if (!(std::isfinite(rate) && rate >= 1.0f && rate <= 10000.0f))
        throw InvalidArgument("advance: rate must be in [1, 10000] Hz");
    if (maxSteps < 1 || maxSteps > cloth_limits::kMaxCatchUpSteps)
        throw InvalidArgument("advance: max_steps must be in [1, " +
                              std::to_string(cloth_limits::kMaxCatchUpSteps) + "]");
    Impl& m = *mImpl;
    Lock lock(m.lock);
    m.accumulator += double(realDt);
    // Compared as doubles before any conversion: a huge backlog cannot overflow the count.
    const double due = std::floor(m.accumulator * double(rate));
    int count;
    if (due > double(maxSteps)) { // too far behind: drop the backlog instead of spiralling
        count = maxSteps;
        m.accumulator = 0.0;
    } else {
        count = int(due);
        m.accumulator = std::max(0.0, m.accumulator - double(count) / rate);
    }
    for (int s = 0; s < count; ++s) step(1.0f / rate);
    return count;
}

void Cloth::projectConstraints() {
    Impl& m = *mImpl;
    Lock lock(m.lock);
    std::fill(m.lambda.begin(), m.lambda.end(), 0.0f);
    m.relax(1.0f / 60.0f);
    ++m.meshVersion;
    if (!m.publish()) throw Error("cloth state became non-finite; call reset()");
}

void Cloth::setPositions(const std::vector<glm::vec3>& positions, bool keepVelocity) {
    Impl& m = *mImpl;
    checkPoints(positions, size_t(m.n), "positions");
    checkCoordinates(positions, "positions");
    Lock lock(m.lock);
    ++m.meshVersion;
    for (int k = 0; k < m.n; ++k) {
        const glm::vec3 v = m.particles[size_t(k)].x - m.previous[size_t(k)].x;
        const glm::vec3 x = m.toLocal(positions[size_t(k)]);
        m.particles[size_t(k)].x = x;
        m.previous[size_t(k)].x = keepVelocity ? x - v : x;
    }
    m.hasPendingVelocity = false;
    m.publish();
    wake();
}

void Cloth::setVelocities(const std::vector<glm::vec3>& velocities) {
    Impl& m = *mImpl;
    checkPoints(velocities, size_t(m.n), "velocities");
    for (const glm::vec3& v : velocities)
        if (glm::length(v) > cloth_limits::kMaxCoordinate)
            throw InvalidArgument("velocities must be below " +
                                  std::to_string(cloth_limits::kMaxCoordinate) + " m/s");
    Lock lock(m.lock);
    m.pendingVelocity = velocities;
    m.hasPendingVelocity = true;
    wake();
}

std::vector<glm::vec3> Cloth::velocities() const {
    const Impl& m = *mImpl;
    Lock lock(m.lock);
    if (m.hasPendingVelocity) return m.pendingVelocity;
    std::vector<glm::vec3> v(size_t(m.n));
    for (int k = 0; k < m.n; ++k)
        v[size_t(k)] = (m.particles[size_t(k)].x - m.previous[size_t(k)].x) / m.lastH;
    return v;
}

void Cloth::reset() {
    Impl& m = *mImpl;
    Lock lock(m.lock);
    for (int k = 0; k < m.n; ++k) {
        m.particles[size_t(k)].x = m.rest[size_t(k)];
        m.previous[size_t(k)].x = m.rest[size_t(k)];
    }
    std::fill(m.faceAlive.begin(), m.faceAlive.end(), uint8_t(1));
    m.torn = false;
    m.grabbed.clear();
    m.grabTargets.clear();
    m.grabWorld.clear();
    m.hasPendingVelocity = false;
    m.accumulator = 0.0;
    ++m.meshVersion;
    m.applyInverseMasses();
    m.publish();
    wake();
}

void Cloth::pin(const std::vector<int>& particles) {
    checkIndices(particles, mImpl->n, "pin");
    Lock lock(mImpl->lock);
    for (int k : particles) mImpl->pinned[size_t(k)] = 1;
    mImpl->applyInverseMasses();
    wake();
}

void Cloth::unpin(const std::vector<int>& particles) {
    checkIndices(particles, mImpl->n, "unpin");
    Lock lock(mImpl->lock);
    for (int k : particles) mImpl->pinned[size_t(k)] = 0;
    mImpl->applyInverseMasses();
    wake();
}

void Cloth::grab(const std::vector<int>& particles, const std::vector<glm::vec3>& targets) {
    checkIndices(particles, mImpl->n, "grab");
    if (particles.empty()) throw InvalidArgument("grab: no particles given");
    checkPoints(targets, particles.size(), "grab targets");
    checkCoordinates(targets, "grab targets");
    Lock lock(mImpl->lock);
    mImpl->grabbed = particles;
    mImpl->grabTargets.clear();
    for (const glm::vec3& t : targets) mImpl->grabTargets.push_back(mImpl->toLocal(t));
    mImpl->grabWorld = targets;
    mImpl->applyInverseMasses();
    wake();
}

void Cloth::moveGrab(const std::vector<glm::vec3>& targets) {
    Lock lock(mImpl->lock);
    if (mImpl->grabbed.empty()) throw InvalidArgument("move_grab: nothing is grabbed");
    checkPoints(targets, mImpl->grabbed.size(), "grab targets");
    checkCoordinates(targets, "grab targets");
    mImpl->grabTargets.clear();
    for (const glm::vec3& t : targets) mImpl->grabTargets.push_back(mImpl->toLocal(t));
    mImpl->grabWorld = targets;
    wake();
}

void Cloth::release() {
    Lock lock(mImpl->lock);
    mImpl->grabbed.clear();
    mImpl->grabTargets.clear();
    mImpl->grabWorld.clear();
    mImpl->applyInverseMasses();
    wake();
}

int Cloth::pick(const glm::vec3& origin, const glm::vec3& direction, float maxDistance) const {
    requireFinite(origin, "ray origin");
    requireFinite(direction, "ray direction");
    if (glm::length(direction) < 1e-12f) throw InvalidArgument("ray direction must not be zero");
    requirePositive(maxDistance, "max_distance");
    checkCoordinates({origin}, "ray origin");
    Lock lock(mImpl->lock);
    const glm::vec3 d = glm::normalize(direction);
    const glm::vec3 from = mImpl->toLocal(origin);
    int best = -1;
    float bestT = std::numeric_limits<float>::max();
    for (int k = 0; k < mImpl->n; ++k) {
        if (mImpl->hole[size_t(k)]) continue;
        const glm::vec3 rel = mImpl->particles[size_t(k)].x - from;
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
    Lock lock(m.lock);
    for (int k = 0; k < m.n; ++k) m.hole[size_t(k)] = mask[size_t(k)] ? 1 : 0;
    ++m.meshVersion;
    // Constraints come back where both ends are cloth again (torn faces stay torn).
    m.applyInverseMasses();
    m.publish();
    wake();
}

bool Cloth::isHole(int particle) const {
    checkIndices({particle}, mImpl->n, "is_hole");
    return mImpl->hole[size_t(particle)] != 0;
}

void Cloth::setWind(const Wind& wind) {
    wind.validate();
    Lock lock(mImpl->lock);
    mImpl->wind = wind;
    wake();
}

Wind Cloth::wind() const {
    Lock lock(mImpl->lock);
    return mImpl->wind;
}

namespace {
// The collider in the cloth's local frame (positions relative to frame, in double).
Collider localCollider(const Collider& c, const glm::dvec3& frame) {
    Collider l = c;
    l.center = glm::vec3(glm::dvec3(c.center) - frame);
    l.end = glm::vec3(glm::dvec3(c.end) - frame);
    l.origin = glm::vec3(glm::dvec3(c.origin) - frame);
    return l;
}
} // namespace

int Cloth::addCollider(const Collider& collider) {
    collider.validate();
    Lock lock(mImpl->lock);
    mImpl->colliders.push_back(collider);
    mImpl->localColliders.push_back(localCollider(collider, mImpl->frame));
    wake();
    return int(mImpl->colliders.size() - 1);
}

void Cloth::setCollider(int id, const Collider& collider) {
    Lock lock(mImpl->lock);
    if (id < 0 || id >= int(mImpl->colliders.size()))
        throw InvalidArgument("collider id " + std::to_string(id) + " does not exist");
    collider.validate();
    mImpl->colliders[size_t(id)] = collider;
    mImpl->localColliders[size_t(id)] = localCollider(collider, mImpl->frame);
    wake();
}

void Cloth::clearColliders() {
    Lock lock(mImpl->lock);
    mImpl->colliders.clear();
    mImpl->localColliders.clear();
    wake();
}

int Cloth::colliderCount() const { return int(mImpl->colliders.size()); }

ClothStats Cloth::stats() const {
    const Impl& m = *mImpl;
    Lock lock(m.lock);
    ClothStats s;
    double sum = 0.0;
    for (size_t c = 0; c < m.constraints.size(); ++c) {
        if (!m.active[c]) continue;
        const cloth::Constraint& k = m.constraints[c];
        const float len = glm::length(m.particles[size_t(k.b)].x - m.particles[size_t(k.a)].x);
        const float strain = std::abs(len - k.rest) / k.rest;
        sum += strain;
        // a NaN strain must show: std::max would drop it
        s.maxStrain = std::isnan(strain) || std::isnan(s.maxStrain) ? std::nanf("")
                                                                    : std::max(s.maxStrain, strain);
        ++s.activeConstraints;
    }
    s.meanStrain = s.activeConstraints ? float(sum / s.activeConstraints) : 0.0f;
    for (int k = 0; k < m.n; ++k) { // a non-finite particle without active constraints too
        const glm::vec3 x = m.particles[size_t(k)].x;
        if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z))) {
            s.meanStrain = s.maxStrain = std::nanf("");
            break;
        }
    }
    return s;
}

void Cloth::constraints(std::vector<int>& a, std::vector<int>& b, std::vector<float>& rest,
                        std::vector<uint8_t>& family, std::vector<uint8_t>& active) const {
    const Impl& m = *mImpl;
    Lock lock(m.lock);
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
    Lock lock(m.lock);
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
    Lock lock(mImpl->lock);
    mImpl->asleep = false;
    mImpl->quietSteps = 0;
}

uint64_t Cloth::stepCount() const { return mImpl->steps; }
uint64_t Cloth::meshVersion() const { return mImpl->meshVersion; }

} // namespace weft
