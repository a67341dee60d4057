#pragma once
// The inner loops of the cloth solver. The distance-constraint projection (eq. 3.3/3.4, XPBD
// when alphaTilde > 0) over constraints
// that share no particle (one batch, or part of one): constraint q joins particles a[q] and
// a[q] + delta. The SIMD versions project 4 (SSE) or 8 (AVX) constraints at once with the same
// float operations in the same order as the scalar one, so all give bit-identical positions
// (the tests check this); the fastest the CPU supports is picked at run time. Tethers likewise,
// 4 or 8 particles at a time, and the Verlet integration.
#include <cstdint>

#include <glm/glm.hpp>

namespace weft::cloth {

/// A particle record: position and inverse mass, 16 bytes (one SIMD register).
struct alignas(16) Particle {
    glm::vec3 x;
    float w;
};

/// What a projection needs besides the particles.
struct BatchJob {
    const int* a;         // particle a of each constraint
    int count;            // constraints
    int delta;            // particle b = particle a + delta
    const float* rest;    // rest lengths
    const uint8_t* on;    // 0 = broken or touching a hole: skipped
    float* lambda;        // XPBD multipliers (read and written only when alphaTilde > 0)
    float alphaTilde;     // compliance / h^2
    glm::vec3 restOffset; // rest offset b - a (the same in a batch): direction for coincident ends
};

/// Tethers of particles [begin, end): slot s of particle k is anchor[s * n + k] at most
/// length[s * n + k] away (+inf: no tether in that slot). Anchors have inverse mass 0.
struct TetherJob {
    int begin, end;
    int slots, n;
    const int* anchor;
    const float* length;
};

/// Position Verlet with damping (eq. 3.12) for particles [begin, end), acceleration gravity
/// plus wind s (n . r) n (eq. 3.5) when normals are given. Particles of inverse mass 0 stay:
/// pinned ones lose their velocity, grabbed ones (and holes) keep their previous position.
struct IntegrateJob {
    int begin, end;
    const uint8_t* pinned;
    const uint8_t* hole;
    glm::vec3 gravity;
    float h, damping;
    const glm::vec4* normals; // nullptr: no wind
    glm::vec3 windDirection;  // unit
    float windStrength;
};

enum class Isa { Scalar, Sse, Avx };

/// Positions and inverse masses as a structure of arrays (the relaxation's layout when the CPU
/// has AVX-512). The grid's columns are split into m = 2 k classes by i mod m (k: the bend
/// distance), each stored segment-major: column i of row j is slot
/// (i mod m) * ny * L + j * L + i / m, with L = ceil(nx / m). Every batch offset (dx in
/// {0, 1, k}) then maps the particles a of one class onto those b of one class at a fixed slot
/// distance, and a class holds only a's of a batch (dx > 0) or whole rows of alternating
/// colour (dx = 0): a batch is a few long contiguous runs of slots across rows, whose vectors
/// stay full even for narrow grids. Unused slots have w = 0. Each array holds at least kSoaPad
/// floats after the last slot.
struct SoaParticles {
    float* x;
    float* y;
    float* z;
    float* w;
};
constexpr int kSoaPad = 80;

/// One class of a batch: particles a at offset + j * L + t (t < L), b = a + delta.
struct DenseSegment {
    int offset, delta;
};

/// One batch, rows [rowBegin, rowEnd) of particle a, in the SoA layout: rest[a] is the rest
/// length of the active constraint of the batch whose first particle is slot a, or -1 where
/// there is none. A vector of 16 slots projects the constraints starting there at once (no two
/// share a particle) and reads and writes only their particles, so rows may be split between
/// threads. With colourRows > 0 (dx = 0) only rows j with (j / colourRows) % 2 == parity hold
/// constraints; they are visited row by row when a row fills a vector, else masked.
struct DenseBatchJob {
    int rowBegin, rowEnd;
    int length; // L: slots per row of a class
    const DenseSegment* segments;
    int segmentCount;
    int colourRows, parity;
    const float* rest;
    float* lambda; // same layout; read and written only when alphaTilde > 0
    float alphaTilde;
    glm::vec3 restOffset; // rest offset b - a: direction for coincident ends
};

/// integrate() whose new positions (and inverse masses) go to the SoA slots slot[k] instead of
/// the records; previous is updated as there. The same float operations as integrate().
void integrateToSoa(const Particle* particles, Particle* previous, const IntegrateJob& job,
                    const SoaParticles& soa, const int* slot);

/// The SoA slots of a grid (see SoaParticles): m classes of ny * L slots.
struct SoaGrid {
    int nx, ny, m, L;
};
/// integrateToSoa over the rows [job.begin, job.end) of the grid (job.begin and job.end are
/// rows here), 16 columns at a time with AVX-512 where m divides 16 and there is no wind.
void integrateRowsToSoa(const Particle* particles, Particle* previous, const IntegrateJob& job,
                        const SoaParticles& soa, const SoaGrid& grid, const int* slot);
/// Copies the positions of rows [rowBegin, rowEnd) from the SoA slots back to the records.
void soaRowsToRecords(const SoaParticles& soa, Particle* particles, int rowBegin, int rowEnd,
                      const SoaGrid& grid, const int* slot);

/// Whether this build and CPU have the AVX-512 kernels of the structure-of-arrays layout.
bool hasSoaKernels();
/// The same float operations as projectBatch, per constraint, on the SoA layout (AVX-512).
void projectDense(const SoaParticles& p, const DenseBatchJob& job);
/// Tethers on the SoA layout: TetherJob over slots, where with table != nullptr anchor[t] is
/// an index into table[0 .. tableSize), tableSize <= 16 (the anchors' slots: their positions
/// are then read once per call and picked from a register instead of gathered).
struct SoaTetherJob {
    TetherJob tethers;
    const int* table;
    int tableSize;
};
constexpr int kTetherTable = 16;
/// projectTethers on the SoA layout (AVX-512).
void projectTethersSoa(const SoaParticles& p, const SoaTetherJob& job);

/// The widest instruction set this build and this CPU support.
Isa bestIsa();
/// Projects the job's constraints with the given instruction set (at most bestIsa()).
void projectBatch(Particle* particles, const BatchJob& job, Isa isa);
/// Pulls each free particle back within its tethers' lengths, slot by slot.
void projectTethers(Particle* particles, const TetherJob& job, Isa isa);
/// x_prev holds the previous positions (its w is unused); SSE or AVX use one SSE register per
/// particle record.
void integrate(Particle* particles, Particle* previous, const IntegrateJob& job, Isa isa);

// Shared by the record (ClothKernels.cpp) and SoA (ClothKernelsSoa.cpp) kernels.

/// Coincident particles have no direction: they are separated along their rest offset, so a
/// collapsed cloth unfolds instead of staying stuck.
constexpr float kCoincident2 = 1e-24f;
constexpr float kUnfold = 1e-6f;

/// The Verlet step's acceleration term of particle k times h^2 (gravity, plus wind when Windy).
template <bool Windy> inline glm::vec3 acceleration(const IntegrateJob& job, int k) {
    glm::vec3 a = job.gravity;
    if (Windy) {
        const glm::vec3 nn(job.normals[k]);
        a += job.windStrength * glm::dot(nn, job.windDirection) * nn;
    }
    return a * (job.h * job.h);
}

} // namespace weft::cloth
