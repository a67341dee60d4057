// Bindings of the light types: DirectionalLight, PointLight, SpotLight.
#include <cmath>
#include <string>

#include <pybind11/stl.h>

#include <weft/Scene.h>

#include "Convert.h"
#include "Fields.h"

namespace weft::py_bind {

namespace {

// attenuation: (k_c, k_l, k_q) as one tuple; radius (the windowed falloff) a field of its own
template <class L> auto attenuationFields() {
    return std::make_tuple(field<py::handle, L>(
                               "attenuation",
                               [](const L& l) {
                                   return py::make_tuple(l.attenuation.constant,
                                                         l.attenuation.linear,
                                                         l.attenuation.quadratic);
                               },
                               [](L& l, py::handle terms) {
                                   auto t = numericArray(terms, "attenuation");
                                   if (t.ndim() != 1 || t.shape(0) != 3)
                                       throw InvalidArgument("attenuation must be (k_c, k_l, k_q)");
                                   l.attenuation.constant = float(t.at(0));
                                   l.attenuation.linear = float(t.at(1));
                                   l.attenuation.quadratic = float(t.at(2));
                               }),
                           field<float, L>(
                               "radius", [](const L& l) { return l.attenuation.radius; },
                               [](L& l, float r) { l.attenuation.radius = r; }));
}

template <class L>
std::string lightRepr(const char* kind, const L& l, const std::string& where,
                      const char* extra = "") {
    return std::string("<weft.") + kind + " " + where + " color=" + vecRepr(l.color) +
           " intensity=" + std::to_string(l.intensity) + extra +
           (l.castShadows ? " shadows>" : ">");
}

} // namespace

void bindLights(py::module_& m) {
    using DL = DirectionalLight;
    const auto directional = std::make_tuple(
        field("direction", &DL::direction), field("color", &DL::color),
        field("intensity", &DL::intensity), field("cast_shadows", &DL::castShadows),
        field("angular_radius", &DL::angularRadius,
              "Radians of the disc the light comes from (the sun: 0.0047); > 0 softens "
              "its shadow by the penumbra that disc casts, 0 keeps the fixed PCF kernel."));
    py::class_<DL> directionalLight(
        m, "DirectionalLight", "Sun-like light. `direction` points from the light into the scene.");
    defInit(directionalLight, validated<DL>, directional,
            "A directional light shining along `direction` with `color` x `intensity`; "
            "`angular_radius` (radians) of its disc softens its shadow.");
    defProperties(directionalLight, directional);
    directionalLight.def("__repr__", [](const DL& l) {
        return lightRepr("DirectionalLight", l, "direction=" + vecRepr(l.direction));
    });

    const auto point =
        std::tuple_cat(std::make_tuple(field("position", &PointLight::position),
                                       field("color", &PointLight::color),
                                       field("intensity", &PointLight::intensity)),
                       attenuationFields<PointLight>(),
                       std::make_tuple(field("cast_shadows", &PointLight::castShadows),
                                       field("shadow_near", &PointLight::shadowNear)));
    py::class_<PointLight> pointLight(
        m, "PointLight",
        "Light from a point in all directions. Attenuation a(d) = 1 / (k_c + k_l d + k_q d^2)\n"
        "(eq. 2.3), or max(0, 1 - d^2 / radius^2) (eq. 2.4) when radius > 0. Shadows use six\n"
        "perspective views.");
    defInit(pointLight, validated<PointLight>, point,
            "A point light at `position` with `color` x `intensity`; attenuation (k_c, k_l, "
            "k_q) of 1 / (k_c + k_l d + k_q d²), or with radius > 0 the windowed falloff "
            "(SPEC §1.2); shadow_near: the near plane of its shadow views.");
    defProperties(pointLight, point);
    pointLight
        .def(
            "attenuation_at",
            [](const PointLight& l, float d) {
                if (!(d >= 0.0f && std::isfinite(d)))
                    throw InvalidArgument(
                        "PointLight.attenuation_at: distance must be finite and >= 0, got " +
                        std::to_string(d));
                return l.attenuation(d);
            },
            py::arg("distance"), "a(d) at a distance from the light.")
        .def("__repr__", [](const PointLight& l) {
            return lightRepr("PointLight", l, "position=" + vecRepr(l.position));
        });

    const auto spot = std::tuple_cat(std::make_tuple(field("position", &SpotLight::position),
                                                     field("direction", &SpotLight::direction),
                                                     field("color", &SpotLight::color),
                                                     field("intensity", &SpotLight::intensity),
                                                     field("inner_angle", &SpotLight::innerAngle),
                                                     field("outer_angle", &SpotLight::outerAngle)),
                                     attenuationFields<SpotLight>(),
                                     std::make_tuple(field("cookie", &SpotLight::cookie),
                                                     field("cast_shadows", &SpotLight::castShadows),
                                                     field("shadow_near", &SpotLight::shadowNear)));
    py::class_<SpotLight> spotLight(
        m, "SpotLight",
        "Light into a cone around `direction`: full intensity within inner_angle of the axis,\n"
        "smooth falloff to zero at outer_angle (half-angles, radians), distance attenuation as\n"
        "PointLight, an optional `cookie` texture projected over the cone (RGB modulates).");
    defInit(spotLight, validated<SpotLight>, spot,
            "A spot light at `position` shining along `direction`, full inside inner_angle "
            "and falling smoothly to zero at outer_angle (radians); attenuation and radius as "
            "PointLight; an optional cookie Texture projected through the cone.");
    defProperties(spotLight, spot);
    spotLight.def("__repr__", [](const SpotLight& l) {
        return lightRepr("SpotLight", l,
                         "position=" + vecRepr(l.position) + " direction=" + vecRepr(l.direction),
                         l.cookie ? " cookie" : "");
    });
}

} // namespace weft::py_bind
