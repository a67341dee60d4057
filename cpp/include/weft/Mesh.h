#pragma once
// Triangle meshes: the vertex layout every renderer pass uses, built-in shapes and OBJ loading.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace weft {

/// Indexed triangle mesh. Triangles are counter-clockwise seen from the front (outside).
/// UV (0,0) addresses the first texel of the first (top) image row.
struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals; // unit length, one per position
    std::vector<glm::vec2> uvs;     // one per position
    std::vector<uint32_t> indices;  // 3 per triangle

    size_t vertexCount() const { return positions.size(); }
    size_t triangleCount() const { return indices.size() / 3; }

    /// Throws InvalidArgument for mismatched array sizes, indices out of range, a count of
    /// indices that is not a multiple of 3, an empty mesh, non-finite values or a zero normal.
    void validate() const;
    /// Axis-aligned bounds of the positions (min, max). Throws InvalidArgument without vertices.
    void bounds(glm::vec3& lo, glm::vec3& hi) const;

    /// A rectangle in the XZ plane centred at the origin, normal +Y, UVs spanning [0,1]
    /// (u along +X, v along +Z), subdivided into segmentsX x segmentsZ quads.
    /// Sizes must be positive and finite, segment counts in [1, 4096] (else InvalidArgument).
    static Mesh plane(float sizeX = 1.0f, float sizeZ = 1.0f, int segmentsX = 1, int segmentsZ = 1);
    /// A sphere centred at the origin; `segments` around the Y axis, `rings` from pole to pole.
    /// v = 0 at the +Y pole; the u = 0 / u = 1 seam is duplicated. segments in [3, 4096],
    /// rings in [2, 4096], radius positive and finite (else InvalidArgument).
    static Mesh uvSphere(float radius = 0.5f, int segments = 32, int rings = 16);
    /// An axis-aligned box centred at the origin with flat-shaded faces (24 vertices), each
    /// face's UVs spanning [0,1] upright seen from outside (+Y/-Y faces: u along +X).
    /// Sizes must be positive and finite (else InvalidArgument).
    static Mesh box(const glm::vec3& size = glm::vec3(1.0f));
    /// Terrain over a rows x cols grid of heights (row-major, rows along +Z) spanning
    /// [origin.x, origin.x + size.x] x [origin.z, origin.z + size.y] at height origin.y + h: the
    /// surface a cloth Collider::HeightField with the same data collides with (there bilinear,
    /// here two triangles per cell). Normals from central differences; UVs span [0, uvScale].
    static Mesh heightField(const std::vector<float>& heights, int rows, int cols,
                            const glm::vec3& origin, const glm::vec2& size, float uvScale = 1.0f);
};

/// Per-vertex tangents for normal mapping (SPEC §1.4): xyz = the unit direction of increasing u
/// in the surface (area-weighted over the triangles, orthogonalised against the normal),
/// w = +1 or -1 so that the bitangent b = w * (n x t) points towards decreasing v (up the
/// image, since v = 0 is the top row). Tangent-space normal maps therefore use x right and
/// y up in the image, z out of the surface ("OpenGL" convention); (128, 128, 255) is flat.
/// Vertices without a usable UV gradient get any unit tangent orthogonal to n.
std::vector<glm::vec4> computeTangents(const Mesh& mesh);

/// Angle-weighted vertex normals of an indexed triangle list (Thürmer & Wüthrich 1998): each
/// triangle adds its unit normal times its interior angle at the vertex, and each sum is
/// normalised, so the result does not depend on how a face is tessellated. Degenerate
/// triangles add nothing; a vertex with no other triangle gets +Y (validate() needs a unit
/// normal). Throws InvalidArgument for an index out of range or a count not a multiple of 3.
std::vector<glm::vec3> computeNormals(const std::vector<glm::vec3>& positions,
                                      const std::vector<uint32_t>& indices);

/// The UV fallback of a mesh that has none: a planar projection along the axis in which the
/// bounds are thinnest, u along the longest other axis, v along the remaining one, both divided
/// by the longest extent (square texels, u in [0, 1], v in [0, extent ratio]; an object
/// flat in XZ gets u = (x - min x) / size, v = (z - min z) / size, like Mesh::plane).
/// Throws InvalidArgument without positions.
std::vector<glm::vec2> computePlanarUvs(const std::vector<glm::vec3>& positions);

/// Loads a Wavefront OBJ through tinyobjloader (Debian's libtinyobjloader), which reads the text:
/// v, vt, vn, f (triangles and convex polygons, fan-triangulated; v, v/t, v//n, v/t/n; negative
/// indices count back from the elements defined so far, positive ones may refer to elements
/// defined later in the file, as tinyobjloader and trimesh allow). Numbers are read as
/// tinyobjloader reads them (a word that is no number reads as 0, a missing one as 0; indices
/// as atoi reads them, so in an f line such a word, e.g. a trailing # comment, is index 0 and
/// refused).
/// Missing normals are computed (area-weighted), missing UVs are zero. Groups, objects and
/// materials are ignored (loadObjParts in ModelIo.h reads materials). Throws IoError naming the
/// file (and line) for a missing or non-regular file or one over kMaxInputFileBytes (4 GiB), a
/// face with fewer than 3 corners, a position index 0, an out-of-range index, a value outside
/// float range, more than 2^32 - 1 distinct vertices or no faces.
/// OBJ puts vt v = 0 at the bottom image row, so the loaded uv is (u, 1 - v). Each distinct
/// (v, vt, vn) triple becomes one vertex; computed normals are smooth over each OBJ position.
Mesh loadObj(const std::string& path);

} // namespace weft
