// Mesh validation, bounds and the built-in shapes.
#include <weft/Error.h>
#include <weft/Mesh.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <utility>

namespace {

constexpr double kPi = 3.14159265358979323846;

glm::dvec3 corner(const weft::Mesh& mesh, size_t triangle, int k) {
    return glm::dvec3(mesh.positions[mesh.indices[3 * triangle + k]]);
}

// cross(b - a, c - a): points out of the front face, length twice the area.
glm::dvec3 faceNormal(const weft::Mesh& mesh, size_t triangle) {
    const glm::dvec3 a = corner(mesh, triangle, 0);
    return glm::cross(corner(mesh, triangle, 1) - a, corner(mesh, triangle, 2) - a);
}

double surfaceArea(const weft::Mesh& mesh) {
    double area = 0.0;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        area += 0.5 * glm::length(faceNormal(mesh, t));
    }
    return area;
}

// Divergence theorem; positive for a closed mesh wound counter-clockwise seen from outside.
double signedVolume(const weft::Mesh& mesh) {
    double volume = 0.0;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        volume += glm::dot(corner(mesh, t, 0), glm::cross(corner(mesh, t, 1), corner(mesh, t, 2)));
    }
    return volume / 6.0;
}

void expectUnitNormals(const weft::Mesh& mesh) {
    for (size_t i = 0; i < mesh.vertexCount(); ++i) {
        ASSERT_NEAR(glm::length(mesh.normals[i]), 1.0f, 1e-5f) << "vertex " << i;
    }
}

// Every triangle is counter-clockwise seen from the side its vertex normals point to, and no
// triangle is degenerate. `minCosine` bounds the angle between face and vertex normals.
void expectWindingAgreesWithNormals(const weft::Mesh& mesh, double minCosine = 0.5) {
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::dvec3 n = faceNormal(mesh, t);
        ASSERT_GT(glm::length(n), 0.0) << "degenerate triangle " << t;
        const glm::dvec3 unit = glm::normalize(n);
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 vertexNormal(mesh.normals[mesh.indices[3 * t + k]]);
            ASSERT_GT(glm::dot(unit, vertexNormal), minCosine)
                << "triangle " << t << " corner " << k;
        }
    }
}

void expectUvsInUnitSquare(const weft::Mesh& mesh) {
    for (const glm::vec2& uv : mesh.uvs) {
        ASSERT_GE(uv.x, 0.0f);
        ASSERT_LE(uv.x, 1.0f);
        ASSERT_GE(uv.y, 0.0f);
        ASSERT_LE(uv.y, 1.0f);
    }
}

// Seen from the front with u to the right and v down, a triangle that is counter-clockwise in
// space must be counter-clockwise in (u, -v) too; otherwise textures appear mirrored.
void expectUvsNotMirrored(const weft::Mesh& mesh) {
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const uint32_t* idx = &mesh.indices[3 * t];
        const glm::dvec2 e1 = glm::dvec2(mesh.uvs[idx[1]]) - glm::dvec2(mesh.uvs[idx[0]]);
        const glm::dvec2 e2 = glm::dvec2(mesh.uvs[idx[2]]) - glm::dvec2(mesh.uvs[idx[0]]);
        ASSERT_GT(e1.y * e2.x - e1.x * e2.y, 0.0) << "triangle " << t;
    }
}

weft::Mesh oneTriangle() {
    weft::Mesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.normals.assign(3, glm::vec3(0, 0, 1));
    mesh.uvs.assign(3, glm::vec2(0));
    mesh.indices = {0, 1, 2};
    return mesh;
}

} // namespace

TEST(MeshTest, ValidateAcceptsAConsistentMesh) { EXPECT_NO_THROW(oneTriangle().validate()); }

TEST(MeshTest, ValidateRejectsBrokenMeshes) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    using Edit = void (*)(weft::Mesh&);
    const std::pair<const char*, Edit> edits[] = {
        {"empty", [](weft::Mesh& m) { m = weft::Mesh(); }},
        {"no indices", [](weft::Mesh& m) { m.indices.clear(); }},
        {"missing normal", [](weft::Mesh& m) { m.normals.pop_back(); }},
        {"extra uv", [](weft::Mesh& m) { m.uvs.push_back(glm::vec2(0)); }},
        {"index count", [](weft::Mesh& m) { m.indices.push_back(0); }},
        {"index range", [](weft::Mesh& m) { m.indices[2] = 3; }},
        {"zero normal", [](weft::Mesh& m) { m.normals[1] = glm::vec3(0); }},
    };
    for (const auto& [name, edit] : edits) {
        weft::Mesh mesh = oneTriangle();
        edit(mesh);
        EXPECT_THROW(mesh.validate(), weft::InvalidArgument) << name;
    }
    for (float bad : {nan, inf, -inf}) {
        weft::Mesh mesh = oneTriangle();
        mesh.positions[1].y = bad;
        EXPECT_THROW(mesh.validate(), weft::InvalidArgument) << "position " << bad;
        mesh = oneTriangle();
        mesh.normals[0].x = bad;
        EXPECT_THROW(mesh.validate(), weft::InvalidArgument) << "normal " << bad;
        mesh = oneTriangle();
        mesh.uvs[2].x = bad;
        EXPECT_THROW(mesh.validate(), weft::InvalidArgument) << "uv " << bad;
    }
}

TEST(MeshTest, BoundsAreTheMinimumAndMaximumOfThePositions) {
    weft::Mesh mesh = oneTriangle();
    mesh.positions = {{-1, 5, 2}, {3, -2, 0.5f}, {0, 0, -7}};
    glm::vec3 lo, hi;
    mesh.bounds(lo, hi);
    EXPECT_EQ(lo, glm::vec3(-1, -2, -7));
    EXPECT_EQ(hi, glm::vec3(3, 5, 2));
    EXPECT_THROW(weft::Mesh().bounds(lo, hi), weft::InvalidArgument);
}

TEST(MeshTest, PlaneHasGridLayoutNormalsAndUvs) {
    const weft::Mesh mesh = weft::Mesh::plane(4.0f, 2.0f, 4, 3);
    ASSERT_NO_THROW(mesh.validate());
    EXPECT_EQ(mesh.vertexCount(), 5u * 4u);
    EXPECT_EQ(mesh.triangleCount(), 2u * 4u * 3u);
    for (size_t i = 0; i < mesh.vertexCount(); ++i) {
        const glm::vec3 p = mesh.positions[i];
        EXPECT_EQ(p.y, 0.0f);
        EXPECT_EQ(mesh.normals[i], glm::vec3(0, 1, 0));
        // u along +X, v along +Z, both spanning [0, 1].
        EXPECT_NEAR(mesh.uvs[i].x, p.x / 4.0f + 0.5f, 1e-6f);
        EXPECT_NEAR(mesh.uvs[i].y, p.z / 2.0f + 0.5f, 1e-6f);
    }
    glm::vec3 lo, hi;
    mesh.bounds(lo, hi);
    EXPECT_EQ(lo, glm::vec3(-2.0f, 0.0f, -1.0f));
    EXPECT_EQ(hi, glm::vec3(2.0f, 0.0f, 1.0f));
    EXPECT_NEAR(surfaceArea(mesh), 8.0, 1e-5);
    expectWindingAgreesWithNormals(mesh);
    expectUvsInUnitSquare(mesh);

    // All (segmentsX + 1) * (segmentsZ + 1) grid points are distinct.
    std::set<std::pair<float, float>> points;
    for (const glm::vec3& p : mesh.positions) points.insert({p.x, p.z});
    EXPECT_EQ(points.size(), mesh.vertexCount());
}

TEST(MeshTest, PlaneDefaultsToOneUnitQuad) {
    const weft::Mesh mesh = weft::Mesh::plane();
    ASSERT_NO_THROW(mesh.validate());
    EXPECT_EQ(mesh.vertexCount(), 4u);
    EXPECT_EQ(mesh.triangleCount(), 2u);
    EXPECT_NEAR(surfaceArea(mesh), 1.0, 1e-6);
    expectWindingAgreesWithNormals(mesh);
}

TEST(MeshTest, PlaneRejectsBadParameters) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_THROW(weft::Mesh::plane(0.0f, 1.0f), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::plane(1.0f, -1.0f), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::plane(nan, 1.0f), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::plane(1.0f, inf), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::plane(1.0f, 1.0f, 0, 1), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::plane(1.0f, 1.0f, 1, -3), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::plane(1.0f, 1.0f, 100000, 1), weft::InvalidArgument);
}

TEST(MeshTest, SphereHasExpectedCountsAndRadius) {
    const int segments = 12, rings = 7;
    const float radius = 1.5f;
    const weft::Mesh mesh = weft::Mesh::uvSphere(radius, segments, rings);
    ASSERT_NO_THROW(mesh.validate());
    // The seam column is duplicated; pole triangles are single.
    EXPECT_EQ(mesh.vertexCount(), size_t(segments + 1) * (rings + 1));
    EXPECT_EQ(mesh.triangleCount(), size_t(2 * segments * (rings - 1)));
    expectUnitNormals(mesh);
    for (size_t i = 0; i < mesh.vertexCount(); ++i) {
        EXPECT_NEAR(glm::length(mesh.positions[i]), radius, 1e-5f) << i;
        // Outward normals: the normal is the direction of the position.
        EXPECT_NEAR(glm::distance(mesh.normals[i], mesh.positions[i] / radius), 0.0f, 1e-5f);
    }
    expectWindingAgreesWithNormals(mesh);
    expectUvsInUnitSquare(mesh);

    glm::vec3 lo, hi;
    mesh.bounds(lo, hi);
    EXPECT_NEAR(hi.y, radius, 1e-6f);
    EXPECT_NEAR(lo.y, -radius, 1e-6f);
}

TEST(MeshTest, SphereUvSeamIsDuplicatedAndVStartsAtTheNorthPole) {
    const int segments = 16, rings = 8;
    const weft::Mesh mesh = weft::Mesh::uvSphere(1.0f, segments, rings);
    size_t seamPairs = 0;
    for (size_t i = 0; i < mesh.vertexCount(); ++i) {
        const glm::vec2 uv = mesh.uvs[i];
        if (uv.y == 0.0f || uv.y == 1.0f) {
            EXPECT_NEAR(mesh.positions[i].y, 1.0f - 2.0f * uv.y, 1e-6f);
        }
        if (uv.x != 0.0f) continue;
        // Each u = 0 vertex has a twin at the same position with u = 1.
        for (size_t j = 0; j < mesh.vertexCount(); ++j) {
            if (mesh.uvs[j] == glm::vec2(1.0f, uv.y) && mesh.positions[j] == mesh.positions[i]) {
                ++seamPairs;
                break;
            }
        }
    }
    EXPECT_EQ(seamPairs, size_t(rings + 1));
}

TEST(MeshTest, SphereUvsAreNotMirrored) {
    expectUvsNotMirrored(weft::Mesh::uvSphere(1.0f, 32, 16));
}

TEST(MeshTest, SphereAreaAndVolumeMatchAnalyticValues) {
    const float radius = 2.0f;
    const weft::Mesh mesh = weft::Mesh::uvSphere(radius, 64, 32);
    ASSERT_NO_THROW(mesh.validate());
    const double area = 4.0 * kPi * radius * radius;
    EXPECT_NEAR(surfaceArea(mesh), area, 0.01 * area);
    const double volume = 4.0 / 3.0 * kPi * radius * radius * radius;
    EXPECT_NEAR(signedVolume(mesh), volume, 0.01 * volume);
}

TEST(MeshTest, SphereAcceptsMinimalTessellation) {
    const weft::Mesh mesh = weft::Mesh::uvSphere(1.0f, 3, 2);
    ASSERT_NO_THROW(mesh.validate());
    EXPECT_EQ(mesh.triangleCount(), 6u);
    expectWindingAgreesWithNormals(mesh, 0.0); // very coarse: normals differ a lot from faces
    EXPECT_GT(signedVolume(mesh), 0.0);
}

TEST(MeshTest, SphereRejectsBadParameters) {
    EXPECT_THROW(weft::Mesh::uvSphere(0.0f), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::uvSphere(-1.0f), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::uvSphere(std::numeric_limits<float>::quiet_NaN()),
                 weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::uvSphere(std::numeric_limits<float>::infinity()),
                 weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::uvSphere(1.0f, 2, 16), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::uvSphere(1.0f, 32, 1), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::uvSphere(1.0f, 32, 0), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::uvSphere(1.0f, 1 << 20, 16), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::uvSphere(1.0f, 32, 1 << 20), weft::InvalidArgument);
}

TEST(MeshTest, BoxHasFlatFacesAndHalfSizeBounds) {
    const glm::vec3 size(2.0f, 4.0f, 6.0f);
    const weft::Mesh mesh = weft::Mesh::box(size);
    ASSERT_NO_THROW(mesh.validate());
    EXPECT_EQ(mesh.vertexCount(), 24u);
    EXPECT_EQ(mesh.triangleCount(), 12u);
    expectUnitNormals(mesh);
    expectWindingAgreesWithNormals(mesh);

    glm::vec3 lo, hi;
    mesh.bounds(lo, hi);
    EXPECT_EQ(lo, -size / 2.0f);
    EXPECT_EQ(hi, size / 2.0f);

    std::set<std::pair<int, int>> faceCorners; // (face normal id, uv corner id)
    for (size_t i = 0; i < mesh.vertexCount(); ++i) {
        const glm::vec3 n = mesh.normals[i];
        // Axis-aligned, outward, and the vertex lies on that face's plane.
        int axis = -1;
        for (int a = 0; a < 3; ++a) {
            if (std::abs(n[a]) == 1.0f) axis = a;
        }
        ASSERT_GE(axis, 0) << "normal not axis-aligned at vertex " << i;
        EXPECT_EQ(mesh.positions[i][axis], n[axis] * size[axis] / 2.0f);
        const glm::vec2 uv = mesh.uvs[i];
        EXPECT_TRUE(uv.x == 0.0f || uv.x == 1.0f);
        EXPECT_TRUE(uv.y == 0.0f || uv.y == 1.0f);
        faceCorners.insert({axis * 2 + (n[axis] > 0 ? 1 : 0), int(uv.x) * 2 + int(uv.y)});
    }
    // Six faces, each with all four UV corners.
    EXPECT_EQ(faceCorners.size(), 24u);
    EXPECT_NEAR(surfaceArea(mesh), 2.0 * (2 * 4 + 4 * 6 + 6 * 2), 1e-4);
    EXPECT_NEAR(signedVolume(mesh), 2.0 * 4.0 * 6.0, 1e-4);
}

TEST(MeshTest, BoxAndPlaneUvsAreNotMirrored) {
    expectUvsNotMirrored(weft::Mesh::box());
    expectUvsNotMirrored(weft::Mesh::plane(1.0f, 1.0f, 3, 2));
}

TEST(MeshTest, BoxRejectsBadSizes) {
    EXPECT_THROW(weft::Mesh::box(glm::vec3(1.0f, 0.0f, 1.0f)), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::box(glm::vec3(-1.0f)), weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::box(glm::vec3(1.0f, 1.0f, std::numeric_limits<float>::quiet_NaN())),
                 weft::InvalidArgument);
    EXPECT_THROW(weft::Mesh::box(glm::vec3(std::numeric_limits<float>::infinity())),
                 weft::InvalidArgument);
}
