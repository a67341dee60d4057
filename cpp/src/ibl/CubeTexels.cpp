// Flat texel arrays and reduced copies of cube maps.
#include "CubeTexels.h"

#include <algorithm>
#include <cmath>

namespace weft {

CubeTexels cubeTexels(const CubeMap& cube) {
    const int s = cube.size();
    CubeTexels t;
    const size_t n = size_t(6) * s * s;
    for (auto* v : {&t.x, &t.y, &t.z, &t.dw, &t.r, &t.g, &t.b}) v->resize(n);
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < s; ++j)
            for (int i = 0; i < s; ++i) {
                const size_t k = (size_t(f) * s + j) * s + i;
                const glm::vec3 d = cubeTexelDirection(f, i, j, s);
                const float w = float(cubeTexelSolidAngle(i, j, s));
                const float* c = cube.texel(f, i, j);
                t.x[k] = d.x;
                t.y[k] = d.y;
                t.z[k] = d.z;
                t.dw[k] = w;
                t.r[k] = c[0] * w;
                t.g[k] = c[1] * w;
                t.b[k] = c[2] * w;
            }
    return t;
}

CubeMap withMips(const CubeMap& cube) {
    CubeMap out(cube.size());
    std::copy(cube.data(), cube.data() + cube.floatCount(), out.data());
    out.buildMips();
    return out;
}

CubeMap reducedCube(const CubeMap& cube, int maxSize) {
    if (cube.size() <= maxSize) {
        CubeMap out(cube.size());
        std::copy(cube.data(), cube.data() + cube.floatCount(), out.data());
        return out;
    }
    const CubeMap chain = withMips(cube);
    int level = 0;
    while (chain.levelSize(level) > maxSize) ++level;
    CubeMap out(chain.levelSize(level));
    std::copy(chain.data(level), chain.data(level) + chain.floatCount(level), out.data());
    return out;
}

void tangentFrame(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
    const glm::vec3 up = std::fabs(n.y) < 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    t = glm::normalize(glm::cross(up, n));
    b = glm::cross(n, t);
}

} // namespace weft
