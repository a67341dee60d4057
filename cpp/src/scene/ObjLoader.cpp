// Wavefront OBJ loading: positions, texture coordinates, normals and polygonal faces.
#include <weft/Error.h>
#include <weft/Mesh.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>
#include "core/FileRead.h"

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

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Splits a line into whitespace-separated tokens.
void tokenize(std::string_view line, std::vector<std::string_view>& tokens) {
    tokens.clear();
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && isSpace(line[i])) ++i;
        const size_t start = i;
        while (i < line.size() && !isSpace(line[i])) ++i;
        if (i > start) tokens.push_back(line.substr(start, i - start));
    }
}

class ObjParser {
public:
    explicit ObjParser(const std::string& path) : mPath(path) {}

    Mesh parse();

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
    uint32_t vertexFor(const Corner& c);
    void computeMissingNormals();

    std::string mPath;
    size_t mLine = 0;
    std::vector<glm::vec3> mPositions;
    std::vector<glm::vec2> mTexcoords;
    std::vector<glm::vec3> mNormals;
    std::vector<Corner> mCorners; // corners of the unique output vertices
    std::unordered_map<Corner, uint32_t, CornerHash> mVertexOf;
    std::vector<Corner> mPolygon;
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
uint32_t ObjParser::resolveIndex(std::string_view text, size_t count, const char* kind) const {
    long long index = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), index);
    if (error != std::errc() || end != text.data() + text.size() || text.empty()) {
        fail(std::string("malformed ") + kind + " index '" + std::string(text) + "'");
    }
    if (index == 0) fail(std::string(kind) + " index 0 is invalid (OBJ indices start at 1)");
    const long long resolved = index > 0 ? index - 1 : static_cast<long long>(count) + index;
    if (resolved < 0 || resolved >= static_cast<long long>(count)) {
        fail(std::string(kind) + " index " + std::to_string(index) + " is out of range (" +
             std::to_string(count) + " defined so far)");
    }
    return uint32_t(resolved);
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
    mPolygon.clear();
    for (size_t i = 1; i < tokens.size(); ++i) mPolygon.push_back(corner(tokens[i]));
    // Convex polygons become a fan around their first corner.
    const uint32_t first = vertexFor(mPolygon[0]);
    uint32_t previous = vertexFor(mPolygon[1]);
    for (size_t i = 2; i < mPolygon.size(); ++i) {
        const uint32_t current = vertexFor(mPolygon[i]);
        mMesh.indices.insert(mMesh.indices.end(), {first, previous, current});
        previous = current;
    }
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

Mesh ObjParser::parse() {
    checkInputFile(mPath, "OBJ file");
    std::ifstream file(mPath, std::ios::binary);
    if (!file) throw IoError("cannot open OBJ file '" + mPath + "'");

    std::string line;
    std::vector<std::string_view> tokens;
    while (std::getline(file, line)) {
        ++mLine;
        std::string_view text(line);
        const size_t hash = text.find('#');
        if (hash != std::string_view::npos) text = text.substr(0, hash);
        tokenize(text, tokens);
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
        }
        // Everything else (o, g, s, usemtl, mtllib, l, p, curves...) is ignored.
    }
    if (file.bad()) throw IoError("error reading OBJ file '" + mPath + "'");
    if (mMesh.indices.empty()) throw IoError("OBJ file '" + mPath + "' contains no faces");

    computeMissingNormals();
    return std::move(mMesh);
}

} // namespace

Mesh loadObj(const std::string& path) { return ObjParser(path).parse(); }

} // namespace weft
