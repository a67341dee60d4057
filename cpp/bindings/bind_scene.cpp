// Bindings of the scene description: Mesh, Camera, Scene (materials: bind_material.cpp, lights:
// bind_lights.cpp).
#include <cstring>

#include <pybind11/stl.h>

#include <weft/Cloth.h>
#include <weft/Scene.h>

#include "Convert.h"
#include "Fields.h"

namespace weft::py_bind {

namespace {

std::shared_ptr<Mesh> makeMesh(py::handle positions, py::handle normals, py::handle uvs,
                               py::handle indices) {
    auto mesh = std::make_shared<Mesh>();
    mesh->positions = rowsOf<glm::vec3, 3>(positions, "positions");
    if (indices.is_none()) throw InvalidArgument("Mesh: indices (M, 3) are required");
    py::array idx = py::array::ensure(indices);
    if (idx && !(idx.ndim() == 1 || (idx.ndim() == 2 && idx.shape(1) == 3)))
        throw InvalidArgument("indices must have shape (M, 3)");
    mesh->indices = integersOf<uint32_t>(indices, "indices", "vertex index");
    // Missing attributes are computed (documented on weft.Mesh), not left for validate().
    if (normals.is_none())
        mesh->normals = computeNormals(mesh->positions, mesh->indices);
    else
        mesh->normals = rowsOf<glm::vec3, 3>(normals, "normals", mesh->positions.size());
    if (uvs.is_none())
        mesh->uvs = computePlanarUvs(mesh->positions);
    else
        mesh->uvs = rowsOf<glm::vec2, 2>(uvs, "uvs", mesh->positions.size());
    mesh->validate();
    return mesh;
}

const char* const kLookups[] = {"cube", "sphere_map"}; // EnvironmentLighting::Lookup's order

// The instance with this id (an id add_mesh or add_cloth returned), else InvalidArgument.
const MeshInstance& instance(const Scene& s, uint32_t id) {
    if (id >= s.instances().size())
        throw InvalidArgument("mesh id " + std::to_string(id) + " does not exist");
    return s.instances()[id];
}

} // namespace

void bindMaterial(py::module_& m); // bind_material.cpp
void bindLights(py::module_& m);   // bind_lights.cpp

void bindScene(py::module_& m) {
    py::class_<Mesh, std::shared_ptr<Mesh>>(
        m, "Mesh", "Indexed triangle mesh (counter-clockwise front faces). Immutable once made.")
        .def(py::init(&makeMesh), py::arg("positions"), py::arg("normals") = py::none(),
             py::arg("uvs") = py::none(), py::arg("indices") = py::none(),
             "positions (N,3), normals (N,3), uvs (N,2) float arrays; indices (M,3) integers\n"
             "(required; e.g. Mesh(positions, indices=faces)). normals=None: angle-weighted\n"
             "vertex normals (a vertex without a non-degenerate triangle gets +Y); uvs=None: a\n"
             "planar projection along the bounds' thinnest axis, u along the longest one,\n"
             "both divided by the longest extent (u in [0, 1]).")
        .def_property_readonly("positions", [](const Mesh& x) { return rowsArray(x.positions); })
        .def_property_readonly("normals", [](const Mesh& x) { return rowsArray(x.normals); })
        .def_property_readonly("uvs", [](const Mesh& x) { return rowsArray(x.uvs); })
        .def_property_readonly(
            "indices",
            [](const Mesh& x) {
                return arrayOf<uint32_t>(x.indices, {py::ssize_t(x.triangleCount()), 3});
            })
        .def_property_readonly(
            "tangents", [](const Mesh& x) { return rowsArray(computeTangents(x)); },
            "(N, 4) tangents the renderer uses for normal mapping: xyz along +u, w = handedness\n"
            "(bitangent w (n x t) points towards decreasing v, up the image).")
        .def_property_readonly("vertex_count", &Mesh::vertexCount)
        .def_property_readonly("triangle_count", &Mesh::triangleCount)
        .def(
            "bounds",
            [](const Mesh& x) {
                glm::vec3 lo, hi;
                x.bounds(lo, hi);
                return py::make_tuple(fromVec3(lo), fromVec3(hi));
            },
            "Axis-aligned bounds ((min x, y, z), (max x, y, z)) of the positions.")
        .def_static(
            "plane",
            [](float sx, float sz, int nx, int nz) {
                return std::make_shared<Mesh>(Mesh::plane(sx, sz, nx, nz));
            },
            py::arg("size_x") = 1.0f, py::arg("size_z") = 1.0f, py::arg("segments_x") = 1,
            py::arg("segments_z") = 1, "Rectangle in the XZ plane, normal +Y.")
        .def_static(
            "uv_sphere",
            [](float r, int segments, int rings) {
                return std::make_shared<Mesh>(Mesh::uvSphere(r, segments, rings));
            },
            py::arg("radius") = 0.5f, py::arg("segments") = 32, py::arg("rings") = 16,
            "A sphere centred at the origin: `segments` around Y, `rings` from pole to pole, "
            "v = 0 at the +Y pole.")
        .def_static(
            "box",
            [](py::handle size) { return std::make_shared<Mesh>(Mesh::box(toVec3(size, "size"))); },
            py::arg("size") = py::make_tuple(1.0, 1.0, 1.0),
            "An axis-aligned box centred at the origin with flat faces (24 vertices), each "
            "face's UVs spanning [0, 1].")
        .def("__repr__", [](const Mesh& x) {
            return "<weft.Mesh " + std::to_string(x.vertexCount()) + " vertices, " +
                   std::to_string(x.triangleCount()) + " triangles>";
        });
    m.def(
        "load_obj", [](const std::string& path) { return std::make_shared<Mesh>(loadObj(path)); },
        py::arg("path"), "Loads a Wavefront OBJ file (read by tinyobjloader) as a Mesh.");

    bindMaterial(m); // Texture, Material, then the lights: before the Scene methods taking them
    bindLights(m);

    const auto cameraFields =
        std::make_tuple(field("position", &Camera::position), field("target", &Camera::target),
                        field("up", &Camera::up), field("fov_y", &Camera::fovY),
                        field("near", &Camera::zNear), field("far", &Camera::zFar));
    py::class_<Camera> camera(m, "Camera", "Perspective camera (fov_y in radians).");
    defInit(camera, validated<Camera>, cameraFields,
            "A perspective camera at `position` looking at `target`; fov_y in radians, near "
            "and far clip distances.");
    defProperties(camera, cameraFields);
    camera
        .def(
            "view_matrix", [](const Camera& c) { return fromMat4(c.view()); },
            "World -> view matrix (4x4, acts on column vectors).")
        .def(
            "projection_matrix",
            [](const Camera& c, float aspect) { return fromMat4(c.projection(aspect)); },
            py::arg("aspect"), "View -> Vulkan clip space (y down, depth 0..1).")
        .def("__repr__", [](const Camera& c) {
            return "<weft.Camera position=" + vecRepr(c.position) + " target=" + vecRepr(c.target) +
                   ">";
        });

    py::class_<Scene, std::shared_ptr<Scene>> scene(m, "Scene",
                                                    "Meshes with materials, lights, ambient.");
    scene.def(py::init<>(), "An empty scene: add meshes, cloths, hair and lights.")
        .def(
            "add_mesh",
            [](Scene& s, std::shared_ptr<Mesh> mesh, std::optional<Material> material,
               py::object transform, bool castShadows) {
                const glm::mat4 t =
                    transform.is_none() ? glm::mat4(1.0f) : toMat4(transform, "transform");
                return s.addMesh(mesh, material.value_or(Material{}), t, castShadows);
            },
            py::arg("mesh"), py::arg("material") = py::none(), py::arg("transform") = py::none(),
            py::arg("cast_shadows") = true, "Adds a mesh instance; returns its id.")
        .def(
            "add_cloth",
            [](Scene& s, std::shared_ptr<Cloth> cloth, std::optional<Material> material,
               bool castShadows) {
                return s.addCloth(cloth, material.value_or(Material{}), castShadows);
            },
            py::arg("cloth"), py::arg("material") = py::none(), py::arg("cast_shadows") = true,
            "Adds a weft.Cloth, drawn two-sided from its state at each render (its mesh is\n"
            "uploaded only when it changed). Do not step it while a render runs. Returns its id.")
        .def(
            "set_transform",
            [](Scene& s, uint32_t id, py::handle t) { s.setTransform(id, toMat4(t, "transform")); },
            "Sets the 4x4 model matrix of the instance with this id.")
        .def("set_material", &Scene::setMaterial,
             "Replaces the material of the instance with this id.")
        .def(
            "material", [](const Scene& s, uint32_t id) { return instance(s, id).material; },
            py::arg("id"), "A copy of an instance's material.")
        .def(
            "transform",
            [](const Scene& s, uint32_t id) { return fromMat4(instance(s, id).transform); },
            py::arg("id"), "An instance's object -> world matrix (4x4).")
        // Read-only getters so that exporters (weft.reference.picture: the Mitsuba reference)
        // can read a scene back instead of rebuilding it from a second description.
        .def(
            "mesh",
            [](const Scene& s, uint32_t id) -> py::object {
                const MeshPtr& mesh = instance(s, id).mesh;
                if (!mesh) return py::none();
                return py::cast(std::const_pointer_cast<Mesh>(mesh));
            },
            py::arg("id"), "An instance's weft.Mesh (object space), or None for a cloth instance.")
        .def(
            "cloth",
            [](const Scene& s, uint32_t id) -> py::object {
                const auto cloth =
                    std::dynamic_pointer_cast<const Cloth>(instance(s, id).deformable);
                if (!cloth) return py::none();
                return py::cast(std::const_pointer_cast<Cloth>(cloth));
            },
            py::arg("id"), "A cloth instance's weft.Cloth (its mesh() is world space), else None.")
        .def(
            "casts_shadows",
            [](const Scene& s, uint32_t id) { return instance(s, id).castShadows; }, py::arg("id"),
            "Whether an instance casts shadows.")
        .def("add_light", &Scene::addLight, py::arg("light"),
             "Adds a DirectionalLight, PointLight or SpotLight; returns its id.")
        .def("set_light", &Scene::setLight, py::arg("id"), py::arg("light"),
             "Replaces the light with this id (as returned by add_light).")
        .def_property(
            "ambient", [](const Scene& s) { return fromVec3(s.ambient()); },
            [](Scene& s, py::handle v) { s.setAmbient(toVec3(v, "ambient")); })
        .def_property(
            "background", [](const Scene& s) { return fromVec3(s.background()); },
            [](Scene& s, py::handle v) { s.setBackground(toVec3(v, "background")); })
        .def("clear_environment", &Scene::clearEnvironment,
             "Removes the environment (back to the constant ambient).")
        .def_property(
            "background_image",
            [](const Scene& s) { return std::const_pointer_cast<Texture>(s.backgroundImage()); },
            [](Scene& s, std::shared_ptr<Texture> t) { s.setBackgroundImage(t); },
            "A weft.Texture behind everything instead of the background colour, stretched\n"
            "over the output (a camera frame for AR with phantom materials); None clears it.")
        .def_property_readonly(
            "environment",
            [](const Scene& s) -> py::object {
                if (!s.environment().environment) return py::none();
                return py::cast(s.environment().environment);
            },
            "The scene's weft.ibl.Environment, or None.")
        .def_property_readonly("environment_intensity",
                               [](const Scene& s) { return s.environment().intensity; })
        .def_property_readonly("lights", &Scene::lights)
        .def_property_readonly("instance_count",
                               [](const Scene& s) { return s.instances().size(); })
        .def(
            "bounds",
            [](const Scene& s) {
                glm::vec3 lo, hi;
                s.bounds(lo, hi);
                return py::make_tuple(fromVec3(lo), fromVec3(hi));
            },
            "World-space axis-aligned bounds ((min), (max)) of every instance.")
        .def("__repr__", [](const Scene& s) {
            return "<weft.Scene " + std::to_string(s.instances().size()) + " meshes, " +
                   std::to_string(s.lights().size()) + " lights>";
        });

    using E = EnvironmentLighting;
    const auto environment = std::make_tuple(
        required(field<py::object, E>(
            "environment", [](const E& e) { return py::cast(e.environment); },
            [](E& e, const py::object& environment) {
                if (py::isinstance<Environment>(environment))
                    e.environment = environment.cast<std::shared_ptr<Environment>>();
                else if (py::isinstance<CubeMap>(environment))
                    e.environment =
                        std::make_shared<Environment>(environment.cast<const CubeMap&>());
                else
                    throw InvalidArgument("Scene.set_environment: expected a weft.ibl.Environment "
                                          "or a weft.ibl.CubeMap (radiance, world space)");
            })),
        field("intensity", &E::intensity), field("specular_size", &E::specularSize),
        field("specular_levels", &E::specularLevels),
        field("specular_samples", &E::specularSamples), field("dome_lights", &E::domeLights),
        field("dome_map_size", &E::domeMapSize), field("dome_refresh", &E::domeRefresh),
        field("dome_blur", &E::domeBlur),
        field("dome_blur_depth_tolerance", &E::domeBlurDepthTolerance),
        enumField("lookup", &E::lookup, kLookups), field("sphere_map_size", &E::sphereMapSize),
        field("background", &E::background), field("background_blur", &E::backgroundBlur));
    defMethod(
        scene, "set_environment", [](Scene& s, const E& e) { s.setEnvironment(e); }, environment,
        "Lights the scene with an environment (a weft.ibl.Environment, re-baked when its version\n"
        "changes, or a weft.ibl.CubeMap, copied into a new one): SH9 irradiance for materials'\n"
        "environment_diffuse, a GGX chain (level l: roughness l / (levels - 1)) for their\n"
        "reflectivity. dome_lights (0, 8, ..., 64) shadow lights of Environment.shadow_dome\n"
        "cast dome_map_size shadow maps; the diffuse loses the occluded ones' light (eq. 2.23);\n"
        "while casters move, dome_refresh maps per frame are re-rendered (0: all).\n"
        "dome_blur > 0 blurs the dome's shadows over that many pixels (bilateral: depths that\n"
        "differ by more than dome_blur_depth_tolerance, relative, do not mix); they darken the\n"
        "diffuse light only. lookup='sphere_map' is the seed's eye-space path: the environment\n"
        "is read as eye space (a capture from the viewer's camera) and looked up in sphere maps\n"
        "of sphere_map_size at normalize(d_eye + (0, 0, 1)). background=True draws the\n"
        "environment behind the scene (and in the dynamic probe): sharp, or at background_blur\n"
        "> 0 the glossy chain at that roughness (0..1). A background_image wins over it.");

    m.def(
        "default_scene",
        [] {
            auto scene = std::make_shared<Scene>();
            Camera camera;
            makeDefaultScene(*scene, camera);
            return py::make_tuple(scene, camera);
        },
        "The demo's scene and camera: textured ground, sphere, box, a shadow-casting sun.");
}

} // namespace weft::py_bind
