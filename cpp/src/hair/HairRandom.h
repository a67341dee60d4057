#pragma once
// The integer hash behind every random choice of the hair generators and the per-strand glint
// angle. glsl/common/hair_shading.glsl and python/weft/reference/hair.py use the same function,
// so CPU, GPU and NumPy draw the same numbers.
#include <cstdint>

#include <glm/glm.hpp>

namespace weft::hair {

inline uint32_t hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

/// Uniform in [0, 1): 24 bits of hash(hash(seed) ^ (index * 8 + channel)).
inline float random01(uint32_t seed, uint32_t index, uint32_t channel) {
    return float(hash32(hash32(seed) ^ (index * 8u + channel)) >> 8) * (1.0f / 16777216.0f);
}

/// Two unit vectors completing `n` (unit) to an orthonormal basis (Duff et al. 2017).
inline void orthonormalBasis(const glm::vec3& n, glm::vec3& b1, glm::vec3& b2) {
    const float sign = n.z >= 0.0f ? 1.0f : -1.0f;
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    b1 = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    b2 = glm::vec3(b, sign + n.y * n.y * a, -n.y);
}

} // namespace weft::hair
