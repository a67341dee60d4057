// Mesh validation and the built-in shapes.
#include <weft/Error.h>
#include <weft/Mesh.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace weft {

namespace {

// Upper limit of any segment count; 4096 x 4096 quads is already 32M triangles.
constexpr int kMaxSegments = 4096;

bool isFinite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool isFinite(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

void checkSize(const char* shape, const char* name, float value) {
    if (!std::isfinite(value) || value <= 0.0f) {
        throw InvalidArgument(std::string(shape) + ": " + name +
                              " must be positive and finite, got " + std::to_string(value));
    }
}

void checkSegments(const char* shape, const char* name, int value, int minimum) {
    if (value < minimum || value > kMaxSegments) {
        throw InvalidArgument(std::string(shape) + ": " + name + " must be in [" +
                              std::to_string(minimum) + ", " + std::to_string(kMaxSegments) +
                              "], got " + std::to_string(value));
    }
}

} // namespace

void Mesh::validate() const {
    const size_t n = positions.size();
    if (n == 0) throw InvalidArgument("mesh has no vertices");
    if (indices.empty()) throw InvalidArgument("mesh has no triangles");
    if (normals.size() != n || uvs.size() != n) {
        throw InvalidArgument("mesh has " + std::to_string(n) + " positions but " +
                              std::to_string(normals.size()) + " normals and " +
                              std::to_string(uvs.size()) + " uvs");
    }
    if (indices.size() % 3 != 0) {
        throw InvalidArgument("mesh index count " + std::to_string(indices.size()) +
                              " is not a multiple of 3");
    }
    for (size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= n) {
            throw InvalidArgument("mesh index " + std::to_string(i) + " is " +
                                  std::to_string(indices[i]) + ", but there are only " +
                                  std::to_string(n) + " vertices");
        }
    }
    for (size_t i = 0; i < n; ++i) {
        if (!isFinite(positions[i]) || !isFinite(normals[i]) || !isFinite(uvs[i])) {
            throw InvalidArgument("mesh vertex " + std::to_string(i) + " has a non-finite value");
        }
        if (glm::dot(normals[i], normals[i]) < 1e-24f) {
            throw InvalidArgument("mesh vertex " + std::to_string(i) + " has a zero normal");
        }
    }
}

void Mesh::bounds(glm::vec3& lo, glm::vec3& hi) const {
    if (positions.empty()) throw InvalidArgument("bounds of a mesh without vertices");
    lo = hi = positions[0];
    for (const glm::vec3& p : positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
}

Mesh Mesh::plane(float sizeX, float sizeZ, int segmentsX, int segmentsZ) {
    checkSize("plane", "sizeX", sizeX);
    checkSize("plane", "sizeZ", sizeZ);
    checkSegments("plane", "segmentsX", segmentsX, 1);
    checkSegments("plane", "segmentsZ", segmentsZ, 1);

    Mesh mesh;
    const size_t columns = size_t(segmentsX) + 1;
    const size_t vertexCount = columns * (size_t(segmentsZ) + 1);
    mesh.positions.reserve(vertexCount);
    mesh.normals.assign(vertexCount, glm::vec3(0.0f, 1.0f, 0.0f));
    mesh.uvs.reserve(vertexCount);
    for (int j = 0; j <= segmentsZ; ++j) {
        const float v = float(j) / float(segmentsZ);
        for (int i = 0; i <= segmentsX; ++i) {
            const float u = float(i) / float(segmentsX);
            mesh.positions.emplace_back((u - 0.5f) * sizeX, 0.0f, (v - 0.5f) * sizeZ);
            mesh.uvs.emplace_back(u, v);
        }
    }

    // Vertex (i, j) is j * columns + i. Going +Z then +X is counter-clockwise seen from +Y.
    mesh.indices.reserve(size_t(segmentsX) * size_t(segmentsZ) * 6);
    for (int j = 0; j < segmentsZ; ++j) {
        for (int i = 0; i < segmentsX; ++i) {
            const uint32_t a = uint32_t(j * columns + i); // (i, j)
            const uint32_t b = uint32_t(a + columns);     // (i, j + 1)
            const uint32_t c = a + 1;                     // (i + 1, j)
            const uint32_t d = b + 1;                     // (i + 1, j + 1)
            mesh.indices.insert(mesh.indices.end(), {a, b, c, c, b, d});
        }
    }
    return mesh;
}

Mesh Mesh::uvSphere(float radius, int segments, int rings) {
    checkSize("uvSphere", "radius", radius);
    checkSegments("uvSphere", "segments", segments, 3);
    checkSegments("uvSphere", "rings", rings, 2);

    // Ring r is at polar angle pi * r / rings from +Y; column s at azimuth 2 pi * s / segments,
    // starting at +Z and turning towards +X, so that u grows to the right seen from outside
    // and v = 0 is the north pole. Column `segments` repeats column 0 with u = 1 (the seam).
    Mesh mesh;
    const size_t columns = size_t(segments) + 1;
    const size_t vertexCount = columns * (size_t(rings) + 1);
    mesh.positions.reserve(vertexCount);
    mesh.normals.reserve(vertexCount);
    mesh.uvs.reserve(vertexCount);
    const double pi = 3.14159265358979323846;
    for (int r = 0; r <= rings; ++r) {
        const double polar = pi * r / rings;
        const double sinPolar = (r == 0 || r == rings) ? 0.0 : std::sin(polar);
        const double cosPolar = std::cos(polar);
        for (int s = 0; s <= segments; ++s) {
            const double azimuth = 2.0 * pi * (s % segments) / segments;
            const glm::vec3 n(float(sinPolar * std::sin(azimuth)), float(cosPolar),
                              float(sinPolar * std::cos(azimuth)));
            mesh.positions.push_back(n * radius);
            mesh.normals.push_back(n);
            mesh.uvs.emplace_back(float(s) / float(segments), float(r) / float(rings));
        }
    }

    // Quad (a top-left, b bottom-left, c bottom-right, d top-right) seen from outside; the
    // triangle touching a pole with two corners is degenerate and left out.
    mesh.indices.reserve(size_t(segments) * size_t(rings - 1) * 6);
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = uint32_t(r * columns + s);
            const uint32_t b = uint32_t(a + columns);
            const uint32_t c = b + 1;
            const uint32_t d = a + 1;
            if (r != rings - 1) mesh.indices.insert(mesh.indices.end(), {a, b, c});
            if (r != 0) mesh.indices.insert(mesh.indices.end(), {a, c, d});
        }
    }
    return mesh;
}

Mesh Mesh::box(const glm::vec3& size) {
    checkSize("box", "size.x", size.x);
    checkSize("box", "size.y", size.y);
    checkSize("box", "size.z", size.z);

    // Per face: outward normal, direction of growing u and direction of growing v. Seen from
    // outside u runs left to right and v top to bottom, so cross(down, right) == normal.
    struct Face {
        glm::vec3 normal, right, down;
    };
    static const Face faces[6] = {
        {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},   {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},
        {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, -1, 0}},
    };
    static const glm::vec2 corners[4] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};

    Mesh mesh;
    const glm::vec3 half = size * 0.5f;
    for (const Face& face : faces) {
        const uint32_t base = uint32_t(mesh.positions.size());
        for (const glm::vec2& uv : corners) {
            const glm::vec3 unit =
                face.normal + face.right * (2.0f * uv.x - 1.0f) + face.down * (2.0f * uv.y - 1.0f);
            mesh.positions.push_back(unit * half);
            mesh.normals.push_back(face.normal);
            mesh.uvs.push_back(uv);
        }
        mesh.indices.insert(mesh.indices.end(),
                            {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return mesh;
}

Mesh Mesh::heightField(const std::vector<float>& heights, int rows, int cols,
                       const glm::vec3& origin, const glm::vec2& size, float uvScale) {
    checkSegments("heightField", "rows", rows, 2);
    checkSegments("heightField", "cols", cols, 2);
    checkSize("heightField", "size x", size.x);
    checkSize("heightField", "size z", size.y);
    checkSize("heightField", "uv scale", uvScale);
    if (!isFinite(origin)) throw InvalidArgument("heightField: origin must be finite");
    if (heights.size() != size_t(rows) * size_t(cols))
        throw InvalidArgument(
            "heightField: expected rows * cols = " + std::to_string(size_t(rows) * size_t(cols)) +
            " heights, got " + std::to_string(heights.size()));
    for (float h : heights)
        if (!std::isfinite(h)) throw InvalidArgument("heightField: heights must be finite");
    Mesh m;
    const float dx = size.x / float(cols - 1), dz = size.y / float(rows - 1);
    auto h = [&](int i, int j) {
        return heights[size_t(std::clamp(j, 0, rows - 1)) * size_t(cols) +
                       size_t(std::clamp(i, 0, cols - 1))];
    };
    for (int j = 0; j < rows; ++j) {
        for (int i = 0; i < cols; ++i) {
            m.positions.push_back(origin + glm::vec3(float(i) * dx, h(i, j), float(j) * dz));
            const float dhdx = (h(i + 1, j) - h(i - 1, j)) /
                               (float(std::min(i + 1, cols - 1) - std::max(i - 1, 0)) * dx);
            const float dhdz = (h(i, j + 1) - h(i, j - 1)) /
                               (float(std::min(j + 1, rows - 1) - std::max(j - 1, 0)) * dz);
            m.normals.push_back(glm::normalize(glm::vec3(-dhdx, 1.0f, -dhdz)));
            m.uvs.push_back(glm::vec2(float(i) / float(cols - 1), float(j) / float(rows - 1)) *
                            uvScale);
        }
    }
    for (int j = 0; j + 1 < rows; ++j) {
        for (int i = 0; i + 1 < cols; ++i) {
            const uint32_t a = uint32_t(j * cols + i), b = a + 1, c = a + uint32_t(cols), d = c + 1;
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d}); // counter-clockwise from +Y
        }
    }
    return m;
}

std::vector<glm::vec4> computeTangents(const Mesh& mesh) {
    const size_t n = mesh.vertexCount();
    std::vector<glm::vec3> tan(n, glm::vec3(0.0f)), bit(n, glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
        const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0];
        const glm::vec3 e2 = mesh.positions[i2] - mesh.positions[i0];
        const glm::vec2 d1 = mesh.uvs[i1] - mesh.uvs[i0];
        const glm::vec2 d2 = mesh.uvs[i2] - mesh.uvs[i0];
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (std::abs(det) < 1e-20f) continue;
        // dP/du and dP/dv scaled by the triangle's UV area (|det|): area weighting for free.
        const float sign = det > 0.0f ? 1.0f : -1.0f;
        const glm::vec3 dPdu = (e1 * d2.y - e2 * d1.y) * sign;
        const glm::vec3 dPdv = (e2 * d1.x - e1 * d2.x) * sign;
        for (uint32_t i : {i0, i1, i2}) {
            tan[i] += dPdu;
            bit[i] += dPdv;
        }
    }
    std::vector<glm::vec4> out(n);
    for (size_t i = 0; i < n; ++i) {
        const glm::vec3 nrm = mesh.normals[i];
        glm::vec3 t = tan[i] - nrm * glm::dot(nrm, tan[i]);
        if (glm::dot(t, t) < 1e-24f) { // no UV gradient: any tangent orthogonal to n
            const glm::vec3 ref = std::abs(nrm.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
            t = glm::cross(ref, nrm);
        }
        t = glm::normalize(t);
        const float w = glm::dot(glm::cross(nrm, t), -bit[i]) < 0.0f ? -1.0f : 1.0f;
        out[i] = glm::vec4(t, w);
    }
    return out;
}

} // namespace weft
