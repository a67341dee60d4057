#pragma once
// The distance-constraint projection (eq. 3.3/3.4, XPBD when alphaTilde > 0) over one row of a
// batch: constraint q joins particles base[cols[q]] and base[cols[q] + delta]. The SIMD version
// projects four constraints at once with the same float operations in the same order as the
// scalar one, so both give bit-identical positions (the tests check this).
#include <cstdint>

#include <glm/glm.hpp>

namespace weft::cloth {

/// A particle record: position and inverse mass, 16 bytes (one SIMD register).
struct alignas(16) Particle {
    glm::vec3 x;
    float w;
};

/// What one row projection needs besides the particles.
struct RowJob {
    const int* cols;      // column offset of particle a of each constraint within the row
    int count;            // constraints in the row
    int delta;            // particle b = particle a + delta
    const float* rest;    // rest lengths of the row's constraints
    const uint8_t* on;    // 0 = broken or touching a hole: skipped
    float* lambda;        // XPBD multipliers (read and written only when alphaTilde > 0)
    float alphaTilde;     // compliance / h^2
    glm::vec3 restOffset; // rest offset b - a (the same in a batch): direction for coincident ends
};

/// One constraint at a time (the definition; also the tail of the SIMD rows).
void projectRowScalar(Particle* base, const RowJob& job);
/// Four constraints at a time where SSE is available, else the scalar loop; same results.
void projectRow(Particle* base, const RowJob& job);

} // namespace weft::cloth
