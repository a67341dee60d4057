// Bindings of the model loaders that return meshes with materials: weft.load_gltf and
// weft.load_obj_parts, as lists of weft.MeshPart.
#include <pybind11/stl.h>

#include <weft/ModelIo.h>

#include "Convert.h"

namespace weft::py_bind {

namespace {

// Python holds meshes by shared_ptr (weft.Mesh is immutable and shared between scenes).
struct PyMeshPart {
    std::string name;
    std::shared_ptr<Mesh> mesh;
    Material material;
};

std::vector<PyMeshPart> toPython(std::vector<MeshPart>&& parts) {
    std::vector<PyMeshPart> out;
    out.reserve(parts.size());
    for (MeshPart& p : parts)
        out.push_back({std::move(p.name), std::make_shared<Mesh>(std::move(p.mesh)), p.material});
    return out;
}

} // namespace

void bindModelIo(py::module_& m) {
    py::class_<PyMeshPart>(
        m, "MeshPart",
        "One mesh of a model file with its material: scene.add_mesh(part.mesh, part.material).")
        .def_readonly("name", &PyMeshPart::name, "The file's name for it (may be empty).")
        .def_readonly("mesh", &PyMeshPart::mesh, "The Mesh, in world space.")
        .def_readonly("material", &PyMeshPart::material, "The file's material as a weft Material.")
        .def("__repr__", [](const PyMeshPart& p) {
            return "<weft.MeshPart '" + p.name + "' " + std::to_string(p.mesh->vertexCount()) +
                   " vertices, " + std::to_string(p.mesh->triangleCount()) + " triangles>";
        });
    m.def(
        "load_gltf",
        [](const std::string& path) {
            std::vector<MeshPart> parts;
            {
                py::gil_scoped_release release; // file IO and image decoding
                parts = loadGltf(path);
            }
            return toPython(std::move(parts));
        },
        py::arg("path"),
        "Loads a glTF 2.0 file (.gltf or .glb) as a list of MeshPart, one per triangle primitive\n"
        "instanced by the default scene, node transforms applied. Missing normals: flat (as the\n"
        "glTF spec requires); missing UVs: Mesh's planar fallback. Materials: base colour factor\n"
        "and texture, kd = 1 - metallic, ks = mix(0.04, base colour, metallic), shininess\n"
        "2 / roughness^4 - 2 (clamped to [1, 4096]), normal map and scale, MASK alpha cutoff,\n"
        "double-sided, KHR_texture_transform of the base colour texture. Raises IoError naming\n"
        "the file for anything malformed, unsupported or too large.");
    m.def(
        "load_obj_parts",
        [](const std::string& path) {
            std::vector<MeshPart> parts;
            {
                py::gil_scoped_release release;
                parts = loadObjParts(path);
            }
            return toPython(std::move(parts));
        },
        py::arg("path"),
        "Loads a Wavefront OBJ with its .mtl materials (both read by tinyobjloader) as a list of\n"
        "MeshPart, one per material used (Kd -> kd, Ks -> ks, Ns -> shininess, map_Kd -> texture,\n"
        "PNG). Raises IoError naming the file for what load_obj refuses, a missing .mtl or\n"
        "texture, an unknown material or a negative or non-finite Kd, Ks or Ns.");
}

} // namespace weft::py_bind
