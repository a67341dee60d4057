// Bindings of the analytic daylight sky (weft/Sky.h): weft.ibl.SkyModel, sky(), sun_light().
#include <cmath>

#include <pybind11/stl.h>

#include <weft/Sky.h>
#include <weft/SunLight.h>

#include "Convert.h"

namespace weft::py_bind {

namespace {

const char* kUnits =
    "Radiance is linear Rec. 709 RGB whose luminance is Y in kcd/m^2 times `scale` (irradiance\n"
    "in klx times `scale`); +Y is up.";

// ground_albedo: one grey value or an RGB triple
SkyParams skyParams(py::handle sunDirection, float turbidity, py::handle groundAlbedo, float scale,
                    py::handle night) {
    SkyParams p;
    p.sunDirection = toVec3(sunDirection, "sun_direction");
    p.turbidity = turbidity;
    p.groundAlbedo = py::hasattr(groundAlbedo, "__len__") ? toVec3(groundAlbedo, "ground_albedo")
                                                          : glm::vec3(groundAlbedo.cast<float>());
    p.scale = scale;
    if (!night.is_none()) p.nightRadiance = toVec3(night, "night_radiance");
    p.validate();
    return p;
}

// (N, 3) float directions -> f(direction) per row, as an (N, 3) float32 array.
template <class F> py::array_t<float> perDirection(py::handle obj, F f) {
    auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(obj);
    if (!a || a.ndim() != 2 || a.shape(1) != 3)
        throw InvalidArgument("directions must be an (N, 3) float array");
    py::array_t<float> out({a.shape(0), py::ssize_t(3)});
    for (py::ssize_t k = 0; k < a.shape(0); ++k) {
        const glm::vec3 v = f(glm::vec3(a.at(k, 0), a.at(k, 1), a.at(k, 2)));
        for (int c = 0; c < 3; ++c) out.mutable_at(k, c) = v[c];
    }
    return out;
}

} // namespace

void bindSky(py::module_& m) {
    py::class_<SkyModel>(
        m, "SkyModel",
        "The analytic daylight sky of Preetham, Shirley & Smits 1999 for one sun and turbidity:\n"
        "the Perez distribution of luminance Y and chromaticity x, y scaled to the paper's zenith\n"
        "values, xyY -> XYZ -> linear Rec. 709. Below the horizon a Lambertian ground of\n"
        "`ground_albedo` (grey, or RGB); with the sun below the horizon the sky of a sun on\n"
        "the horizon dimmed by 10^(0.4 h) (h: solar elevation in degrees) plus\n"
        "`night_radiance`. See weft/Sky.h.")
        .def(py::init([](py::handle sunDirection, float turbidity, py::handle groundAlbedo,
                         float scale, py::handle night) {
                 return SkyModel(skyParams(sunDirection, turbidity, groundAlbedo, scale, night));
             }),
             py::arg("sun_direction"), py::arg("turbidity") = 3.0f, py::arg("ground_albedo") = 0.2f,
             py::arg("scale") = 1.0f, py::arg("night_radiance") = py::none(),
             "The analytic sky (Preetham 1999) for a sun in sun_direction, with the class "
             "description's turbidity, ground_albedo, radiance scale and night_radiance (RGB, "
             "None = black).")
        .def(
            "radiance",
            [](const SkyModel& s, py::handle dirs) {
                return perDirection(dirs, [&](const glm::vec3& d) { return s.radiance(d); });
            },
            py::arg("directions"),
            (std::string("RGB radiance (N, 3) in directions (N, 3), without the sun's disc. ") +
             kUnits)
                .c_str())
        .def(
            "xyY",
            [](const SkyModel& s, py::handle dirs) {
                return perDirection(dirs, [&](const glm::vec3& d) { return s.xyY(d); });
            },
            py::arg("directions"),
            "The paper's CIE x, y, Y (kcd/m^2) (N, 3) of the sky in directions (N, 3) (upper\n"
            "hemisphere; before twilight dimming, night and scale).")
        .def_property_readonly(
            "zenith", [](const SkyModel& s) { return fromVec3(s.zenithxyY()); },
            "The paper's zenith (x_z, y_z, Y_z in kcd/m^2) for this sun and turbidity.")
        .def_property_readonly("to_sun", [](const SkyModel& s) { return fromVec3(s.toSun()); })
        .def_property_readonly(
            "sun_irradiance", [](const SkyModel& s) { return fromVec3(s.sunIrradiance()); },
            "RGB irradiance of the sun's disc at normal incidence (klx x scale), see sun_light.")
        .def_property_readonly(
            "sky_horizontal_irradiance",
            [](const SkyModel& s) { return fromVec3(s.skyHorizontalIrradiance()); },
            "RGB irradiance of the sky without the sun on an upward-facing surface.");

    m.def(
        "sky",
        [](py::handle sunDirection, float turbidity, int size, py::handle groundAlbedo, bool sun,
           float scale, py::handle night) {
            SkyParams p = skyParams(sunDirection, turbidity, groundAlbedo, scale, night);
            p.sun = sun;
            py::gil_scoped_release release;
            return skyCube(p, size);
        },
        py::arg("sun_direction"), py::arg("turbidity") = 3.0f, py::arg("size") = 64,
        py::arg("ground_albedo") = 0.2f, py::arg("sun") = true, py::arg("scale") = 1.0f,
        py::arg("night_radiance") = py::none(),
        (std::string(
             "A radiance CubeMap (size 1..2048 per face) of the analytic sky (Preetham 1999, see\n"
             "SkyModel) for the sun in `sun_direction` (towards the sun, any length) and turbidity\n"
             "in [1.7, 10]. With `sun` the sun's disc (0.533 deg) is added so that the cube\n"
             "integrates to sun_light's irradiance over it at any size; leave it out when the sun\n"
             "is a directional light. ") +
         kUnits)
            .c_str());
    m.def(
        "sun_light",
        [](py::handle sunDirection, float turbidity, float scale) {
            return sunLight(skyParams(sunDirection, turbidity, py::float_(0.2), scale, py::none()));
        },
        py::arg("sun_direction"), py::arg("turbidity") = 3.0f, py::arg("scale") = 1.0f,
        "The sun of the analytic sky as a weft.DirectionalLight: colour x intensity = E / pi,\n"
        "E its irradiance at normal incidence (klx x scale; the luminous solar constant 133.8\n"
        "klx through Rayleigh and aerosol extinction along the air mass), the convention under\n"
        "which a light matches an environment. Dims and reddens as the sun sets; intensity 0\n"
        "below the horizon.");
}

} // namespace weft::py_bind
