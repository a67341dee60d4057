// Wavefront OBJ loading: positions, texture coordinates, normals and polygonal faces, split by
// material (usemtl) for loadObjParts.
#include <weft/Error.h>
#include <weft/Mesh.h>
#include <weft/ModelIo.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>
#include <filesystem>
#include "core/FileRead.h"
#include "scene/LineTokens.h"
#include "scene/MtlLoader.h"

namespace weft {

namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// One face corner: zero-based indices into the v, vt and vn lists (kNone when absent).
struct Corner {
    uint32_t v = kNone, t = kNone, n = kNone;
    bool operator==(const Corner& o) const { return v == o.v && t == o.t && n == o.n; }
};

struct CornerHash {
    size_t operator()(const Corner& c) const {
        uint64_t h = c.v;
        h = h * 0x9E3779B97F4A7C15ull + c.t;
        h = h * 0x9E3779B97F4A7C15ull + c.n;
        return size_t(h ^ (h >> 32));
    }
};

// A face as read: its corners (mFaceCorners[first, first + count)), line and material.
struct Face {
    size_t line;
    size_t first, count;
    uint32_t material; // index into mMaterialNames; 0 = before any usemtl
};

class ObjParser {
public:
    explicit ObjParser(const std::string& path) : mPath(path) { mMaterialOf.emplace("", 0); }

    /// Reads the whole file; faces are resolved afterwards, because OBJ files (and
    /// tinyobjloader, trimesh) allow a face to use v/vt/vn lines that come after it.
    void read();
    /// The faces whose material is `material` (all faces when kAll) as one mesh.
    Mesh build(uint32_t material);
    /// The faces of each material (index = material), made once so that a file with many
    /// materials is not walked once per material.
    std::vector<std::vector<uint32_t>> facesByMaterial() const;

    static constexpr uint32_t kAll = kNone;
    std::vector<std::string> mMaterialNames{""}; // in order of first usemtl
    std::vector<size_t> mFacesPerMaterial{0};
    std::vector<std::string> mLibraries;         // mtllib file names, as written

private:
    [[noreturn]] void fail(const std::string& message) const {
        throw IoError(mPath + ":" + std::to_string(mLine) + ": " + message);
    }
    float number(std::string_view token) const;
    uint32_t resolveIndex(std::string_view text, size_t count, const char* kind) const;
    Corner corner(std::string_view token) const;
    void readNumbers(const std::vector<std::string_view>& tokens, size_t minimum, size_t maximum,
                float* out) const;
    void face(const std::vector<std::string_view>& tokens);
    void checkRange(uint32_t index, size_t count, const char* kind) const;
    uint32_t vertexFor(const Corner& c);
    void computeMissingNormals();

    std::string mPath;
    size_t mLine = 0;
    std::vector<glm::vec3> mPositions;
    std::vector<glm::vec2> mTexcoords;
    std::vector<glm::vec3> mNormals;
    std::vector<Corner> mFaceCorners;
    std::vector<Face> mFaces;
    uint32_t mMaterial = 0;
    std::unordered_map<std::string, uint32_t> mMaterialOf;
    std::vector<std::vector<uint32_t>> mFacesByMaterial;
    // State of one build():
    std::vector<Corner> mCorners; // corners of the unique output vertices
    std::unordered_map<Corner, uint32_t, CornerHash> mVertexOf;
    Mesh mMesh;
};

float ObjParser::number(std::string_view token) const {
    std::string_view digits = token;
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    float value = 0.0f;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error != std::errc() || end != digits.data() + digits.size() || digits.empty() ||
        !std::isfinite(value)) {
        fail("malformed number '" + std::string(token) + "'");
    }
    return value;
}

// OBJ indices are 1-based; negative ones count back from the last element defined so far.
// Positive ones may refer to elements defined later in the file; checkRange() checks them
// once the file is read.
uint32_t ObjParser::resolveIndex(std::string_view text, size_t count, const char* kind) const {
    long long index = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), index);
    if (error == std::errc::result_out_of_range)
        fail(std::string(kind) + " index '" + std::string(text) + "' is out of range");
    if (error != std::errc() || end != text.data() + text.size() || text.empty()) {
        fail(std::string("malformed ") + kind + " index '" + std::string(text) + "'");
    }
    if (index == 0) fail(std::string(kind) + " index 0 is invalid (OBJ indices start at 1)");
    if (index > 0) {
        if (index >= static_cast<long long>(kNone))
            fail(std::string(kind) + " index " + std::to_string(index) + " is out of range");
        return uint32_t(index - 1);
    }
    const long long resolved = static_cast<long long>(count) + index;
    if (resolved < 0) {
        fail(std::string(kind) + " index " + std::to_string(index) + " is out of range (" +
             std::to_string(count) + " defined so far)");
    }
    return uint32_t(resolved);
}

void ObjParser::checkRange(uint32_t index, size_t count, const char* kind) const {
    if (index != kNone && index >= count)
        fail(std::string(kind) + " index " + std::to_string(uint64_t(index) + 1) +
             " is out of range (" + std::to_string(count) + " in the file)");
}

// Parses "v", "v/t", "v//n" or "v/t/n".
Corner ObjParser::corner(std::string_view token) const {
    Corner c;
    const size_t slash1 = token.find('/');
    c.v = resolveIndex(token.substr(0, slash1), mPositions.size(), "position");
    if (slash1 == std::string_view::npos) return c;
    const std::string_view rest = token.substr(slash1 + 1);
    const size_t slash2 = rest.find('/');
    const std::string_view t = rest.substr(0, slash2);
    if (!t.empty()) c.t = resolveIndex(t, mTexcoords.size(), "texture coordinate");
    if (slash2 == std::string_view::npos) return c;
    c.n = resolveIndex(rest.substr(slash2 + 1), mNormals.size(), "normal");
    return c;
}

// Reads tokens[1..] into out; needs at least `minimum` numbers, ignores those past `maximum`.
void ObjParser::readNumbers(const std::vector<std::string_view>& tokens, size_t minimum,
                       size_t maximum, float* out) const {
    if (tokens.size() - 1 < minimum) {
        fail("'" + std::string(tokens[0]) + "' needs at least " + std::to_string(minimum) +
             " numbers");
    }
    for (size_t i = 1; i < tokens.size(); ++i) {
        const float value = number(tokens[i]);
        if (i <= maximum) out[i - 1] = value;
    }
}

uint32_t ObjParser::vertexFor(const Corner& c) {
    const auto found = mVertexOf.find(c);
    if (found != mVertexOf.end()) return found->second;
    if (mCorners.size() >= kNone) fail("too many vertices");
    const uint32_t index = uint32_t(mCorners.size());
    mVertexOf.emplace(c, index);
    mCorners.push_back(c);
    mMesh.positions.push_back(mPositions[c.v]);
    // OBJ puts v = 0 at the bottom image row, weft at the top one.
    mMesh.uvs.push_back(c.t == kNone ? glm::vec2(0.0f)
                                     : glm::vec2(mTexcoords[c.t].x, 1.0f - mTexcoords[c.t].y));
    mMesh.normals.push_back(c.n == kNone ? glm::vec3(0.0f) : mNormals[c.n]);
    return index;
}

void ObjParser::face(const std::vector<std::string_view>& tokens) {
    if (tokens.size() < 4) {
        fail("face needs at least 3 vertices, has " + std::to_string(tokens.size() - 1));
    }
    const size_t first = mFaceCorners.size();
    for (size_t i = 1; i < tokens.size(); ++i) mFaceCorners.push_back(corner(tokens[i]));
    mFaces.push_back({mLine, first, tokens.size() - 1, mMaterial});
    ++mFacesPerMaterial[mMaterial];
}

std::vector<std::vector<uint32_t>> ObjParser::facesByMaterial() const {
    std::vector<std::vector<uint32_t>> out(mMaterialNames.size());
    for (size_t i = 0; i < mFaces.size(); ++i) out[mFaces[i].material].push_back(uint32_t(i));
    return out;
}

Mesh ObjParser::build(uint32_t material) {
    mCorners.clear();
    mVertexOf.clear();
    mMesh = Mesh();
    std::vector<uint32_t> all;
    const std::vector<uint32_t>* faces = &all;
    if (material == kAll) {
        all.resize(mFaces.size());
        for (size_t i = 0; i < all.size(); ++i) all[i] = uint32_t(i);
    } else {
        if (mFacesByMaterial.empty()) mFacesByMaterial = facesByMaterial();
        faces = &mFacesByMaterial[material];
    }
    for (uint32_t faceIndex : *faces) {
        const Face& f = mFaces[faceIndex];
        mLine = f.line; // errors name the face's line
        const Corner* polygon = mFaceCorners.data() + f.first;
        for (size_t i = 0; i < f.count; ++i) {
            checkRange(polygon[i].v, mPositions.size(), "position");
            checkRange(polygon[i].t, mTexcoords.size(), "texture coordinate");
            checkRange(polygon[i].n, mNormals.size(), "normal");
        }
        // Convex polygons become a fan around their first corner.
        const uint32_t firstVertex = vertexFor(polygon[0]);
        uint32_t previous = vertexFor(polygon[1]);
        for (size_t i = 2; i < f.count; ++i) {
            const uint32_t current = vertexFor(polygon[i]);
            mMesh.indices.insert(mMesh.indices.end(), {firstVertex, previous, current});
            previous = current;
        }
    }
    if (mMesh.indices.empty()) throw IoError("OBJ file '" + mPath + "' contains no faces");
    computeMissingNormals();
    return std::move(mMesh);
}

// Vertices without a usable normal get the area-weighted average of the normals of all
// triangles that share their position (so smoothing ignores UV seams).
void ObjParser::computeMissingNormals() {
    bool missing = false;
    for (const glm::vec3& n : mMesh.normals) missing = missing || glm::dot(n, n) == 0.0f;
    if (!missing) return;

    std::vector<glm::dvec3> sums(mPositions.size(), glm::dvec3(0.0));
    for (size_t i = 0; i + 2 < mMesh.indices.size(); i += 3) {
        const Corner& a = mCorners[mMesh.indices[i]];
        const Corner& b = mCorners[mMesh.indices[i + 1]];
        const Corner& c = mCorners[mMesh.indices[i + 2]];
        const glm::dvec3 pa(mPositions[a.v]), pb(mPositions[b.v]), pc(mPositions[c.v]);
        const glm::dvec3 weighted = glm::cross(pb - pa, pc - pa); // length = 2 * area
        sums[a.v] += weighted;
        sums[b.v] += weighted;
        sums[c.v] += weighted;
    }
    for (size_t i = 0; i < mMesh.normals.size(); ++i) {
        glm::vec3& n = mMesh.normals[i];
        if (glm::dot(n, n) != 0.0f) continue;
        const glm::dvec3 sum = sums[mCorners[i].v];
        const double length = glm::length(sum);
        // A position used only by degenerate triangles has no direction; pick any.
        n = length > 0.0 ? glm::vec3(sum / length) : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

void ObjParser::read() {
    checkInputFile(mPath, "OBJ file");
    std::ifstream file(mPath, std::ios::binary);
    if (!file) throw IoError("cannot open OBJ file '" + mPath + "'");

    std::string line;
    std::vector<std::string_view> tokens;
    while (std::getline(file, line)) {
        ++mLine;
        const std::string_view text = tokenizeLine(line, tokens);
        if (tokens.empty()) continue;

        const std::string_view keyword = tokens[0];
        if (keyword == "v") {
            glm::vec3 p(0.0f);
            readNumbers(tokens, 3, 3, &p.x);
            mPositions.push_back(p);
        } else if (keyword == "vt") {
            glm::vec2 t(0.0f);
            readNumbers(tokens, 1, 2, &t.x);
            mTexcoords.push_back(t);
        } else if (keyword == "vn") {
            glm::vec3 n(0.0f);
            readNumbers(tokens, 3, 3, &n.x);
            // A zero normal is kept as "missing" and replaced by a computed one.
            const float length = glm::length(n);
            mNormals.push_back(length > 0.0f && std::isfinite(length) ? n / length
                                                                     : glm::vec3(0.0f));
        } else if (keyword == "f") {
            face(tokens);
        } else if (keyword == "usemtl" || keyword == "mtllib") {
            // Names may contain spaces: the rest of the line, trimmed.
            const size_t start = size_t(tokens[1 < tokens.size() ? 1 : 0].data() - text.data());
            const std::string rest(tokens.size() > 1
                                       ? text.substr(start, size_t(tokens.back().data() +
                                                                   tokens.back().size() -
                                                                   text.data()) - start)
                                       : std::string_view());
            if (keyword == "mtllib") {
                if (!rest.empty()) mLibraries.push_back(rest);
            } else {
                const auto [found, added] = mMaterialOf.emplace(rest, uint32_t(mMaterialNames.size()));
                if (added) {
                    mMaterialNames.push_back(rest);
                    mFacesPerMaterial.push_back(0);
                }
                mMaterial = found->second;
            }
        }
        // Everything else (o, g, s, l, p, curves...) is ignored.
    }
    if (file.bad()) throw IoError("error reading OBJ file '" + mPath + "'");
}

} // namespace

Mesh loadObj(const std::string& path) {
    ObjParser parser(path);
    parser.read();
    return parser.build(ObjParser::kAll);
}

std::vector<MeshPart> loadObjParts(const std::string& path) {
    ObjParser parser(path);
    parser.read();
    std::unordered_map<std::string, Material> materials;
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    for (const std::string& library : parser.mLibraries)
        for (auto& [name, material] : loadMtl((dir / library).string()))
            materials.emplace(name, material); // the first definition wins, as in tinyobjloader
    std::vector<MeshPart> parts;
    for (uint32_t m = 0; m < parser.mMaterialNames.size(); ++m) {
        if (parser.mFacesPerMaterial[m] == 0) continue;
        MeshPart part;
        part.name = parser.mMaterialNames[m];
        if (m > 0) {
            const auto found = materials.find(part.name);
            if (found == materials.end())
                throw IoError("OBJ file '" + path + "': material '" + part.name +
                              "' is not defined in its mtllib files");
            part.material = found->second;
        }
        part.mesh = parser.build(m);
        parts.push_back(std::move(part));
    }
    if (parts.empty()) throw IoError("OBJ file '" + path + "' contains no faces");
    return parts;
}

} // namespace weft
