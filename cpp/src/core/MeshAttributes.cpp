// Vertex attributes computed for meshes that arrive without them (weft.Mesh without normals or
// UVs): angle-weighted normals and a planar UV projection.
#include <weft/Error.h>
#include <weft/Mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace weft {

std::vector<glm::vec3> computeNormals(const std::vector<glm::vec3>& positions,
                                      const std::vector<uint32_t>& indices) {
    if (indices.size() % 3 != 0)
        throw InvalidArgument("mesh indices: count " + std::to_string(indices.size()) +
                              " is not a multiple of 3");
    // Doubles: a large, finely tessellated mesh sums many small contributions per vertex.
    // Each corner adds the unit face normal times its interior angle (Thürmer & Wüthrich 1998),
    // so the result does not change when a face is split into more triangles, unlike area or
    // uniform weights; trimesh weights the same way.
    std::vector<glm::dvec3> sums(positions.size(), glm::dvec3(0.0));
    for (size_t i = 0; i < indices.size(); i += 3) {
        const uint32_t corner[3] = {indices[i], indices[i + 1], indices[i + 2]};
        for (uint32_t v : corner)
            if (v >= positions.size())
                throw InvalidArgument("mesh indices: triangle " + std::to_string(i / 3) +
                                      " refers to a vertex out of range");
        const glm::dvec3 p[3] = {glm::dvec3(positions[corner[0]]), glm::dvec3(positions[corner[1]]),
                                 glm::dvec3(positions[corner[2]])};
        const glm::dvec3 cross = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double twiceArea = glm::length(cross);
        if (!(twiceArea > 0.0) || !std::isfinite(twiceArea)) continue; // degenerate: no direction
        const glm::dvec3 faceNormal = cross / twiceArea;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 e1 = p[(k + 1) % 3] - p[k], e2 = p[(k + 2) % 3] - p[k];
            // atan2(|e1 x e2|, e1.e2) is accurate for angles near 0 and pi, unlike acos.
            const double angle = std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
            sums[corner[k]] += angle * faceNormal;
        }
    }
    std::vector<glm::vec3> normals(positions.size());
    for (size_t i = 0; i < sums.size(); ++i) {
        const double length = glm::length(sums[i]);
        normals[i] = length > 0.0 && std::isfinite(length) ? glm::vec3(sums[i] / length)
                                                           : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    return normals;
}

std::vector<glm::vec2> computePlanarUvs(const std::vector<glm::vec3>& positions) {
    if (positions.empty()) throw InvalidArgument("mesh: no positions to project UVs from");
    glm::vec3 lo(positions[0]), hi(positions[0]);
    for (const glm::vec3& p : positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::vec3 extent = hi - lo;
    // Axes by decreasing extent; ties keep X before Z before Y so that a flat XZ patch maps
    // like Mesh::plane (u along +X, v along +Z).
    std::array<int, 3> axes = {0, 2, 1};
    std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return extent[a] > extent[b]; });
    const int uAxis = axes[0], vAxis = axes[1];
    const float scale = extent[uAxis] > 0.0f ? 1.0f / extent[uAxis] : 1.0f;
    std::vector<glm::vec2> uvs(positions.size());
    for (size_t i = 0; i < positions.size(); ++i)
        uvs[i] = glm::vec2((positions[i][uAxis] - lo[uAxis]) * scale,
                           (positions[i][vAxis] - lo[vAxis]) * scale);
    return uvs;
}

} // namespace weft
