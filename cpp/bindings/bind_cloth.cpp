// Bindings of the cloth solver: weft.Cloth, weft.Wind, weft.Collider.
#include <cmath>
#include <cstring>

#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include <weft/Cloth.h>

#include "sim/cloth/NaturalGsPeer.h"

#include "Convert.h"
#include "Fields.h"

namespace weft::py_bind {

namespace {

std::vector<int> particles(py::handle obj, const char* name) {
    return integersOf<int>(obj, name, "particle index", 0, INT32_MAX);
}

// A read-only (N, 3) view of 16-byte particle records owned by the cloth (kept alive by `owner`).
py::array recordView(const float* data, int n, int columns, py::handle owner) {
    py::array view(
        py::dtype::of<float>(),
        columns == 1 ? std::vector<py::ssize_t>{n} : std::vector<py::ssize_t>{n, columns},
        columns == 1 ? std::vector<py::ssize_t>{16} : std::vector<py::ssize_t>{16, 4}, data, owner);
    view.attr("setflags")(py::arg("write") = false);
    return view;
}

std::vector<uint8_t> holeMask(const Cloth& cloth, py::handle obj) {
    const int nx = cloth.params().nx, ny = cloth.params().ny;
    py::array a = py::array::ensure(obj);
    if (!a) throw py::type_error("hole mask must be an array");
    std::vector<uint8_t> mask(size_t(nx) * ny, 0);
    const char kind = a.dtype().kind();
    if (kind == 'u' && a.itemsize() == 1) { // an image: dark (or transparent) texels are holes
        if (a.ndim() != 2 && a.ndim() != 3)
            throw InvalidArgument("hole image must be (H, W) or (H, W, C)");
        const int h = int(a.shape(0)), w = int(a.shape(1)), c = a.ndim() == 3 ? int(a.shape(2)) : 1;
        if (h < 1 || w < 1 || c < 1 || c > 4) throw InvalidArgument("hole image must not be empty");
        auto img = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(a);
        const int channel = c == 4 ? 3 : 0;
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const float u = nx > 1 ? float(i) / float(nx - 1) : 0.0f;
                const float v = ny > 1 ? float(j) / float(ny - 1) : 0.0f;
                const int x = std::min(int(u * float(w)), w - 1),
                          y = std::min(int(v * float(h)), h - 1);
                mask[size_t(j * nx + i)] = img.data()[(size_t(y) * w + x) * c + channel] < 128;
            }
        return mask;
    }
    if (kind != 'b' && kind != 'i' && kind != 'u' && kind != 'f')
        throw py::type_error("hole mask must be boolean or numeric");
    if (a.ndim() != 2 || a.shape(0) != ny || a.shape(1) != nx)
        throw InvalidArgument("hole mask must have shape (ny, nx) = (" + std::to_string(ny) + ", " +
                              std::to_string(nx) + ") or be a uint8 image");
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    for (size_t k = 0; k < mask.size(); ++k) {
        if (!std::isfinite(d.data()[k])) throw InvalidArgument("hole mask must be finite");
        mask[k] = d.data()[k] != 0.0;
    }
    return mask;
}

Collider makeCollider(Collider::Kind kind, float friction) {
    Collider c;
    c.kind = kind;
    c.friction = friction;
    return c;
}

} // namespace

void bindCloth(py::module_& m) {
    // The benchmark's natural-order Gauss-Seidel peer (issue 17): not public API.
    py::class_<cloth::NaturalGsPeer>(m, "_NaturalGsPeer")
        .def(py::init([](py::handle positions, py::handle inverseMass, py::handle a, py::handle b,
                         py::handle rest, py::handle compliance, py::handle tetherParticle,
                         py::handle tetherAnchor, py::handle tetherLength, py::handle gravity,
                         float damping, int iterations, int substeps) {
                 auto floats = [](py::handle h) {
                     auto arr =
                         py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(h);
                     if (!arr) throw py::type_error("expected a float array");
                     return std::vector<float>(arr.data(), arr.data() + arr.size());
                 };
                 cloth::NaturalGsPeerSetup s;
                 s.positions = rowsOf<glm::vec3, 3>(positions, "positions");
                 s.inverseMass = floats(inverseMass);
                 s.a = particles(a, "a");
                 s.b = particles(b, "b");
                 s.rest = floats(rest);
                 s.compliance = floats(compliance);
                 s.tetherParticle = particles(tetherParticle, "tether_particle");
                 s.tetherAnchor = particles(tetherAnchor, "tether_anchor");
                 s.tetherLength = floats(tetherLength);
                 s.gravity = toVec3(gravity, "gravity");
                 s.damping = damping;
                 s.iterations = iterations;
                 s.substeps = substeps;
                 return cloth::NaturalGsPeer(std::move(s));
             }),
             py::arg("positions"), py::arg("inverse_mass"), py::arg("a"), py::arg("b"),
             py::arg("rest"), py::arg("compliance"), py::arg("tether_particle"),
             py::arg("tether_anchor"), py::arg("tether_length"), py::arg("gravity"),
             py::arg("damping"), py::arg("iterations"), py::arg("substeps"))
        .def("step", &cloth::NaturalGsPeer::step, py::arg("dt"),
             py::call_guard<py::gil_scoped_release>())
        .def_property_readonly(
            "positions", [](const cloth::NaturalGsPeer& p) { return rowsArray(p.positions()); })
        .def("kinetic_energy", &cloth::NaturalGsPeer::kineticEnergy, py::arg("particle_mass"));

    const auto windFields =
        std::make_tuple(field("direction", &Wind::direction), field("strength", &Wind::strength));
    py::class_<Wind> wind(m, "Wind",
                          "Global wind: per-particle acceleration s (n.r) n (SPEC eq. 3.5).\n"
                          "A value: Cloth.wind returns a copy; assign Cloth.wind to change it.\n"
                          "direction: finite, non-zero; |strength| <= 1e4 m/s^2.");
    defInit(wind, validated<Wind>, windFields,
            "Wind blowing along `direction` (normalised) with `strength` in m/s^2.");
    defProperties(wind, windFields);
    wind.def(py::self == py::self).def("__repr__", [](const Wind& w) {
        return "<weft.Wind direction=(" + std::to_string(w.direction.x) + ", " +
               std::to_string(w.direction.y) + ", " + std::to_string(w.direction.z) +
               ") strength=" + std::to_string(w.strength) + ">";
    });

    py::class_<Collider>(m, "Collider", "A shape the cloth is projected out of (SPEC §2.2).")
        .def_static(
            "sphere",
            [](py::handle center, float radius, float friction) {
                Collider c = makeCollider(Collider::Kind::Sphere, friction);
                c.center = toVec3(center, "center");
                c.radius = radius;
                c.validate();
                return c;
            },
            py::arg("center"), py::arg("radius"), py::arg("friction") = 0.0f,
            "A sphere collider (centre, radius > 0) with Coulomb friction coefficient "
            "`friction`.")
        .def_static(
            "plane",
            [](py::handle point, py::handle normal, float friction) {
                Collider c = makeCollider(Collider::Kind::Plane, friction);
                c.center = toVec3(point, "point");
                c.normal = toVec3(normal, "normal");
                c.validate();
                return c;
            },
            py::arg("point"), py::arg("normal"), py::arg("friction") = 0.0f,
            "An infinite plane collider through `point` with outward `normal`.")
        .def_static(
            "box",
            [](py::handle center, py::handle halfExtents, py::object rotation, float friction) {
                Collider c = makeCollider(Collider::Kind::Box, friction);
                c.center = toVec3(center, "center");
                c.halfExtents = toVec3(halfExtents, "half_extents");
                if (!rotation.is_none()) {
                    auto r = numericArray(rotation, "rotation");
                    if (r.ndim() != 2 || r.shape(0) != 3 || r.shape(1) != 3)
                        throw InvalidArgument("rotation must be a 3x3 matrix");
                    auto v = r.unchecked<2>();
                    for (int row = 0; row < 3; ++row)
                        for (int col = 0; col < 3; ++col) c.rotation[col][row] = float(v(row, col));
                }
                c.validate();
                return c;
            },
            py::arg("center"), py::arg("half_extents"), py::arg("rotation") = py::none(),
            py::arg("friction") = 0.0f,
            "An oriented box collider: centre, half extents, optional 3x3 rotation (None = "
            "axis-aligned).")
        .def_static(
            "capsule",
            [](py::handle a, py::handle b, float radius, float friction) {
                Collider c = makeCollider(Collider::Kind::Capsule, friction);
                c.center = toVec3(a, "a");
                c.end = toVec3(b, "b");
                c.radius = radius;
                c.validate();
                return c;
            },
            py::arg("a"), py::arg("b"), py::arg("radius"), py::arg("friction") = 0.0f,
            "A capsule collider: the segment a-b swept by a sphere of `radius`.")
        .def_static(
            "height_field",
            [](py::handle heights, py::handle origin, py::handle size, float friction) {
                Collider c = makeCollider(Collider::Kind::HeightField, friction);
                auto h = numericArray(heights, "heights");
                if (h.ndim() != 2) throw InvalidArgument("heights must have shape (rows, cols)");
                c.rows = int(h.shape(0));
                c.cols = int(h.shape(1));
                c.heights.assign(h.data(), h.data() + h.size());
                c.origin = toVec3(origin, "origin");
                auto s = numericArray(size, "size");
                if (s.ndim() != 1 || s.size() != 2)
                    throw InvalidArgument("size must be (size_x, size_z)");
                c.size = glm::vec2(float(s.data()[0]), float(s.data()[1]));
                c.validate();
                return c;
            },
            py::arg("heights"), py::arg("origin"), py::arg("size"), py::arg("friction") = 0.0f,
            "Terrain: heights (rows along z, cols along x) over [x0, x0+sx] x [z0, z0+sz].")
        .def(
            "distance",
            [](const Collider& c, py::handle pts) {
                const std::vector<glm::vec3> p = rowsOf<glm::vec3, 3>(pts, "points");
                py::array_t<float> d(py::ssize_t(p.size()));
                std::vector<glm::vec3> normals(p.size());
                for (size_t i = 0; i < p.size(); ++i)
                    d.mutable_data()[i] = c.distance(p[i], normals[i]);
                return py::make_tuple(d, rowsArray(normals));
            },
            py::arg("points"), "Signed distances (negative inside) and outward normals.")
        .def_readonly("friction", &Collider::friction)
        .def("__repr__", [](const Collider& c) {
            const char* names[] = {"sphere", "plane", "box", "capsule", "height_field"};
            return std::string("<weft.Collider ") + names[int(c.kind)] + ">";
        });

    using P = ClothParams;
    const auto layout = std::make_tuple( // fixed when the cloth is made
        field("nx", &P::nx), field("ny", &P::ny),
        field<py::handle, P>(
            "size", [](const P& p) { return py::make_tuple(p.size.x, p.size.y); },
            [](P& p, py::handle v) {
                auto s = numericArray(v, "size");
                if (s.ndim() != 1 || s.size() != 2)
                    throw InvalidArgument("size must be (size_u, size_v)");
                p.size = glm::vec2(float(s.data()[0]), float(s.data()[1]));
            }),
        field("origin", &P::origin), field("axis_u", &P::axisU), field("axis_v", &P::axisV),
        field("mass", &P::mass), field("bend_distance", &P::bendDistance),
        field("extra_axial", &P::extraAxial));
    const auto settings = std::make_tuple( // also properties
        field("damping", &P::damping), field("gravity", &P::gravity),
        field("iterations", &P::iterations), field("substeps", &P::substeps),
        field("compliance_stretch", &P::complianceStretch),
        field("compliance_shear", &P::complianceShear),
        field("compliance_bend", &P::complianceBend), field("tethers", &P::tethers),
        field("thickness", &P::thickness), field("self_collision", &P::selfCollision),
        field("self_thickness", &P::selfThickness), field("tear_strain", &P::tearStrain),
        field("sleep_threshold", &P::sleepThreshold), field("sleep_steps", &P::sleepSteps),
        field("threads", &P::threads));
    py::class_<Cloth, std::shared_ptr<Cloth>> cloth(
        m, "Cloth",
        "Grid cloth simulated with position-based dynamics (SPEC §2): Verlet + XPBD distance\n"
        "constraints over a graph-coloured parallel Gauss-Seidel, colliders, wind, grabbing,\n"
        "holes, tearing, self-collision, sleeping. Particle p = j * nx + i.\n"
        "Accepted ranges (else weft.InvalidArgument): size 1e-3..1e3 m per side, |origin| <= 1e7 m,\n"
        "mass 1e-6..1e6 kg, |gravity| and |wind strength| <= 1e4 m/s^2, compliance <= 1e6 m/N,\n"
        "thickness and self_thickness <= 1 m, tear_strain <= 100, sleep_threshold <= 100 m/s,\n"
        "advance(max_steps) <= 1000. Calls from several threads are serialised.");
    defInit(
        cloth, [](const P& p) { return std::make_unique<Cloth>(p); },
        std::tuple_cat(layout, settings),
        "A rectangular nx x ny particle grid spanning `size` along axis_u/axis_v from "
        "`origin`, simulated with XPBD (SPEC §3): stretch, shear and bend compliances, "
        "tethers, collisions, self-collision, tearing and sleeping as the keywords say. "
        "Raises InvalidArgument for out-of-range parameters.");
    defSettingProperties(
        cloth, [](const Cloth& c) { return c.params(); },
        [](Cloth& c, const P& p) { c.setParams(p); }, settings);
    cloth
        .def_static("soa_kernels_available", &Cloth::soaKernelsAvailable,
                    "Whether this CPU runs the structure-of-arrays relaxation (AVX-512; cloths\n"
                    "without colliders, unless WEFT_CLOTH_AOS=1); results are bit-identical.")
        .def_property_readonly("nx", [](const Cloth& c) { return c.params().nx; })
        .def_property_readonly("ny", [](const Cloth& c) { return c.params().ny; })
        .def_property_readonly("particle_count", &Cloth::particleCount)
        .def_property_readonly("constraint_count", &Cloth::constraintCount)
        .def_property_readonly("step_count", &Cloth::stepCount)
        .def_property_readonly("sleeping", &Cloth::sleeping)
        .def_property_readonly(
            "positions",
            [](py::object self) {
                const Cloth& c = self.cast<const Cloth&>();
                return recordView(c.particleData(), c.particleCount(), 3, self);
            },
            "(N, 3) float32 read-only view of the particle positions (no copy).")
        .def_property_readonly(
            "inverse_masses",
            [](py::object self) {
                const Cloth& c = self.cast<const Cloth&>();
                return recordView(c.particleData() + 3, c.particleCount(), 1, self);
            },
            "(N,) float32 read-only view; 0 for pinned, grabbed and hole particles.")
        .def_property_readonly(
            "normals",
            [](py::object self) {
                const Cloth& c = self.cast<const Cloth&>();
                return recordView(c.normalData(), c.particleCount(), 3, self);
            },
            "(N, 3) float32 read-only view of the particle normals (eq. 3.6), updated each step.")
        .def(
            "step",
            [](Cloth& c, float dt) {
                py::gil_scoped_release release;
                c.step(dt);
            },
            py::arg("dt"), "One fixed step of dt seconds (substeps inside).")
        .def(
            "advance",
            [](Cloth& c, float realDt, float rate, int maxSteps) {
                py::gil_scoped_release release;
                return c.advance(realDt, rate, maxSteps);
            },
            py::arg("real_dt"), py::arg("rate") = 60.0f, py::arg("max_steps") = 8,
            "Runs the fixed steps real time needs (capped); returns how many ran.")
        .def(
            "project_constraints",
            [](Cloth& c) {
                py::gil_scoped_release release;
                c.projectConstraints();
            },
            "One relaxation sweep + tethers + colliders, no integration (eq. 3.3/3.4).")
        .def(
            "set_positions",
            [](Cloth& c, py::handle p, bool keep) {
                c.setPositions(rowsOf<glm::vec3, 3>(p, "positions"), keep);
            },
            py::arg("positions"), py::arg("keep_velocity") = false,
            "Moves the particles to positions (N, 3); keep_velocity keeps each particle's "
            "velocity, otherwise they start at rest.")
        .def(
            "set_velocities",
            [](Cloth& c, py::handle v) { c.setVelocities(rowsOf<glm::vec3, 3>(v, "velocities")); },
            py::arg("velocities"),
            "Sets the particles' velocities (N, 3), consistently with the Verlet integration.")
        .def(
            "velocities", [](const Cloth& c) { return rowsArray(c.velocities()); },
            "The particles' velocities (N, 3) in m/s.")
        .def("reset", &Cloth::reset, "Returns the cloth to its initial grid at rest (pins kept).")
        .def(
            "pin", [](Cloth& c, py::handle idx) { c.pin(particles(idx, "pin")); },
            py::arg("indices"), "Pins the particles with these indices in place (inverse mass 0).")
        .def(
            "unpin", [](Cloth& c, py::handle idx) { c.unpin(particles(idx, "unpin")); },
            py::arg("indices"), "Frees pinned particles.")
        .def(
            "grab",
            [](Cloth& c, py::handle idx, py::handle targets) {
                c.grab(particles(idx, "grab"), rowsOf<glm::vec3, 3>(targets, "targets"));
            },
            py::arg("indices"), py::arg("targets"),
            "Grabs particles: they get inverse mass 0 and follow `targets` (one per index) "
            "exactly until release().")
        .def(
            "move_grab",
            [](Cloth& c, py::handle targets) {
                c.moveGrab(rowsOf<glm::vec3, 3>(targets, "targets"));
            },
            py::arg("targets"),
            "Moves the grabbed particles to new targets (one per grabbed particle).")
        .def("release", &Cloth::release, "Lets go of the grabbed particles.")
        .def(
            "pick",
            [](const Cloth& c, py::handle origin, py::handle direction, float maxDistance) {
                return c.pick(toVec3(origin, "origin"), toVec3(direction, "direction"),
                              maxDistance);
            },
            py::arg("origin"), py::arg("direction"), py::arg("max_distance") = 0.05f,
            "Index of the particle nearest to the ray (origin, direction) within "
            "max_distance, or -1.")
        .def(
            "set_holes", [](Cloth& c, py::handle mask) { c.setHoles(holeMask(c, mask)); },
            py::arg("mask"),
            "Bool/number (ny, nx) array (nonzero = hole) or a uint8 image of any size\n"
            "(dark, or transparent with 4 channels, = hole).")
        .def_property_readonly("holes",
                               [](const Cloth& c) {
                                   const int nx = c.params().nx, ny = c.params().ny;
                                   py::array_t<bool> out({ny, nx});
                                   for (int k = 0; k < nx * ny; ++k)
                                       out.mutable_data()[k] = c.isHole(k);
                                   return out;
                               })
        .def_property(
            "wind", [](const Cloth& c) { return c.wind(); }, &Cloth::setWind,
            "A copy of the wind (changing it changes nothing until assigned back).")
        .def("add_collider", &Cloth::addCollider, py::arg("collider"),
             "Adds a Collider; returns its id (for set_collider).")
        .def("set_collider", &Cloth::setCollider, py::arg("id"), py::arg("collider"),
             "Replaces the collider with this id (to move it between steps).")
        .def("clear_colliders", &Cloth::clearColliders, "Removes every collider.")
        .def_property_readonly("collider_count", &Cloth::colliderCount)
        .def(
            "stats",
            [](const Cloth& c) {
                const ClothStats s = c.stats();
                py::dict d;
                d["mean_strain"] = s.meanStrain;
                d["max_strain"] = s.maxStrain;
                d["active_constraints"] = s.activeConstraints;
                return d;
            },
            "Relative strain |len - rest| / rest over active constraints (mean, max).")
        .def(
            "constraints",
            [](const Cloth& c) {
                std::vector<int> a, b;
                std::vector<float> rest;
                std::vector<uint8_t> family, active;
                c.constraints(a, b, rest, family, active);
                py::dict d;
                d["a"] = py::array_t<int32_t>(py::ssize_t(a.size()), a.data());
                d["b"] = py::array_t<int32_t>(py::ssize_t(b.size()), b.data());
                d["rest"] = py::array_t<float>(py::ssize_t(rest.size()), rest.data());
                d["family"] = py::array_t<uint8_t>(py::ssize_t(family.size()), family.data());
                d["active"] = boolArray(active, {py::ssize_t(active.size())});
                return d;
            },
            "Every constraint: {'a', 'b'} particle indices, 'rest' length, 'family' (stretch, "
            "shear, bend, tether) and 'active' (False once torn).")
        .def("kinetic_energy", &Cloth::kineticEnergy,
             "Kinetic energy Σ m v²/2 of the particles (J).")
        .def("wake", &Cloth::wake, "Wakes a sleeping cloth so that the next step simulates it.")
        .def(
            "mesh",
            [](const Cloth& c) {
                const ClothMesh mesh = c.mesh();
                py::dict d;
                d["positions"] = rowsArray(mesh.positions);
                d["normals"] = rowsArray(mesh.normals);
                d["uvs"] = rowsArray(mesh.uvs);
                d["tangents"] = rowsArray(mesh.tangents);
                d["indices"] =
                    arrayOf<uint32_t>(mesh.indices, {py::ssize_t(mesh.indices.size() / 3), 3});
                return d;
            },
            "positions, normals, uvs, tangents (xyz + handedness) and intact triangles.")
        .def("__repr__", [](const Cloth& c) {
            return "<weft.Cloth " + std::to_string(c.params().nx) + "x" +
                   std::to_string(c.params().ny) + ", " + std::to_string(c.constraintCount()) +
                   " constraints, " + std::to_string(c.params().iterations) + " iterations x " +
                   std::to_string(c.params().substeps) + " substeps>";
        });
}

} // namespace weft::py_bind
