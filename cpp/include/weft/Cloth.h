#pragma once
// Position-based cloth (SPEC §2): a grid of particles linked by distance constraints, Position
// Verlet with damping, gravity and wind, collisions by projection, grabbing, holes; beyond the
// seed: XPBD compliance per constraint family, substeps, long-range tethers, self-collision,
// tearing, sleeping, and a graph-coloured parallel Gauss-Seidel solver that gives the same
// result for any thread count.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <weft/DeformableMesh.h>
#include <weft/Error.h>

namespace weft {

/// Constraint families of the 12(+4)-neighbour pattern (seed fig. 3.4 / 3.8).
enum class ConstraintFamily : uint8_t { Stretch = 0, Shear = 1, Bend = 2 };

/// The physical ranges ClothParams::validate, Wind and Collider accept (SI units). Outside them
/// float32 positions, inverse masses or accelerations lose the precision the solver needs (or
/// overflow), so values there are rejected with InvalidArgument instead of turning into NaN.
namespace cloth_limits {
constexpr float kMinSize = 1e-3f, kMaxSize = 1e3f; // cloth side (m)
constexpr float kMaxCoordinate = 1e7f;             // |origin|, collider, grab, ray (m)
constexpr float kMinMass = 1e-6f, kMaxMass = 1e6f; // total mass (kg)
constexpr float kMaxAcceleration = 1e4f;           // |gravity|, |wind strength| (m/s^2)
constexpr float kMaxCompliance = 1e6f;             // XPBD compliance (m/N)
constexpr float kMaxThickness = 1.0f;              // collider / self thickness (m)
constexpr float kMaxTearStrain = 100.0f;
constexpr float kMaxSleepSpeed = 100.0f; // sleep threshold (m/s)
/// advance(): at most this many steps per call (its max_steps); backlog beyond is dropped.
constexpr int kMaxCatchUpSteps = 1000;
} // namespace cloth_limits

struct ClothParams {
    int nx = 32, ny = 32;       // particles along u and v
    glm::vec2 size{1.0f, 1.0f}; // metres along u and v
    // The solver works in a frame centred on origin (positions relative to it, rest lengths
    // in double), so a cloth far from the world origin behaves like one near it.
    glm::vec3 origin{-0.5f, 1.0f, -0.5f}; // position of particle (0, 0)
    glm::vec3 axisU{1.0f, 0.0f, 0.0f};    // grid direction of i (unit)
    glm::vec3 axisV{0.0f, 0.0f, 1.0f};    // grid direction of j (unit)
    float mass = 1.0f;                    // total kg, spread evenly over the particles
    int bendDistance = 2;                 // k: outer diagonal (bend) neighbours at grid distance k
    bool extraAxial = false;              // also 4 axis-aligned neighbours at distance k
    float damping = 0.99f;                // Verlet velocity factor per 1/60 s (1 = none)
    glm::vec3 gravity{0.0f, -9.81f, 0.0f};
    int iterations = 1;             // relaxation sweeps per substep
    int substeps = 1;               // sub-steps per step ("small steps")
    float complianceStretch = 0.0f; // XPBD compliance (m/N); 0 = inextensible (the seed)
    float complianceShear = 0.0f;
    float complianceBend = 0.0f;
    bool tethers = false;     // long-range attachments to pinned particles
    float thickness = 0.005f; // collision distance to colliders (m)
    bool selfCollision = false;
    float selfThickness = 0.0f; // particle-particle distance; 0 = 0.9 x grid spacing
    // Tearing: a face (grid triangle) tears when it is stretched beyond 1 + tearStrain (crack
    // tips first); a constraint lives while the faces it runs through do. 0 = never.
    float tearStrain = 0.0f;
    float sleepThreshold = 0.0f; // sleep below this mean speed (m/s); 0 = never sleep
    int sleepSteps = 30;         // ... for this many consecutive steps
    int threads = 0;             // at most this many of the engine pool's threads; 0 = all

    /// Throws InvalidArgument for impossible values (sizes, NaN, counts, axes) and values
    /// outside the ranges of cloth_limits.
    void validate() const;
};

struct Wind {
    glm::vec3 direction{1.0f, 0.0f, 0.0f}; // r, normalised on use
    float strength = 0.0f;                 // s: acceleration per particle w_i = s (n.r) n (eq. 3.5)

    /// Direction finite and non-zero, |strength| <= cloth_limits::kMaxAcceleration.
    void validate() const;
    bool operator==(const Wind& o) const {
        return direction == o.direction && strength == o.strength;
    }
};

/// A collider the cloth is projected out of (SPEC §2.2). Kinds and their fields:
/// Sphere (center, radius), Plane (center = point, normal), Box (center, halfExtents, rotation),
/// Capsule (center = a, end = b, radius), HeightField (heights over a rows x cols grid spanning
/// [origin.x, origin.x + size.x] x [origin.z, origin.z + size.y] at height origin.y + h).
struct Collider {
    enum class Kind : uint8_t { Sphere, Plane, Box, Capsule, HeightField };
    Kind kind = Kind::Sphere;
    glm::vec3 center{0.0f};
    float radius = 0.5f;
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    glm::vec3 halfExtents{0.5f};
    glm::mat3 rotation{1.0f};
    glm::vec3 end{0.0f, 1.0f, 0.0f};
    int rows = 0, cols = 0;
    std::vector<float> heights; // rows * cols, row-major, rows along z
    glm::vec3 origin{0.0f};
    glm::vec2 size{1.0f};
    float friction = 0.0f; // 0..1: fraction of tangential motion removed on contact

    void validate() const;
    /// Signed distance from p to the surface (negative inside) and the outward normal there.
    float distance(const glm::vec3& p, glm::vec3& normalOut) const;
};

struct ClothMesh {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec4> tangents; // xyz along +u, w = handedness of the bitangent (+v)
    std::vector<uint32_t> indices;   // triangles whose three edges are intact (see tearing)
};

struct ClothStats {
    // |len - rest| / rest over active constraints; NaN when any position is not finite
    float meanStrain = 0.0f, maxStrain = 0.0f;
    int activeConstraints = 0;
};

class Cloth : public DeformableMesh {
public:
    /// Whether this CPU runs the structure-of-arrays relaxation (AVX-512; cloths without
    /// colliders, unless WEFT_CLOTH_AOS=1). Results are bit-identical either way.
    static bool soaKernelsAvailable();

    explicit Cloth(const ClothParams& params = {});
    ~Cloth();
    Cloth(Cloth&&) noexcept;
    Cloth& operator=(Cloth&&) noexcept;

    ClothParams params() const; // a copy, taken under the lock
    /// Changes solver parameters (iterations, substeps, compliance, damping, gravity, wind-free
    /// settings...). Grid size, size, origin, axes, mass and neighbour pattern need a new Cloth.
    void setParams(const ClothParams& params);

    int particleCount() const;
    int constraintCount() const; // including broken ones
    /// Particle positions as x, y, z, inverse mass (16-byte records, index j * nx + i).
    const float* particleData() const;
    /// Particle normals as x, y, z, 0 records of the positions after the last step (computed
    /// on the first read after a step; not safe to call concurrently with other calls).
    const float* normalData() const;

    /// Advances one fixed step of dt seconds (split into substeps). Sleeping cloth does nothing.
    /// Every call on one Cloth is serialised by a lock (calls from several threads wait for
    /// each other); the views of particleData/normalData are not, read them between steps.
    /// Throws weft::Error if the state became non-finite (it cannot from accepted input).
    void step(float dt);
    /// Runs as many fixed steps of 1/rate seconds as real time needs (leftover time is kept),
    /// at most maxSteps in [1, cloth_limits::kMaxCatchUpSteps] (the rest of the backlog is
    /// dropped). realDt must be finite and >= 0 (any size: the count never overflows).
    /// Returns the number of steps run.
    int advance(float realDt, float rate = 60.0f, int maxSteps = 8);
    /// One constraint relaxation sweep (and collisions) without integration; XPBD multipliers
    /// start from zero, so with compliance 0 it is exactly eq. 3.3/3.4.
    void projectConstraints();

    void setPositions(const std::vector<glm::vec3>& positions, bool keepVelocity = false);
    /// Sets velocities consistently with Verlet (x_prev = x - v h + g h^2 / 2 per substep h).
    void setVelocities(const std::vector<glm::vec3>& velocities);
    std::vector<glm::vec3> velocities() const;
    void reset();

    void pin(const std::vector<int>& particles);
    void unpin(const std::vector<int>& particles);
    /// Grabs particles: they get inverse mass 0 and follow `targets` exactly until release().
    void grab(const std::vector<int>& particles, const std::vector<glm::vec3>& targets);
    void moveGrab(const std::vector<glm::vec3>& targets);
    void release();
    /// Index of the particle nearest to the ray (origin, direction) within maxDistance, or -1.
    int pick(const glm::vec3& origin, const glm::vec3& direction, float maxDistance) const;

    /// Removes particles where mask is true (ny * nx, row-major) and their constraints.
    void setHoles(const std::vector<uint8_t>& mask);
    bool isHole(int particle) const;

    void setWind(const Wind& wind);
    Wind wind() const; // a copy: change it with setWind
    int addCollider(const Collider& collider);
    void setCollider(int id, const Collider& collider);
    void clearColliders();
    int colliderCount() const;

    ClothStats stats() const;
    /// Relative strain of every constraint (0 for broken ones), and the constraint ends/family.
    void constraints(std::vector<int>& a, std::vector<int>& b, std::vector<float>& rest,
                     std::vector<uint8_t>& family, std::vector<uint8_t>& active) const;
    double kineticEnergy() const;
    bool sleeping() const;
    void wake();
    uint64_t stepCount() const;
    /// Changes whenever the renderable surface may have changed (a step that ran, new
    /// positions, holes, tears, reset); a renderer re-uploads the mesh only then.
    uint64_t meshVersion() const override;

    ClothMesh mesh() const;
    /// mesh() without the tangents, as the renderer draws it.
    Mesh surface() const override;
    /// Bounds of the particles that are not holes.
    void surfaceBounds(glm::vec3& lo, glm::vec3& hi) const override;

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

} // namespace weft
