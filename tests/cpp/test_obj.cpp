// Wavefront OBJ loading.
#include <weft/Error.h>
#include <weft/Mesh.h>

#include <gtest/gtest.h>

#include "TempDir.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace fs = std::filesystem;

namespace {

// The IoError message of loading `path`, or "" when it loads.
std::string loadError(const std::string& path) {
    try {
        weft::loadObj(path);
    } catch (const weft::IoError& e) { return e.what(); }
    return "";
}

void expectSameMesh(const weft::Mesh& a, const weft::Mesh& b) {
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.uvs, b.uvs);
    EXPECT_EQ(a.indices, b.indices);
}

const char* const kQuad = R"(# a unit quad in the XY plane, facing +Z
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1 4/4/1
)";

} // namespace

TEST(ObjTest, QuadWithAllAttributesBecomesTwoTriangles) {
    TempDir dir;
    const weft::Mesh mesh = weft::loadObj(dir.write("quad.obj", kQuad));
    ASSERT_NO_THROW(mesh.validate());
    ASSERT_EQ(mesh.vertexCount(), 4u);
    ASSERT_EQ(mesh.triangleCount(), 2u);
    EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(mesh.positions, (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
    for (const glm::vec3& n : mesh.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
    // OBJ's v = 0 is the bottom image row; weft's is the top row, so v is flipped.
    EXPECT_EQ(mesh.uvs, (std::vector<glm::vec2>{{0, 1}, {1, 1}, {1, 0}, {0, 0}}));
}

TEST(ObjTest, NegativeIndicesCountBackFromTheLastDefinition) {
    TempDir dir;
    const std::string relative = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
f -4/-4/-1 -3/-3/-1 -2/-2/-1 -1/-1/-1
)";
    const weft::Mesh absolute = weft::loadObj(dir.write("abs.obj", kQuad));
    const weft::Mesh mesh = weft::loadObj(dir.write("rel.obj", relative));
    expectSameMesh(mesh, absolute);

    // -1 means the latest vertex at the time the face is read, not at the end of the file.
    const weft::Mesh twice = weft::loadObj(dir.write("twice.obj", R"(v 0 0 0
v 1 0 0
v 0 1 0
f -3 -2 -1
v 5 0 0
v 6 0 0
v 5 1 0
f -3 -2 -1
)"));
    ASSERT_EQ(twice.triangleCount(), 2u);
    EXPECT_EQ(twice.positions[twice.indices[0]], glm::vec3(0, 0, 0));
    EXPECT_EQ(twice.positions[twice.indices[3]], glm::vec3(5, 0, 0));
    EXPECT_EQ(twice.positions[twice.indices[5]], glm::vec3(5, 1, 0));
}

TEST(ObjTest, AllFaceVertexFormsAreAccepted) {
    TempDir dir;
    const weft::Mesh mesh = weft::loadObj(dir.write("forms.obj", R"(v 0 0 0
v 1 0 0
v 0 1 0
vt 0.25 0.5
vn 0 0 -1
f 1 2 3
f 1/1 2/1 3/1
f 1//1 2//1 3//1
f 1/1/1 2/1/1 3/1/1
)"));
    ASSERT_NO_THROW(mesh.validate());
    EXPECT_EQ(mesh.triangleCount(), 4u);
    // Four different (v, t, n) combinations per position.
    EXPECT_EQ(mesh.vertexCount(), 12u);
    // Face 2 (v/t) has the texture coordinate, face 1 (v) gets zero.
    EXPECT_EQ(mesh.uvs[mesh.indices[0]], glm::vec2(0.0f));
    EXPECT_EQ(mesh.uvs[mesh.indices[3]], glm::vec2(0.25f, 0.5f));
    // Face 3 (v//n) has the file's normal although it points against the winding.
    EXPECT_EQ(mesh.normals[mesh.indices[6]], glm::vec3(0, 0, -1));
    EXPECT_EQ(mesh.uvs[mesh.indices[6]], glm::vec2(0.0f));
    // Face 1 (no normal) gets the computed one, which follows the winding (+Z).
    EXPECT_NEAR(glm::distance(mesh.normals[mesh.indices[0]], glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
}

TEST(ObjTest, VerticesAreSharedPerPositionUvNormalTriple) {
    TempDir dir;
    // A cube with one normal per face: 8 positions x 3 faces each = 24 distinct vertices.
    const weft::Mesh mesh = weft::loadObj(dir.write("cube.obj", R"(v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 0 1 0
vn -1 0 0
vn 1 0 0
f 1//1 4//1 3//1 2//1
f 5//2 6//2 7//2 8//2
f 1//3 2//3 6//3 5//3
f 4//4 8//4 7//4 3//4
f 1//5 5//5 8//5 4//5
f 2//6 3//6 7//6 6//6
)"));
    ASSERT_NO_THROW(mesh.validate());
    EXPECT_EQ(mesh.vertexCount(), 24u);
    EXPECT_EQ(mesh.triangleCount(), 12u);
    // Each triangle is counter-clockwise seen from the side its normals point to.
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
        const glm::vec3 b = mesh.positions[mesh.indices[3 * t + 1]];
        const glm::vec3 c = mesh.positions[mesh.indices[3 * t + 2]];
        EXPECT_GT(glm::dot(glm::cross(b - a, c - a), mesh.normals[mesh.indices[3 * t]]), 0.0f);
    }
}

TEST(ObjTest, PolygonsAreFanTriangulated) {
    TempDir dir;
    const weft::Mesh mesh = weft::loadObj(dir.write("pentagon.obj", R"(v 0 0 0
v 2 0 0
v 3 1 0
v 1 2 0
v -1 1 0
f 1 2 3 4 5
)"));
    ASSERT_NO_THROW(mesh.validate());
    EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
    for (const glm::vec3& n : mesh.normals) {
        EXPECT_NEAR(glm::distance(n, glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
    }
}

TEST(ObjTest, ComputedNormalsOfATetrahedronPointOutward) {
    TempDir dir;
    const weft::Mesh mesh = weft::loadObj(dir.write("tetra.obj", R"(v 1 1 1
v 1 -1 -1
v -1 1 -1
v -1 -1 1
f 1 2 3
f 1 3 4
f 1 4 2
f 2 4 3
)"));
    ASSERT_NO_THROW(mesh.validate());
    EXPECT_EQ(mesh.vertexCount(), 4u);
    EXPECT_EQ(mesh.triangleCount(), 4u);
    for (size_t i = 0; i < mesh.vertexCount(); ++i) {
        const glm::vec3 n = mesh.normals[i];
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
        // The centroid is the origin; by symmetry the smooth normal is the position direction.
        EXPECT_NEAR(glm::dot(n, glm::normalize(mesh.positions[i])), 1.0f, 1e-6f) << i;
    }
}

TEST(ObjTest, ComputedNormalsAreAreaWeighted) {
    TempDir dir;
    // The origin is shared by a triangle of area 2 facing +Z and one of area 0.5 facing +X.
    const weft::Mesh mesh = weft::loadObj(dir.write("weights.obj", R"(v 0 0 0
v 2 0 0
v 0 2 0
v 0 1 0
v 0 0 1
f 1 2 3
f 1 4 5
)"));
    ASSERT_NO_THROW(mesh.validate());
    const glm::vec3 expected = glm::normalize(glm::vec3(0.5f, 0.0f, 2.0f));
    EXPECT_NEAR(glm::distance(mesh.normals[0], expected), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(mesh.normals[1], glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(mesh.normals[4], glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
}

TEST(ObjTest, FileNormalsAreNormalizedAndZeroOnesAreComputed) {
    TempDir dir;
    const weft::Mesh mesh = weft::loadObj(dir.write("normals.obj", R"(v 0 0 0
v 1 0 0
v 0 1 0
vn 0 0 5
vn 0 0 0
f 1//1 2//2 3//1
)"));
    ASSERT_NO_THROW(mesh.validate());
    for (const glm::vec3& n : mesh.normals) {
        EXPECT_NEAR(glm::distance(n, glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
    }
}

TEST(ObjTest, IgnoresUnsupportedStatementsCommentsAndExtraValues) {
    TempDir dir;
    const weft::Mesh mesh = weft::loadObj(dir.write("extras.obj", R"(# exported by something
mtllib scene.mtl
o Thing
g group1 group2

  v 0 0 0 1.0   # w is ignored
v 1 0 0 0.5 0.5 0.5
	v	0	1	0
vt 0.5
vt 0.25 0.75 0.0
vp 0.1 0.2
usemtl red
s off
l 1 2
p 3
curv 0 1 1 2
f 1/1 2/2 3/1
)"));
    ASSERT_NO_THROW(mesh.validate());
    EXPECT_EQ(mesh.triangleCount(), 1u);
    EXPECT_EQ(mesh.positions[mesh.indices[2]], glm::vec3(0, 1, 0));
    // A vt without v has v = 0, i.e. the bottom row: weft v = 1.
    EXPECT_EQ(mesh.uvs[mesh.indices[0]], glm::vec2(0.5f, 1.0f));
    EXPECT_EQ(mesh.uvs[mesh.indices[1]], glm::vec2(0.25f, 0.25f));
}

TEST(ObjTest, CrlfLineEndingsGiveTheSameMesh) {
    TempDir dir;
    std::string crlf;
    for (const char* c = kQuad; *c; ++c) {
        if (*c == '\n') crlf += '\r';
        crlf += *c;
    }
    crlf = "# windows file\r\n\r\n" + crlf;
    crlf.resize(crlf.size() - 2); // no line break after the last line
    const weft::Mesh mesh = weft::loadObj(dir.write("crlf.obj", crlf));
    expectSameMesh(mesh, weft::loadObj(dir.write("lf.obj", kQuad)));
    EXPECT_EQ(mesh.triangleCount(), 2u);

    // Line numbers still count CRLF lines (and a lone CR, as tinyobjloader does).
    const std::string path = dir.write("bad.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1e99 0\r\n");
    EXPECT_NE(loadError(path).find(path + ":3:"), std::string::npos) << loadError(path);
    const std::string cr = dir.write("cr.obj", "v 0 0 0\rv 1 0 0\r\rv 0 1e99 0\r\n");
    EXPECT_NE(loadError(cr).find(cr + ":4:"), std::string::npos) << loadError(cr);
}

// tinyobjloader reads the numbers: a word that is no number reads as 0, a missing one as 0 (its
// reading is weft's); a value outside float range is refused, naming the line.
TEST(ObjTest, NumbersAreTinyobjloadersReadingAndOutOfRangeOnesReportTheLine) {
    TempDir dir;
    const weft::Mesh mesh = weft::loadObj(dir.write("words.obj", R"(v 0 0 0
v 1 abc 0
v 1 2
f 1 2 3
)"));
    ASSERT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(mesh.positions[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(mesh.positions[2], glm::vec3(1, 2, 0));

    for (const char* line : {"v 1e99 0 0", "v 1 2 -1e39", "vt 0.5 1e300", "vn 0 1e40 0"}) {
        const std::string bad = dir.write("bad.obj", std::string("v 0 0 0\n") + line + "\n");
        const std::string error = loadError(bad);
        EXPECT_NE(error.find(bad + ":2:"), std::string::npos) << line << " -> " << error;
        EXPECT_NE(error.find("not finite"), std::string::npos) << line << " -> " << error;
    }
}

TEST(ObjTest, MalformedFacesReportTheLine) {
    TempDir dir;
    const std::string header = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";
    // fewer than 3 corners; a word that is no index (tinyobjloader reads it as 0), also a
    // trailing comment, which tinyobjloader's own LoadObj refuses too
    for (const char* face : {"f 1 2", "f 1 2 x", "f 1/ 2 3/1/1/1", "f 1//", "f 1 2 3 # c"}) {
        const std::string path = dir.write("face.obj", header + "# c\n" + face + "\n");
        const std::string error = loadError(path);
        EXPECT_NE(error.find(path + ":7:"), std::string::npos) << face << " -> " << error;
    }
    // tinyobjloader reads an index with atoi: "1.5" is 1, "z" is none
    const std::string read = dir.write("read.obj", header + "f 1.5 2 3\nf 1/1/1 2//z 3\n");
    const weft::Mesh mesh = weft::loadObj(read);
    EXPECT_EQ(mesh.triangleCount(), 2u);
    EXPECT_EQ(mesh.positions[mesh.indices[0]], glm::vec3(0, 0, 0));
}

TEST(ObjTest, InvalidIndicesReportTheLine) {
    TempDir dir;
    const std::string header = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";
    for (const char* face : {"f 0 1 2", "f 1 2 4", "f 1 2 -4", "f 1/2 2/1 3/1", "f 1//2 2 3",
                             "f 1/-2 2 3", "f 1 2 3000000000"}) {
        const std::string path = dir.write("index.obj", header + face + "\n");
        const std::string error = loadError(path);
        EXPECT_NE(error.find(path + ":6:"), std::string::npos) << face << " -> " << error;
    }
    // Faces may use vertices defined after them (tinyobjloader and trimesh accept that), but
    // an index beyond the whole file names the face's line.
    const std::string early = dir.write("early.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    EXPECT_EQ(weft::loadObj(early).triangleCount(), 1u);
    const std::string beyond = dir.write("beyond.obj", "f 1 2 4\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    EXPECT_NE(loadError(beyond).find(beyond + ":1:"), std::string::npos) << loadError(beyond);
}

TEST(ObjTest, MissingFileThrowsIoErrorNamingIt) {
    TempDir dir;
    const std::string path = (fs::path(dir.write("x.obj", "")).parent_path() / "nope.obj").string();
    const std::string error = loadError(path);
    EXPECT_NE(error.find(path), std::string::npos) << error;
    EXPECT_THROW(weft::loadObj(path), weft::Error);
}

TEST(ObjTest, FileWithoutFacesThrowsIoError) {
    TempDir dir;
    EXPECT_THROW(weft::loadObj(dir.write("empty.obj", "")), weft::IoError);
    EXPECT_THROW(weft::loadObj(dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")),
                 weft::IoError);
}
