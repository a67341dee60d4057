// glTF 2.0 loading through tinygltf (Debian's libtinygltf): the library parses JSON, GLB,
// base64 buffers and decodes images; this file checks what tinygltf does not (accessor bounds,
// image sizes before decoding, node cycles, output size) and maps the result onto weft's Mesh
// and Material (ModelIo.h documents the mapping).
#include <weft/Error.h>
#include <weft/ModelIo.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/FileRead.h"

namespace weft {

namespace {

// Images larger than this a side are refused before decoding (a forged header would otherwise
// make the decoder allocate gigabytes); 16384 is the largest texture most GPUs accept.
constexpr uint32_t kMaxImageSide = 16384;
// Caps on what instancing can multiply: a node graph sharing one mesh a million times.
// Vertices (32 bytes each, unwelded flat-shaded corners included) and indices over all parts.
constexpr size_t kMaxParts = size_t(1) << 16;
constexpr size_t kMaxTotalVertices = size_t(1) << 26;
constexpr size_t kMaxTotalIndices = size_t(3) << 26;
constexpr int kMaxNodeDepth = 1024;
// Node visits: a chain of nodes that each list the next one twice is visited 2^depth times
// even without a mesh.
constexpr size_t kMaxNodeVisits = size_t(1) << 20;

uint32_t bigEndian16(const unsigned char* p) { return (uint32_t(p[0]) << 8) | p[1]; }
uint32_t bigEndian32(const unsigned char* p) { return (bigEndian16(p) << 16) | bigEndian16(p + 2); }

// Width and height from a PNG or JPEG header; false for anything else or a truncated header.
bool imageSize(const unsigned char* bytes, size_t size, uint32_t& width, uint32_t& height) {
    static const unsigned char pngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (size >= 24 && std::equal(pngSignature, pngSignature + 8, bytes)) {
        width = bigEndian32(bytes + 16); // the IHDR chunk always comes first
        height = bigEndian32(bytes + 20);
        return true;
    }
    if (size < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return false;
    // JPEG: walk the marker segments up to the start-of-frame one, which holds the size.
    size_t at = 2;
    while (at + 4 <= size) {
        if (bytes[at] != 0xFF) return false;
        const unsigned marker = bytes[at + 1];
        if (marker == 0xFF) {
            ++at;
            continue;
        } // fill byte
        const size_t length = bigEndian16(bytes + at + 2);
        const bool startOfFrame =
            marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (startOfFrame) {
            if (at + 9 > size) return false;
            height = bigEndian16(bytes + at + 5);
            width = bigEndian16(bytes + at + 7);
            return true;
        }
        if (length < 2) return false;
        at += 2 + length;
    }
    return false;
}

// tinygltf's image callback: the size check, then its own stb_image decoder.
bool loadImage(tinygltf::Image* image, const int index, std::string* err, std::string* warn,
               int requestedWidth, int requestedHeight, const unsigned char* bytes, int size,
               void*) {
    uint32_t width = 0, height = 0;
    if (size <= 0 || !imageSize(bytes, size_t(size), width, height)) {
        if (err) *err += "image " + std::to_string(index) + ": not a PNG or JPEG image\n";
        return false;
    }
    if (width == 0 || height == 0 || width > kMaxImageSide || height > kMaxImageSide) {
        if (err)
            *err += "image " + std::to_string(index) + ": size " + std::to_string(width) + "x" +
                    std::to_string(height) + " is outside 1.." + std::to_string(kMaxImageSide) +
                    " a side\n";
        return false;
    }
    return tinygltf::LoadImageData(image, index, err, warn, requestedWidth, requestedHeight, bytes,
                                   size, nullptr);
}

// External buffers and images go through weft's checked reader (regular files, size cap).
bool fileExists(const std::string& path, void*) {
    std::error_code error;
    return std::filesystem::is_regular_file(path, error);
}
std::string expandPath(const std::string& path, void*) { return path; }
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void*) {
    try {
        *out = readInputFile(path, "glTF resource");
        return true;
    } catch (const Error& e) {
        if (err) *err += std::string(e.what()) + "\n";
        return false;
    }
}
bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "weft does not write files while loading\n";
    return false;
}

class GltfConverter {
public:
    GltfConverter(const std::string& path, const tinygltf::Model& model)
        : mPath(path), mModel(model) {}
    std::vector<MeshPart> convert();

private:
    [[noreturn]] void fail(const std::string& message) const {
        throw IoError("glTF file '" + mPath + "': " + message);
    }
    // Element i of an accessor as floats (integer components normalised when the accessor is).
    class Reader {
    public:
        Reader(const GltfConverter& owner, int accessor, int components, const char* what);
        size_t count() const { return mCount; }
        float get(size_t i, int c) const;
        uint32_t index(size_t i) const;

    private:
        const unsigned char* mData = nullptr;
        size_t mCount = 0, mStride = 0, mComponentSize = 0;
        int mComponentType = 0;
        bool mNormalized = false;
    };
    void visit(int node, const glm::dmat4& parent, int depth);
    void addPrimitive(const tinygltf::Mesh& mesh, const tinygltf::Primitive& primitive,
                      const glm::dmat4& world, const std::string& name);
    Material material(int index);
    TexturePtr texture(int index, bool srgb);
    std::vector<uint32_t> triangles(const tinygltf::Primitive& primitive, size_t vertices) const;

    std::string mPath;
    const tinygltf::Model& mModel;
    std::vector<MeshPart> mParts;
    size_t mTotalVertices = 0;
    size_t mTotalIndices = 0;
    size_t mNodeVisits = 0;
    std::vector<bool> mOnPath; // nodes on the current root-to-node path (cycle check)
    std::map<std::pair<int, bool>, TexturePtr> mTextures;
};

GltfConverter::Reader::Reader(const GltfConverter& owner, int accessorIndex, int components,
                              const char* what) {
    const tinygltf::Model& m = owner.mModel;
    const std::string name = std::string(what) + " accessor " + std::to_string(accessorIndex);
    if (accessorIndex < 0 || size_t(accessorIndex) >= m.accessors.size())
        owner.fail(name + " does not exist");
    const tinygltf::Accessor& a = m.accessors[accessorIndex];
    if (a.sparse.isSparse) owner.fail(name + " is sparse (not supported)");
    if (tinygltf::GetNumComponentsInType(uint32_t(a.type)) != components)
        owner.fail(name + " has " + std::to_string(tinygltf::GetNumComponentsInType(a.type)) +
                   " components, expected " + std::to_string(components));
    const int componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    if (componentSize <= 0) owner.fail(name + " has an unknown component type");
    if (a.bufferView < 0 || size_t(a.bufferView) >= m.bufferViews.size())
        owner.fail(name + " has no buffer view (not supported)");
    const tinygltf::BufferView& view = m.bufferViews[a.bufferView];
    if (view.buffer < 0 || size_t(view.buffer) >= m.buffers.size())
        owner.fail(name + ": its buffer view refers to a missing buffer");
    const std::vector<unsigned char>& buffer = m.buffers[view.buffer].data;
    const uint64_t elementSize = uint64_t(componentSize) * uint64_t(components);
    const uint64_t stride = view.byteStride ? uint64_t(view.byteStride) : elementSize;
    // Subtractions of sizes already checked against an in-memory size, so nothing can wrap.
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
        owner.fail(name + ": its buffer view lies outside its buffer");
    if (stride < elementSize) owner.fail(name + ": byte stride smaller than an element");
    if (a.count == 0) owner.fail(name + " is empty");
    if (a.byteOffset > view.byteLength || view.byteLength - a.byteOffset < elementSize ||
        uint64_t(a.count - 1) > (view.byteLength - a.byteOffset - elementSize) / stride)
        owner.fail(name + " reaches past the end of its buffer view");
    mData = buffer.data() + view.byteOffset + a.byteOffset;
    mCount = a.count;
    mStride = stride;
    mComponentSize = size_t(componentSize);
    mComponentType = a.componentType;
    mNormalized = a.normalized;
}

float GltfConverter::Reader::get(size_t i, int c) const {
    const unsigned char* p = mData + i * mStride + size_t(c) * mComponentSize;
    switch (mComponentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return mNormalized ? p[0] / 255.0f : p[0];
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const float v = float(int8_t(p[0]));
        return mNormalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return mNormalized ? v / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return mNormalized ? std::max(v / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return float(v);
    }
    default: return std::numeric_limits<float>::quiet_NaN(); // rejected by validate()
    }
}

uint32_t GltfConverter::Reader::index(size_t i) const {
    const unsigned char* p = mData + i * mStride;
    switch (mComponentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    default: return std::numeric_limits<uint32_t>::max(); // out of range below
    }
}

glm::dmat4 localTransform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data()); // column-major
    glm::dmat4 m(1.0);
    if (node.translation.size() == 3)
        m = glm::translate(m, glm::make_vec3(node.translation.data()));
    if (node.rotation.size() == 4) {
        const std::vector<double>& q = node.rotation; // glTF stores x, y, z, w
        m *= glm::mat4_cast(glm::normalize(glm::dquat(q[3], q[0], q[1], q[2])));
    }
    if (node.scale.size() == 3) m = glm::scale(m, glm::make_vec3(node.scale.data()));
    return m;
}

std::vector<MeshPart> GltfConverter::convert() {
    mOnPath.assign(mModel.nodes.size(), false);
    const int scene = mModel.defaultScene >= 0 ? mModel.defaultScene : 0;
    if (size_t(scene) < mModel.scenes.size()) {
        for (int node : mModel.scenes[scene].nodes) visit(node, glm::dmat4(1.0), 0);
    } else {
        // No scene: the meshes as they are (a library of assets).
        for (const tinygltf::Mesh& mesh : mModel.meshes)
            for (const tinygltf::Primitive& p : mesh.primitives)
                addPrimitive(mesh, p, glm::dmat4(1.0), mesh.name);
    }
    if (mParts.empty()) fail("contains no triangles");
    return std::move(mParts);
}

void GltfConverter::visit(int index, const glm::dmat4& parent, int depth) {
    if (index < 0 || size_t(index) >= mModel.nodes.size())
        fail("node " + std::to_string(index) + " does not exist");
    if (mOnPath[index]) fail("node " + std::to_string(index) + " is its own ancestor");
    if (depth > kMaxNodeDepth) fail("node hierarchy deeper than " + std::to_string(kMaxNodeDepth));
    if (++mNodeVisits > kMaxNodeVisits)
        fail("nodes instanced more than " + std::to_string(kMaxNodeVisits) + " times in all");
    const tinygltf::Node& node = mModel.nodes[index];
    const glm::dmat4 world = parent * localTransform(node);
    mOnPath[index] = true;
    if (node.mesh >= 0) {
        if (size_t(node.mesh) >= mModel.meshes.size())
            fail("node " + std::to_string(index) + " refers to a missing mesh");
        const tinygltf::Mesh& mesh = mModel.meshes[node.mesh];
        for (const tinygltf::Primitive& p : mesh.primitives)
            addPrimitive(mesh, p, world, mesh.name.empty() ? node.name : mesh.name);
    }
    for (int child : node.children) visit(child, world, depth + 1);
    mOnPath[index] = false;
}

std::vector<uint32_t> GltfConverter::triangles(const tinygltf::Primitive& primitive,
                                               size_t vertices) const {
    std::vector<uint32_t> list;
    if (primitive.indices >= 0) {
        const Reader r(*this, primitive.indices, 1, "indices");
        list.resize(r.count());
        for (size_t i = 0; i < r.count(); ++i) {
            list[i] = r.index(i);
            if (list[i] >= vertices)
                fail("index " + std::to_string(i) + " of accessor " +
                     std::to_string(primitive.indices) + " is out of range (or not unsigned)");
        }
    } else {
        list.resize(vertices);
        for (size_t i = 0; i < vertices; ++i) list[i] = uint32_t(i);
    }
    std::vector<uint32_t> out;
    const size_t n = list.size();
    if (primitive.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // glTF spec 3.7.2.1: triangle i = (v_i, v_{i+1+i%2}, v_{i+2-i%2}).
        for (size_t i = 0; i + 2 < n; ++i)
            out.insert(out.end(), {list[i], list[i + 1 + i % 2], list[i + 2 - i % 2]});
    } else if (primitive.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (size_t i = 0; i + 2 < n; ++i)
            out.insert(out.end(), {list[i + 1], list[i + 2], list[0]});
    } else {
        out.assign(list.begin(), list.end() - n % 3); // a trailing partial triangle is dropped
    }
    return out;
}

void GltfConverter::addPrimitive(const tinygltf::Mesh& gmesh, const tinygltf::Primitive& primitive,
                                 const glm::dmat4& world, const std::string& name) {
    (void)gmesh;
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
        return; // points and lines have no surface to draw
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) return; // allowed by the spec; nothing to draw
    if (mParts.size() >= kMaxParts) fail("more than " + std::to_string(kMaxParts) + " mesh parts");

    MeshPart part;
    part.name = name;
    part.material = material(primitive.material);
    const Reader positions(*this, position->second, 3, "POSITION");
    const size_t count = positions.count();
    if (count > kMaxTotalVertices - mTotalVertices)
        fail("more than " + std::to_string(kMaxTotalVertices) + " vertices in all");
    mTotalVertices += count;

    Mesh& mesh = part.mesh;
    mesh.positions.resize(count);
    for (size_t i = 0; i < count; ++i)
        mesh.positions[i] = glm::vec3(
            world * glm::dvec4(positions.get(i, 0), positions.get(i, 1), positions.get(i, 2), 1.0));
    const auto normal = primitive.attributes.find("NORMAL");
    if (normal != primitive.attributes.end()) {
        const Reader normals(*this, normal->second, 3, "NORMAL");
        if (normals.count() != count) fail("NORMAL and POSITION counts differ");
        const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(world)));
        mesh.normals.resize(count);
        for (size_t i = 0; i < count; ++i) {
            const glm::dvec3 n =
                normalMatrix * glm::dvec3(normals.get(i, 0), normals.get(i, 1), normals.get(i, 2));
            const double length = glm::length(n);
            // A zero normal in the file has no direction; +Y keeps the mesh valid.
            mesh.normals[i] =
                length > 0.0 && std::isfinite(length) ? glm::vec3(n / length) : glm::vec3(0, 1, 0);
        }
    }
    // The UV set the base-colour texture reads (KHR_texture_transform may override it).
    const tinygltf::Material* gm =
        primitive.material >= 0 && size_t(primitive.material) < mModel.materials.size()
            ? &mModel.materials[primitive.material]
            : nullptr;
    int texCoord = gm ? gm->pbrMetallicRoughness.baseColorTexture.texCoord : 0;
    const tinygltf::Value* transform = nullptr;
    if (gm) {
        const auto& ext = gm->pbrMetallicRoughness.baseColorTexture.extensions;
        const auto found = ext.find("KHR_texture_transform");
        if (found != ext.end() && found->second.IsObject()) {
            transform = &found->second;
            if (transform->Has("texCoord") && transform->Get("texCoord").IsInt())
                texCoord = transform->Get("texCoord").GetNumberAsInt();
        }
    }
    const auto uv = primitive.attributes.find("TEXCOORD_" + std::to_string(std::max(texCoord, 0)));
    if (uv != primitive.attributes.end()) {
        const Reader uvs(*this, uv->second, 2, "TEXCOORD");
        if (uvs.count() != count) fail("TEXCOORD and POSITION counts differ");
        mesh.uvs.resize(count);
        for (size_t i = 0; i < count; ++i) mesh.uvs[i] = glm::vec2(uvs.get(i, 0), uvs.get(i, 1));
        if (transform) {
            auto number = [&](const char* key, int i, double fallback) {
                if (!transform->Has(key)) return fallback;
                const tinygltf::Value& v = transform->Get(key);
                const tinygltf::Value& x = i < 0 ? v : v.Get(i);
                return x.IsNumber() ? x.GetNumberAsDouble() : fallback;
            };
            // KHR_texture_transform: uv' = translation * rotation * scale * uv.
            const glm::dvec2 offset(number("offset", 0, 0.0), number("offset", 1, 0.0));
            const glm::dvec2 scale(number("scale", 0, 1.0), number("scale", 1, 1.0));
            const double rotation = number("rotation", -1, 0.0);
            const double c = std::cos(rotation), s = std::sin(rotation);
            for (glm::vec2& t : mesh.uvs) {
                const glm::dvec2 scaled = glm::dvec2(t) * scale;
                t = glm::vec2(
                    offset + glm::dvec2(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y));
            }
        }
    } else {
        mesh.uvs = computePlanarUvs(mesh.positions);
    }

    mesh.indices = triangles(primitive, count);
    if (mesh.indices.empty()) return;
    if (mesh.indices.size() > kMaxTotalIndices - mTotalIndices)
        fail("more than " + std::to_string(kMaxTotalIndices / 3) + " triangles in all");
    mTotalIndices += mesh.indices.size();
    if (glm::determinant(glm::dmat3(world)) < 0.0) // a mirror turns the front face inside
        for (size_t i = 0; i < mesh.indices.size(); i += 3)
            std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
    if (mesh.normals.empty()) {
        // glTF spec 3.7.2.1: without normals, flat shading. One vertex per corner.
        if (mesh.indices.size() > kMaxTotalVertices - mTotalVertices)
            fail("more than " + std::to_string(kMaxTotalVertices) + " vertices in all");
        mTotalVertices += mesh.indices.size();
        Mesh flat;
        flat.positions.reserve(mesh.indices.size());
        flat.uvs.reserve(mesh.indices.size());
        for (uint32_t i : mesh.indices) {
            flat.positions.push_back(mesh.positions[i]);
            flat.uvs.push_back(mesh.uvs[i]);
            flat.indices.push_back(uint32_t(flat.indices.size()));
        }
        flat.normals = computeNormals(flat.positions, flat.indices);
        mesh = std::move(flat);
    }
    try {
        mesh.validate();
        part.material.validate();
    } catch (const InvalidArgument& e) { fail(std::string("mesh '") + name + "': " + e.what()); }
    mParts.push_back(std::move(part));
}

TexturePtr GltfConverter::texture(int index, bool srgb) {
    if (index < 0) return nullptr;
    const auto cached = mTextures.find({index, srgb});
    if (cached != mTextures.end()) return cached->second;
    if (size_t(index) >= mModel.textures.size())
        fail("texture " + std::to_string(index) + " does not exist");
    const int source = mModel.textures[index].source;
    if (source < 0 || size_t(source) >= mModel.images.size())
        fail("texture " + std::to_string(index) +
             " has no image (extensions such as KTX2 or "
             "WebP images are not supported)");
    const tinygltf::Image& gi = mModel.images[source];
    if (gi.width <= 0 || gi.height <= 0 || gi.component < 1 || gi.component > 4 ||
        (gi.bits != 8 && gi.bits != 16) ||
        gi.image.size() != size_t(gi.width) * gi.height * gi.component * (gi.bits / 8))
        fail("image " + std::to_string(source) + " was not decoded");
    ImageU8 image(gi.width, gi.height, gi.component);
    const size_t values = image.pixels.size();
    for (size_t i = 0; i < values; ++i) {
        // 16-bit values are in host order (stb_image); keep their high byte.
        if (gi.bits == 16) {
            uint16_t v;
            std::memcpy(&v, gi.image.data() + 2 * i, 2);
            image.pixels[i] = uint8_t(v >> 8);
        } else {
            image.pixels[i] = gi.image[i];
        }
    }
    TexturePtr t = std::make_shared<Texture>(std::move(image), srgb);
    mTextures[{index, srgb}] = t;
    return t;
}

Material GltfConverter::material(int index) {
    Material m;
    if (index < 0) return m; // the spec's default material: white, metallic 1, roughness 1
    if (size_t(index) >= mModel.materials.size())
        fail("material " + std::to_string(index) + " does not exist");
    const tinygltf::Material& gm = mModel.materials[index];
    const tinygltf::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
    glm::vec3 base(1.0f);
    for (int c = 0; c < 3 && size_t(c) < pbr.baseColorFactor.size(); ++c) {
        if (!std::isfinite(pbr.baseColorFactor[c]))
            fail("material " + std::to_string(index) + " has a non-finite base colour");
        base[c] = float(std::clamp(pbr.baseColorFactor[c], 0.0, 1.0));
    }
    const float metallic = float(std::clamp(pbr.metallicFactor, 0.0, 1.0));
    const float roughness = float(std::clamp(pbr.roughnessFactor, 0.0, 1.0));
    if (!std::isfinite(pbr.metallicFactor) || !std::isfinite(pbr.roughnessFactor))
        fail("material " + std::to_string(index) + " has a non-finite factor");
    m.baseColor = base;
    m.kd = glm::vec3(1.0f - metallic);
    m.ks = glm::mix(glm::vec3(0.04f), base, metallic);
    m.reflectivity = m.ks;
    m.environmentDiffuse = 1.0f;
    const double alpha = double(roughness) * roughness;
    const double exponent = alpha > 0.0 ? 2.0 / (alpha * alpha) - 2.0 : 4096.0;
    m.shininess = float(std::clamp(exponent, 1.0, 4096.0));
    m.texture = texture(pbr.baseColorTexture.index, true);
    m.normalMap = texture(gm.normalTexture.index, false);
    if (m.normalMap) m.normalScale = float(gm.normalTexture.scale);
    if (gm.alphaMode == "MASK") {
        if (!std::isfinite(gm.alphaCutoff))
            fail("material " + std::to_string(index) + " has a non-finite alpha cutoff");
        m.alphaCutoff = float(std::clamp(gm.alphaCutoff, 0.0, 1.0));
    }
    m.twoSided = gm.doubleSided;
    return m;
}

} // namespace

std::vector<MeshPart> loadGltf(const std::string& path) {
    const std::vector<uint8_t> bytes = readInputFile(path, "glTF file");
    if (bytes.size() > std::numeric_limits<unsigned int>::max())
        throw IoError("glTF file '" + path + "' is larger than tinygltf reads");
    tinygltf::TinyGLTF reader;
    reader.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &refuseWrite, nullptr});
    reader.SetImageLoader(&loadImage, nullptr);
    tinygltf::Model model;
    std::string error, warning;
    const std::string baseDir = std::filesystem::path(path).parent_path().string();
    const bool binary = bytes.size() >= 4 && std::equal(bytes.begin(), bytes.begin() + 4, "glTF");
    const bool ok = binary ? reader.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(),
                                                         unsigned(bytes.size()), baseDir)
                           : reader.LoadASCIIFromString(&model, &error, &warning,
                                                        reinterpret_cast<const char*>(bytes.data()),
                                                        unsigned(bytes.size()), baseDir);
    if (!ok) {
        while (!error.empty() && error.back() == '\n') error.pop_back();
        throw IoError("glTF file '" + path +
                      "': " + (error.empty() ? "could not be parsed" : error));
    }
    return GltfConverter(path, model).convert();
}

} // namespace weft
