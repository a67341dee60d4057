#pragma once
// Model files that carry materials as well as geometry: glTF 2.0 (tinygltf) and OBJ + MTL.
// Each loader returns one MeshPart per (mesh, material) pair, ready for Scene::addMesh.
#include <string>
#include <vector>

#include <weft/Material.h>
#include <weft/Mesh.h>

namespace weft {

struct MeshPart {
    std::string name;  ///< the glTF mesh's (or node's) name / the OBJ material's name; may be empty
    Mesh mesh;         ///< in world space (node transforms applied), validated
    Material material; ///< the file's material mapped onto weft's Blinn-Phong one
};

/// Loads a glTF 2.0 file (.gltf with external or embedded buffers, or binary .glb) through
/// tinygltf. Every triangle primitive (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN) instanced by
/// the default scene's nodes (all meshes, untransformed, when the file has no scene) becomes
/// one part, with its node's world transform applied (mirroring transforms keep the front face
/// outside). Points and lines are skipped.
///
/// Attributes: POSITION; NORMAL (when absent, flat normals as the glTF spec requires: the
/// triangles are unwelded); TEXCOORD_n of the base-colour texture (float or normalised
/// integers; absent: computePlanarUvs). glTF UV (0, 0) is the top-left texel, as in weft.
///
/// Materials (pbrMetallicRoughness mapped onto Blinn-Phong): base_color = baseColorFactor.rgb,
/// texture = baseColorTexture (sRGB); kd = 1 - metallic; ks = F0 = mix(0.04, base colour,
/// metallic), also the environment reflectivity (environment_diffuse = 1); shininess = 2 / alpha^2
/// - 2 with alpha = roughness^2 (the Blinn-Phong exponent matching a Beckmann/GGX lobe of that
/// width, Walter et al. 2007), clamped to [1, 4096]; normalTexture -> normal_map with its scale;
/// alphaMode MASK -> alpha_cutoff; doubleSided -> two_sided; KHR_texture_transform on the base
/// colour texture is applied to the UVs. Not mapped: metallicRoughness, occlusion and emissive
/// textures, emissive factors, BLEND (drawn opaque).
///
/// Throws IoError naming the file for anything tinygltf refuses, missing or oversized files
/// (also external buffers and images), accessors outside their buffers, sparse accessors,
/// images other than PNG/JPEG or larger than 16384 pixels a side, node cycles, or no triangles.
std::vector<MeshPart> loadGltf(const std::string& path);

/// Loads an OBJ file with its materials: one part per `usemtl` material used by faces (faces
/// before any `usemtl` get a default Material), geometry as loadObj reads it. tinyobjloader reads
/// the `mtllib` files (relative to the OBJ; of several names on one line the first that loads)
/// and their statements; Kd -> kd, Ks -> ks, Ns -> shininess (clamped to >= 1), map_Kd ->
/// texture (PNG, sRGB; relative to the .mtl; its options such as -s or -o are skipped). A
/// statement the .mtl leaves out has tinyobjloader's default: Ks 0, Ns 1, Kd 0 -- or 0.6 for a
/// material with a map_Kd when no Kd line came before it in the file; a one-number Kd or Ks
/// reads as (r, 0, 0). Throws IoError naming the file for what loadObj refuses, an mtllib line
/// none of whose files can be read (missing, not regular, over 4 GiB), an unknown material
/// name, a negative or non-finite Kd, Ks or Ns, or a texture loadPng refuses.
std::vector<MeshPart> loadObjParts(const std::string& path);

} // namespace weft
