// The renderable surface of a cloth: per-particle normals, UVs and tangents, and the triangles
// whose edges are all intact (holes and tears leave gaps).
#include <cmath>

#include "sim/cloth/ClothImpl.h"

namespace weft {

Mesh Cloth::surface() const {
    ClothMesh cm = mesh();
    Mesh out;
    out.positions = std::move(cm.positions);
    out.normals = std::move(cm.normals);
    out.uvs = std::move(cm.uvs);
    out.indices = std::move(cm.indices);
    return out;
}

void Cloth::surfaceBounds(glm::vec3& lo, glm::vec3& hi) const {
    lo = glm::vec3(1e30f);
    hi = glm::vec3(-1e30f);
    const float* p = particleData(); // x, y, z, w records
    for (int k = 0; k < particleCount(); ++k) {
        if (isHole(k)) continue;
        const glm::vec3 x(p[4 * k], p[4 * k + 1], p[4 * k + 2]);
        lo = glm::min(lo, x);
        hi = glm::max(hi, x);
    }
}

ClothMesh Cloth::mesh() const {
    const Impl& m = *mImpl;
    std::lock_guard<std::recursive_mutex> lock(m.lock);
    const std::vector<glm::vec4>& normals = m.currentNormals();
    const int nx = m.params.nx, ny = m.params.ny;
    ClothMesh out;
    out.positions.resize(size_t(m.n));
    out.normals.resize(size_t(m.n));
    out.uvs.resize(size_t(m.n));
    out.tangents.resize(size_t(m.n));
    auto at = [&](int i, int j) { return m.particles[size_t(j * nx + i)].x; };
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const int k = j * nx + i;
            const glm::vec3 nrm(normals[size_t(k)]);
            out.positions[size_t(k)] = m.frame == glm::dvec3(0.0) ? at(i, j) : m.world[size_t(k)].x;
            out.normals[size_t(k)] = nrm;
            out.uvs[size_t(k)] = glm::vec2(nx > 1 ? float(i) / float(nx - 1) : 0.0f,
                                           ny > 1 ? float(j) / float(ny - 1) : 0.0f);
            // Tangent along +u (dP/du), orthogonalised against the normal; w = handedness.
            const glm::vec3 du = at(std::min(i + 1, nx - 1), j) - at(std::max(i - 1, 0), j);
            const glm::vec3 dv = at(i, std::min(j + 1, ny - 1)) - at(i, std::max(j - 1, 0));
            glm::vec3 t = du - nrm * glm::dot(nrm, du);
            if (glm::length(t) < 1e-12f)
                t = glm::normalize(glm::cross(nrm, glm::vec3(0, 0, 1)) + glm::vec3(1e-6f, 0, 0));
            t = glm::normalize(t);
            const float w = glm::dot(glm::cross(nrm, t), dv) < 0.0f ? -1.0f : 1.0f;
            out.tangents[size_t(k)] = glm::vec4(t, w);
        }
    }
    // Edge activity by particle pair: the stretch (1,0), (0,1) and shear (1,1) constraints.
    std::vector<uint8_t> right(size_t(m.n), 0), down(size_t(m.n), 0), diag(size_t(m.n), 0);
    for (size_t c = 0; c < m.constraints.size(); ++c) {
        if (!m.active[c]) continue;
        const int a = m.constraints[c].a, b = m.constraints[c].b;
        if (b == a + 1)
            right[size_t(a)] = 1;
        else if (b == a + nx)
            down[size_t(a)] = 1;
        else if (b == a + nx + 1)
            diag[size_t(a)] = 1;
    }
    for (int j = 0; j + 1 < ny; ++j) {
        for (int i = 0; i + 1 < nx; ++i) {
            const uint32_t p00 = uint32_t(j * nx + i), p10 = p00 + 1, p01 = p00 + uint32_t(nx),
                           p11 = p01 + 1;
            if (diag[p00] && right[p00] && down[p10])
                out.indices.insert(out.indices.end(), {p00, p11, p10});
            if (diag[p00] && down[p00] && right[p01])
                out.indices.insert(out.indices.end(), {p00, p01, p11});
        }
    }
    return out;
}

} // namespace weft
