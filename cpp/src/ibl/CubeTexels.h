#pragma once
// Helpers for brute-force integrals over a cube map: its texels as flat arrays (directions,
// solid angles, radiance x solid angle) and a copy reduced to a maximum size.
#include <vector>

#include <weft/CubeMap.h>

namespace weft {

struct CubeTexels {
    std::vector<float> x, y, z; // unit directions of the texel centres
    std::vector<float> dw;      // exact solid angles
    std::vector<float> r, g, b; // radiance x solid angle
    size_t size() const { return x.size(); }
};

/// Every texel of level 0 of `cube`.
CubeTexels cubeTexels(const CubeMap& cube);
/// `cube` itself when its size is <= maxSize, else its first mip level that is (one level).
CubeMap reducedCube(const CubeMap& cube, int maxSize);
/// A copy of `cube` with its full mip chain.
CubeMap withMips(const CubeMap& cube);
/// Orthonormal tangent frame (t, b) around unit n.
void tangentFrame(const glm::vec3& n, glm::vec3& t, glm::vec3& b);

} // namespace weft
