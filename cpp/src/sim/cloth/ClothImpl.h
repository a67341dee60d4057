#pragma once
// Private state of weft::Cloth, shared by the files of the solver.
#include <memory>
#include <mutex>
#include <vector>

#include <weft/Cloth.h>

#include "core/ThreadPool.h"
#include "sim/cloth/ClothKernels.h"

namespace weft::cloth {

constexpr int kSelfCollisionPasses = 3;

struct Constraint {
    int a, b;
    float rest;
};

/// Constraints that share no particle: projected in any order, or in parallel. They are all of
/// one grid offset (dx >= 0, dy) and one colour, so particle b is particle a + dy * nx + dx.
struct Batch {
    ConstraintFamily family;
    int begin, end; // range in the constraint arrays
    int dx, dy;
    int rowBegin = 0, rowEnd = 0, parity = 0; // rows of particle a, colour (the SoA path)
    int segmentsBegin = 0, segmentsEnd = 0;   // its segments in batchSegments
};

} // namespace weft::cloth

namespace weft {

struct Cloth::Impl {
    ClothParams params;
    int n = 0;
    // Serialises every public call: the pool and the state admit one stepper at a time.
    mutable std::recursive_mutex lock;

    // The solver's frame: positions are stored relative to frame (the cloth's origin when
    // that is far from the world origin, else 0), so float32 keeps its precision for a cloth
    // far away. With a frame, world holds the published world-space records (particleData),
    // refreshed by publish(); without one the records are published as they are.
    glm::dvec3 frame{0.0};
    std::vector<cloth::Particle> world;
    glm::vec3 toLocal(const glm::vec3& p) const { return glm::vec3(glm::dvec3(p) - frame); }
    glm::vec3 toWorld(const glm::vec3& p) const { return glm::vec3(glm::dvec3(p) + frame); }
    /// Copies the particles to world; returns whether all of them are finite.
    bool publish();

    std::vector<cloth::Particle> particles; // current positions + inverse mass (local frame)
    std::vector<cloth::Particle> previous;  // x_prev of Verlet (w unused)
    std::vector<glm::vec3> rest;            // initial positions
    std::vector<float> baseInvMass;         // inverse mass without pins/grabs
    std::vector<uint8_t> pinned, hole;
    // Normals are needed by wind (computed at the start of each substep) and by readers
    // (normalData, mesh); after a step they are computed on first read, not every step.
    mutable std::vector<glm::vec4> normals;
    mutable bool normalsStale = false;
    std::vector<glm::vec3> pendingVelocity;
    bool hasPendingVelocity = false;

    std::vector<cloth::Constraint> constraints; // ordered by batch
    std::vector<int> endA;                      // constraints[c].a, contiguous
    std::vector<float> restLength;              // constraints[c].rest, contiguous
    std::vector<uint8_t> family, active;
    // Tearing (ClothTearing.cpp): the grid's triangles, 2 per quad; a constraint is active
    // while no end is a hole and (once anything tore) the faces it runs through are alive.
    std::vector<uint8_t> faceAlive;
    std::vector<float> faceStretch; // scratch of tearFaces
    bool torn = false, anyHole = false;
    std::vector<float> lambda;
    std::vector<cloth::Batch> batches;
    // The structure-of-arrays path of the relaxation (CPUs with AVX-512, no colliders,
    // WEFT_CLOTH_AOS unset): the integration writes the new positions into soa (x, y, z, w
    // arrays of soaStride floats, slots as in cloth::SoaParticles: soaSlot[k] is particle
    // k's), the sweeps run there, and fromSoa copies them back to the records. denseRest[b *
    // soaSlots + a]: rest length of batch b's active constraint starting at slot a, -1 where none
    // does (denseLambda likewise); tethers by slot likewise. denseStale after constraints, inverse
    // masses or tethers change.
    bool useSoa = false;
    int soaSegment = 0, soaSlots = 0; // L, m * ny * L
    size_t soaStride = 0;
    std::vector<int> soaSlot;
    std::vector<float> soa;
    std::vector<float> denseRest, denseLambda;
    std::vector<cloth::DenseSegment> batchSegments;
    std::vector<int> tetherAnchorSoa; // into tetherTable when that is not empty
    std::vector<int> tetherTable;     // the anchors' slots, when at most kTetherTable
    std::vector<float> tetherLengthSoa;
    bool denseStale = true;
    // Long-range attachments |x_k - x_anchor| <= length (the rest distance), one-sided, stored
    // by slot: slot s of particle k at [s * n + k] (length +inf where k has fewer tethers).
    int tetherSlots = 0;
    std::vector<int> tetherAnchor;
    std::vector<float> tetherLength;

    std::vector<int> grabbed;
    std::vector<glm::vec3> grabTargets; // local frame
    std::vector<glm::vec3> grabWorld;   // as given
    Wind wind;
    std::vector<Collider> colliders;      // as given (world space)
    std::vector<Collider> localColliders; // the same in the local frame (used by collide)

    double accumulator = 0.0;
    uint64_t steps = 0;
    uint64_t meshVersion = 1;
    int quietSteps = 0;
    bool asleep = false;
    float lastH = 1.0f / 60.0f;
    std::unique_ptr<PoolShare> pool; // this cloth's share of the engine pool
    cloth::Isa isa = cloth::bestIsa();

    void build();                         // grid, constraints, batches (ClothSetup.cpp)
    void rebuildTethers();                // (ClothSetup.cpp)
    void applyInverseMasses();            // base, pins, grabs, holes
    void substep(float h, float damping); // (ClothSolver.cpp)
    void relax(float h);                  // one sweep: batches, tethers, colliders
    void projectBatch(const cloth::Batch& batch, float alphaTilde);
    cloth::SoaParticles soaParticles() {
        float* base = soa.data();
        return {base, base + soaStride, base + 2 * soaStride, base + 3 * soaStride};
    }
    void syncDense(); // dense arrays, w and tethers of the SoA path
    void fromSoa();
    void relaxSoa(float h);
    int soaSplit() const; // minParallel of the SoA passes over rows: all or none
    /// Projects particles [begin, end) out of the colliders; friction only in the relaxation
    /// (the re-projection after self-collision must not brake the cloth a second time).
    void collide(int begin, int end, bool friction);
    // Self-collision (ClothSelfCollision.cpp) keeps each close pair on the side of each other's
    // layer it was on at the start of the substep: the start positions and their normals.
    // Each pass moves a particle by the mean of its pairs' corrections, which resolves one
    // deep contact among shallow ones only partly: a few passes per substep.
    std::vector<glm::vec3> selfStart, selfStartNormal;
    std::vector<int> candidates, candidateCount; // pairs of the substep, per particle
    void rememberSelfStart();
    void selfCollide();
    void computeNormals() const;
    const std::vector<glm::vec4>& currentNormals() const {
        if (normalsStale) computeNormals();
        return normals;
    }
    void afterStep(float dt);   // tearing, sleeping
    bool faceOpen(int f) const; // alive and no corner is a hole
    bool quadAny(int i, int j) const;
    bool quadBoth(int i, int j) const;
    bool supported(size_t c) const; // the faces constraint c runs through are alive
    void updateActive();            // active from holes and faces
    bool tearFaces();               // tears overstretched faces; whether any tore
    void tethersAlongCloth(const std::vector<int>& anchors);
};

} // namespace weft
