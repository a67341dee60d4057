// Bindings of the environment objects: weft.ShadowDome (the dome of shadow lights, seed eq.
// 2.21-2.23) and weft.Environment (a radiance cube whose filtered results are cached by version).
#include <pybind11/stl.h>

#include <weft/Environment.h>
#include <weft/ShadowDome.h>

#include "IblArrays.h"

namespace weft::py_bind {

void bindEnvironment(py::module_& m) {
    py::class_<ShadowDome>(m, "ShadowDome", "Dome of N shadow lights over +Y (seed eq. 2.21-2.23).")
        .def(py::init([](py::handle cube, int count, const std::string& layout, int sourceSize) {
                 const CubeArg c = toCube(cube, "radiance");
                 const DomeLayout l = domeLayout(layout);
                 py::gil_scoped_release release;
                 return ShadowDome(c, count, l, sourceSize);
             }),
             py::arg("radiance"), py::arg("count"), py::arg("layout") = "fibonacci",
             py::arg("source_size") = 128,
             "A dome of `count` shadow lights over +Y laid out as 'fibonacci' (or the other "
             "layouts layout_directions names), each with the radiance of its cell of the "
             "environment (resampled to source_size).")
        .def_static(
            "layout_directions",
            [](int count, const std::string& layout) {
                return rowsArray(ShadowDome::directions(count, domeLayout(layout)));
            },
            py::arg("count"), py::arg("layout") = "fibonacci",
            "The unit directions (count, 3) of a dome layout, without an environment.")
        .def_property_readonly("count", &ShadowDome::size)
        .def_property_readonly("directions",
                               [](const ShadowDome& d) {
                                   std::vector<glm::vec3> v;
                                   for (const auto& l : d.lights()) v.push_back(l.direction);
                                   return rowsArray(v);
                               })
        .def_property_readonly("intensities",
                               [](const ShadowDome& d) {
                                   std::vector<glm::vec3> v;
                                   for (const auto& l : d.lights()) v.push_back(l.intensity);
                                   return rowsArray(v);
                               })
        .def_property_readonly("solid_angles",
                               [](const ShadowDome& d) {
                                   py::array_t<float> out(py::ssize_t(d.size()));
                                   for (int i = 0; i < d.size(); ++i)
                                       out.mutable_data()[i] = d.lights()[size_t(i)].solidAngle;
                                   return out;
                               })
        .def_property_readonly(
            "angular_radii",
            [](const ShadowDome& d) {
                py::array_t<float> out(py::ssize_t(d.size()));
                for (int i = 0; i < d.size(); ++i)
                    out.mutable_data()[i] = d.lights()[size_t(i)].angularRadius;
                return out;
            },
            "Per light: half-angle (radians) of the cone with its cell's light spread.")
        .def(
            "diffuse_visible",
            [](const ShadowDome& d, py::handle normal, py::handle visible) {
                const auto mask = maskVector(visible, "visible", d.size());
                return fromVec3(d.diffuseVisible(toVec3(normal, "normal"), mask));
            },
            py::arg("normal"), py::arg("visible"), "Eq. 2.22: sum of visible T_i max(0, n.V_i).")
        .def(
            "diffuse_subtract",
            [](const ShadowDome& d, py::handle normal, py::handle irradiance, py::handle visible) {
                const auto mask = maskVector(visible, "visible", d.size());
                return fromVec3(d.diffuseSubtract(toVec3(normal, "normal"),
                                                  toVec3(irradiance, "irradiance"), mask));
            },
            py::arg("normal"), py::arg("irradiance"), py::arg("visible"),
            "Eq. 2.23: irradiance minus the sum over occluded lights.")
        .def("refresh_set", &ShadowDome::refreshSet, py::arg("frame"), py::arg("per_frame"),
             "Indices of the lights whose shadow maps update in `frame` (round robin).")
        .def("__repr__", [](const ShadowDome& d) {
            return "<weft.ShadowDome lights=" + std::to_string(d.size()) + ">";
        });

    py::class_<Environment, std::shared_ptr<Environment>>(
        m, "Environment",
        "An environment that re-filters only when its radiance changes (cached by version).")
        .def(py::init(
                 [](py::handle cube) { return new Environment(toCube(cube, "radiance").get()); }),
             py::arg("radiance"),
             "An environment from a radiance CubeMap or (6, S, S, 3) array; filtered results "
             "are cached until set_radiance.")
        .def(
            "set_radiance",
            [](Environment& e, py::handle cube) { e.setRadiance(toCube(cube, "radiance").get()); },
            py::arg("radiance"),
            "Replaces the radiance and invalidates every cached result (version + 1).")
        .def_property_readonly("radiance", [](const Environment& e) { return e.radiance(); })
        .def_property_readonly("version", &Environment::version)
        .def(
            "irradiance_sh",
            [](Environment& e) {
                Sh9 sh;
                {
                    py::gil_scoped_release release;
                    sh = e.irradianceSh();
                }
                return shArray(sh);
            },
            "SH9 radiance coefficients (9, 3), cached.")
        .def("irradiance_map", &Environment::irradianceMap, py::arg("size") = 32,
             py::call_guard<py::gil_scoped_release>(),
             "Irradiance CubeMap of `size` evaluated from SH9 (cached).")
        .def("specular_chain", &Environment::specularChain, py::arg("size") = 128,
             py::arg("levels") = 5, py::arg("samples") = 64,
             py::call_guard<py::gil_scoped_release>(),
             "GGX prefiltered radiance chain of `levels` mip levels, roughness rising with the "
             "level (cached).")
        .def(
            "shadow_dome",
            [](Environment& e, int count, const std::string& layout) {
                const DomeLayout l = domeLayout(layout);
                py::gil_scoped_release release;
                return e.shadowDome(count, l);
            },
            py::arg("count"), py::arg("layout") = "fibonacci",
            "A ShadowDome of `count` lights with intensities from this environment (cached).")
        .def_property_readonly("stats",
                               [](const Environment& e) {
                                   const EnvironmentStats s = e.stats();
                                   py::dict d;
                                   d["version"] = s.version;
                                   d["filter_runs"] = s.filterRuns;
                                   d["cache_hits"] = s.cacheHits;
                                   d["last_refiltered"] = s.lastRefiltered;
                                   return d;
                               })
        .def("__repr__", [](const Environment& e) {
            return "<weft.Environment size=" + std::to_string(e.radiance().size()) +
                   " version=" + std::to_string(e.version()) + ">";
        });
}

} // namespace weft::py_bind
