// Wavefront OBJ + MTL through tinyobjloader (Debian's libtinyobjloader): the library reads the
// text -- numbers, face corners, usemtl / mtllib and every .mtl statement -- through its callback
// API; this file resolves and checks the indices (naming the line of anything it refuses),
// builds one mesh per material and maps the .mtl materials onto weft's.
#include <weft/Error.h>
#include <weft/Image.h>
#include <weft/Mesh.h>
#include <weft/ModelIo.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <istream>
#include <limits>
#include <map>
#include <set>
#include <streambuf>
#include <string>
#include <unordered_map>
#include <vector>

#include <tiny_obj_loader.h>

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

// A face as read: its corners (mFaceCorners[first, first + count)), where its line ends in the
// file (for errors) and its material.
struct Face {
    size_t offset;
    size_t first, count;
    uint32_t material; // index into mMaterialNames; 0 = before any usemtl
};

// A file's bytes as the stream tinyobjloader reads, so that a callback knows where it is.
class ByteStream : public std::streambuf {
public:
    explicit ByteStream(const std::vector<uint8_t>& bytes) {
        char* begin = const_cast<char*>(reinterpret_cast<const char*>(bytes.data()));
        setg(begin, begin, begin + bytes.size());
    }
    /// Bytes read so far: during a callback, the end of the line it reports.
    size_t offset() const { return size_t(gptr() - eback()); }
    /// The 1-based line that ends at `offset`; tinyobjloader ends a line at "\n", "\r\n" or "\r".
    size_t lineEndingAt(size_t offset) const {
        const char* p = eback();
        size_t line = 1;
        for (size_t i = 0; i + 1 < offset; ++i)
            line += p[i] == '\n' || (p[i] == '\r' && p[i + 1] != '\n');
        return line;
    }
};

std::string trimmedRight(std::string s) {
    s.erase(s.find_last_not_of(" \t\r\n") + 1);
    return s;
}

class ObjReader {
public:
    explicit ObjReader(const std::string& path)
        : mPath(path), mBytes(readInputFile(path, "OBJ file")), mBuffer(mBytes), mStream(&mBuffer) {
        mMaterialOf.emplace("", 0);
    }

    /// Reads the whole file; with `withMaterials`, also its mtllib files (relative to the OBJ).
    /// Faces are resolved afterwards, because OBJ files (and tinyobjloader, trimesh) allow a
    /// face to use v/vt/vn lines that come after it.
    void read(bool withMaterials);
    /// The faces whose material is `material` (all faces when kAll) as one mesh.
    Mesh build(uint32_t material);
    /// The .mtl materials by name (the first definition wins, as in tinyobjloader), each with
    /// the path of the .mtl it came from.
    std::map<std::string, std::pair<const tinyobj::material_t*, std::string>> materials() const;

    static constexpr uint32_t kAll = kNone;
    std::vector<std::string> mMaterialNames{""}; // in order of first usemtl
    std::vector<size_t> mFacesPerMaterial{0};
    std::string mPath;

private:
    // tinyobjloader asks this for each file an mtllib line names, until one loads.
    class MtlFiles : public tinyobj::MaterialReader {
    public:
        explicit MtlFiles(ObjReader& owner) : mOwner(owner) {}
        bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                        std::map<std::string, int>* byName, std::string* warn,
                        std::string* err) override;
        ObjReader& mOwner;
    };

    [[noreturn]] void failAt(size_t offset, const std::string& message) const {
        throw IoError(mPath + ":" + std::to_string(mBuffer.lineEndingAt(offset)) + ": " + message);
    }
    [[noreturn]] void fail(const std::string& message) const { failAt(mBuffer.offset(), message); }
    void requireFinite(const char* kind, float x, float y, float z) const {
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
            fail(std::string(kind) + " is not finite (a number out of float range)");
    }
    uint32_t resolveIndex(int index, size_t count, const char* kind) const;
    void checkRange(const Face& face, uint32_t index, size_t count, const char* kind) const;
    uint32_t vertexFor(const Corner& c);
    void computeMissingNormals();

    static void onVertex(void* self, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z,
                         tinyobj::real_t w);
    static void onNormal(void* self, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z);
    static void onTexcoord(void* self, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z);
    static void onFace(void* self, tinyobj::index_t* corners, int count);
    static void onUseMaterial(void* self, const char* name, int);
    static void onMaterials(void* self, const tinyobj::material_t* materials, int count);

    std::vector<uint8_t> mBytes;
    ByteStream mBuffer;
    std::istream mStream;
    std::vector<glm::vec3> mPositions;
    std::vector<glm::vec2> mTexcoords;
    std::vector<glm::vec3> mNormals;
    std::vector<Corner> mFaceCorners;
    std::vector<Face> mFaces;
    uint32_t mMaterial = 0;
    std::unordered_map<std::string, uint32_t> mMaterialOf;
    std::vector<std::vector<uint32_t>> mFacesByMaterial;
    // What the mtllib lines loaded: the materials, the .mtl each came from, and per mtllib
    // line (its end offset) the first file that failed and whether any file loaded.
    std::vector<tinyobj::material_t> mMaterials;
    std::vector<std::string> mMaterialFile;
    std::map<size_t, std::string> mLibraryFailures;
    std::set<size_t> mLibrariesLoaded;
    // State of one build():
    std::vector<Corner> mCorners; // corners of the unique output vertices
    std::unordered_map<Corner, uint32_t, CornerHash> mVertexOf;
    Mesh mMesh;
};

bool ObjReader::MtlFiles::operator()(const std::string& name,
                                     std::vector<tinyobj::material_t>* materials,
                                     std::map<std::string, int>* byName, std::string* warn,
                                     std::string* err) {
    const size_t line = mOwner.mBuffer.offset();
    const std::string path = (std::filesystem::path(mOwner.mPath).parent_path() / name).string();
    std::vector<uint8_t> bytes;
    try {
        bytes = readInputFile(path, "MTL file");
    } catch (const Error& e) {
        mOwner.mLibraryFailures.emplace(line, e.what()); // the first failure of this line
        return false;
    }
    ByteStream buffer(bytes);
    std::istream in(&buffer);
    tinyobj::LoadMtl(byName, materials, &in, warn, err);
    mOwner.mMaterialFile.resize(materials->size(), path);
    mOwner.mLibrariesLoaded.insert(line);
    return true;
}

// OBJ indices are 1-based; negative ones count back from the last element defined so far
// (tinyobjloader passes them as written, 0 for an absent texture coordinate or normal).
// Positive ones may refer to elements defined later in the file; checkRange() checks them
// once the file is read.
uint32_t ObjReader::resolveIndex(int index, size_t count, const char* kind) const {
    if (index > 0) return uint32_t(index - 1);
    const long long resolved = static_cast<long long>(count) + index;
    if (resolved < 0)
        fail(std::string(kind) + " index " + std::to_string(index) + " is out of range (" +
             std::to_string(count) + " defined so far)");
    return uint32_t(resolved);
}

void ObjReader::checkRange(const Face& face, uint32_t index, size_t count, const char* kind) const {
    if (index != kNone && index >= count)
        failAt(face.offset, std::string(kind) + " index " + std::to_string(uint64_t(index) + 1) +
                                " is out of range (" + std::to_string(count) + " in the file)");
}

void ObjReader::onVertex(void* self, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z,
                         tinyobj::real_t) {
    ObjReader& r = *static_cast<ObjReader*>(self);
    r.requireFinite("position", x, y, z);
    r.mPositions.emplace_back(x, y, z);
}

void ObjReader::onNormal(void* self, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z) {
    ObjReader& r = *static_cast<ObjReader*>(self);
    r.requireFinite("normal", x, y, z);
    // A zero normal (or one whose length overflows) is kept as "missing" and computed.
    const glm::vec3 n(x, y, z);
    const float length = glm::length(n);
    r.mNormals.push_back(length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f));
}

void ObjReader::onTexcoord(void* self, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z) {
    ObjReader& r = *static_cast<ObjReader*>(self);
    r.requireFinite("texture coordinate", x, y, z);
    r.mTexcoords.emplace_back(x, y);
}

void ObjReader::onFace(void* self, tinyobj::index_t* corners, int count) {
    ObjReader& r = *static_cast<ObjReader*>(self);
    if (count < 3) r.fail("face needs at least 3 vertices, has " + std::to_string(count));
    const size_t first = r.mFaceCorners.size();
    for (int i = 0; i < count; ++i) {
        const tinyobj::index_t& c = corners[i];
        if (c.vertex_index == 0) // also a word that is no number, e.g. a trailing comment
            r.fail("position index 0 is invalid (OBJ indices start at 1; tinyobjloader reads a "
                   "word that is no index, such as a trailing # comment, as 0)");
        Corner corner;
        corner.v = r.resolveIndex(c.vertex_index, r.mPositions.size(), "position");
        if (c.texcoord_index != 0)
            corner.t = r.resolveIndex(c.texcoord_index, r.mTexcoords.size(), "texture coordinate");
        if (c.normal_index != 0)
            corner.n = r.resolveIndex(c.normal_index, r.mNormals.size(), "normal");
        r.mFaceCorners.push_back(corner);
    }
    r.mFaces.push_back({r.mBuffer.offset(), first, size_t(count), r.mMaterial});
    ++r.mFacesPerMaterial[r.mMaterial];
}

void ObjReader::onUseMaterial(void* self, const char* name, int) {
    ObjReader& r = *static_cast<ObjReader*>(self);
    const std::string key = trimmedRight(name);
    const auto [found, added] = r.mMaterialOf.emplace(key, uint32_t(r.mMaterialNames.size()));
    if (added) {
        r.mMaterialNames.push_back(key);
        r.mFacesPerMaterial.push_back(0);
    }
    r.mMaterial = found->second;
}

void ObjReader::onMaterials(void* self, const tinyobj::material_t* materials, int count) {
    ObjReader& r = *static_cast<ObjReader*>(self);
    r.mMaterials.assign(materials, materials + count); // all so far, from every mtllib
}

void ObjReader::read(bool withMaterials) {
    tinyobj::callback_t callbacks;
    callbacks.vertex_cb = onVertex;
    callbacks.normal_cb = onNormal;
    callbacks.texcoord_cb = onTexcoord;
    callbacks.index_cb = onFace;
    callbacks.usemtl_cb = onUseMaterial;
    callbacks.mtllib_cb = onMaterials;
    MtlFiles mtlFiles(*this);
    std::string warnings, errors;
    const bool ok = tinyobj::LoadObjWithCallback(
        mStream, callbacks, this, withMaterials ? &mtlFiles : nullptr, &warnings, &errors);
    if (!ok || !errors.empty()) throw IoError("OBJ file '" + mPath + "': " + trimmedRight(errors));
    for (const auto& [offset, message] : mLibraryFailures)
        if (!mLibrariesLoaded.count(offset)) failAt(offset, message);
}

std::map<std::string, std::pair<const tinyobj::material_t*, std::string>>
ObjReader::materials() const {
    std::map<std::string, std::pair<const tinyobj::material_t*, std::string>> out;
    for (size_t i = 0; i < mMaterials.size(); ++i)
        out.emplace(
            trimmedRight(mMaterials[i].name),
            std::make_pair(&mMaterials[i], i < mMaterialFile.size() ? mMaterialFile[i] : ""));
    return out;
}

uint32_t ObjReader::vertexFor(const Corner& c) {
    const auto found = mVertexOf.find(c);
    if (found != mVertexOf.end()) return found->second;
    if (mCorners.size() >= kNone) throw IoError("OBJ file '" + mPath + "' has too many vertices");
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

Mesh ObjReader::build(uint32_t material) {
    mCorners.clear();
    mVertexOf.clear();
    mMesh = Mesh();
    std::vector<uint32_t> all;
    const std::vector<uint32_t>* faces = &all;
    if (material == kAll) {
        all.resize(mFaces.size());
        for (size_t i = 0; i < all.size(); ++i) all[i] = uint32_t(i);
    } else {
        if (mFacesByMaterial.empty()) { // made once, not once per material
            mFacesByMaterial.resize(mMaterialNames.size());
            for (size_t i = 0; i < mFaces.size(); ++i)
                mFacesByMaterial[mFaces[i].material].push_back(uint32_t(i));
        }
        faces = &mFacesByMaterial[material];
    }
    for (uint32_t faceIndex : *faces) {
        const Face& f = mFaces[faceIndex];
        const Corner* polygon = mFaceCorners.data() + f.first;
        for (size_t i = 0; i < f.count; ++i) {
            checkRange(f, polygon[i].v, mPositions.size(), "position");
            checkRange(f, polygon[i].t, mTexcoords.size(), "texture coordinate");
            checkRange(f, polygon[i].n, mNormals.size(), "normal");
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
void ObjReader::computeMissingNormals() {
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

// One .mtl material as weft's: Kd -> kd, Ks -> ks, Ns -> shininess (>= 1), map_Kd -> texture.
class MaterialMapper {
public:
    Material map(const std::string& name, const tinyobj::material_t& m, const std::string& mtl) {
        const auto fail = [&](const std::string& message) {
            throw IoError("MTL file '" + mtl + "': material '" + name + "': " + message);
        };
        const auto colour = [&](const char* statement, const tinyobj::real_t* c) {
            for (int i = 0; i < 3; ++i)
                if (!std::isfinite(c[i]) || c[i] < 0.0f)
                    fail(std::string(statement) + " needs finite non-negative numbers, has " +
                         std::to_string(c[0]) + " " + std::to_string(c[1]) + " " +
                         std::to_string(c[2]));
            return glm::vec3(c[0], c[1], c[2]);
        };
        Material out;
        out.kd = colour("Kd", m.diffuse);
        out.ks = colour("Ks", m.specular);
        if (!std::isfinite(m.shininess) || m.shininess < 0.0f)
            fail("Ns needs a finite non-negative number, has " + std::to_string(m.shininess));
        out.shininess = std::max(float(m.shininess), 1.0f); // Ns 0 is common; weft needs > 0
        const std::string texture = trimmedRight(m.diffuse_texname);
        if (!texture.empty()) {
            const std::string file = (std::filesystem::path(mtl).parent_path() / texture).string();
            const auto cached = mTextures.find(file);
            if (cached != mTextures.end()) {
                out.texture = cached->second;
            } else {
                try {
                    out.texture = std::make_shared<Texture>(loadPng(file), true);
                } catch (const Error& e) { fail(std::string("map_Kd: ") + e.what()); }
                mTextures.emplace(file, out.texture);
            }
        }
        return out;
    }

private:
    std::map<std::string, TexturePtr> mTextures; // one Texture per file, shared
};

} // namespace

Mesh loadObj(const std::string& path) {
    ObjReader reader(path);
    reader.read(false);
    return reader.build(ObjReader::kAll);
}

std::vector<MeshPart> loadObjParts(const std::string& path) {
    ObjReader reader(path);
    reader.read(true);
    const auto materials = reader.materials();
    MaterialMapper mapper;
    std::vector<MeshPart> parts;
    for (uint32_t m = 0; m < reader.mMaterialNames.size(); ++m) {
        if (reader.mFacesPerMaterial[m] == 0) continue;
        MeshPart part;
        part.name = reader.mMaterialNames[m];
        if (m > 0) {
            const auto found = materials.find(part.name);
            if (found == materials.end())
                throw IoError("OBJ file '" + path + "': material '" + part.name +
                              "' is not defined in its mtllib files");
            part.material = mapper.map(part.name, *found->second.first, found->second.second);
        }
        part.mesh = reader.build(m);
        parts.push_back(std::move(part));
    }
    if (parts.empty()) throw IoError("OBJ file '" + path + "' contains no faces");
    return parts;
}

} // namespace weft
