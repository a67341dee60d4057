// Bindings of the light types: DirectionalLight, PointLight, SpotLight.
#include <cmath>
#include <string>

#include <pybind11/stl.h>

#include <weft/Scene.h>

#include "Convert.h"
#include "ValueProperty.h"

namespace weft::py_bind {

void bindLights(py::module_& m) {
    py::class_<DirectionalLight>(
        m, "DirectionalLight", "Sun-like light. `direction` points from the light into the scene.")
        .def(py::init([](py::handle direction, py::handle color, float intensity, bool shadows,
                         float angularRadius) {
                 DirectionalLight l;
                 l.direction = toVec3(direction, "direction");
                 l.color = toVec3(color, "color");
                 l.intensity = intensity;
                 l.castShadows = shadows;
                 l.angularRadius = angularRadius;
                 l.validate();
                 return l;
             }),
             py::arg("direction") = py::make_tuple(0, -1, 0),
             py::arg("color") = py::make_tuple(1, 1, 1), py::arg("intensity") = 1.0f,
             py::arg("cast_shadows") = true, py::arg("angular_radius") = 0.0f,
             "A directional light shining along `direction` with `color` x `intensity`; "
             "`angular_radius` (radians) of its disc softens its shadow.")
        .WEFT_VEC3_PROPERTY(DirectionalLight, "direction", direction)
        .WEFT_VEC3_PROPERTY(DirectionalLight, "color", color)
        .def_property(
            "intensity", [](const DirectionalLight& l) { return l.intensity; },
            [](DirectionalLight& l, float v) {
                setChecked(l, [&](DirectionalLight& x) { x.intensity = v; });
            })
        .def_readwrite("cast_shadows", &DirectionalLight::castShadows)
        .def_property(
            "angular_radius", [](const DirectionalLight& l) { return l.angularRadius; },
            [](DirectionalLight& l, float v) {
                setChecked(l, [&](DirectionalLight& x) { x.angularRadius = v; });
            },
            "Radians of the disc the light comes from (the sun: 0.0047); > 0 softens "
            "its shadow by the penumbra that disc casts, 0 keeps the fixed PCF kernel.")
        .def("__repr__", [](const DirectionalLight& l) {
            return "<weft.DirectionalLight direction=" + vecRepr(l.direction) +
                   " color=" + vecRepr(l.color) + " intensity=" + std::to_string(l.intensity) +
                   (l.castShadows ? " shadows>" : ">");
        });

    auto attenuationOf = [](py::handle terms, float radius) {
        Attenuation a;
        auto t = numericArray(terms, "attenuation");
        if (t.ndim() != 1 || t.shape(0) != 3)
            throw InvalidArgument("attenuation must be (k_c, k_l, k_q)");
        a.constant = float(t.at(0));
        a.linear = float(t.at(1));
        a.quadratic = float(t.at(2));
        a.radius = radius;
        return a;
    };
    auto terms = [](const Attenuation& a) {
        return py::make_tuple(a.constant, a.linear, a.quadratic);
    };

    py::class_<PointLight>(
        m, "PointLight",
        "Light from a point in all directions. Attenuation a(d) = 1 / (k_c + k_l d + k_q d^2)\n"
        "(eq. 2.3), or max(0, 1 - d^2 / radius^2) (eq. 2.4) when radius > 0. Shadows use six\n"
        "perspective views.")
        .def(py::init([=](py::handle position, py::handle color, float intensity,
                          py::handle attenuation, float radius, bool shadows, float shadowNear) {
                 PointLight l;
                 l.position = toVec3(position, "position");
                 l.color = toVec3(color, "color");
                 l.intensity = intensity;
                 l.attenuation = attenuationOf(attenuation, radius);
                 l.castShadows = shadows;
                 l.shadowNear = shadowNear;
                 l.validate();
                 return l;
             }),
             py::arg("position") = py::make_tuple(0, 2, 0),
             py::arg("color") = py::make_tuple(1, 1, 1), py::arg("intensity") = 1.0f,
             py::arg("attenuation") = py::make_tuple(1, 0, 0), py::arg("radius") = 0.0f,
             py::arg("cast_shadows") = true, py::arg("shadow_near") = 0.05f,
             "A point light at `position` with `color` x `intensity`; attenuation (k_c, k_l, "
             "k_q) of 1 / (k_c + k_l d + k_q d²), or with radius > 0 the windowed falloff "
             "(SPEC §1.2); shadow_near: the near plane of its shadow views.")
        .WEFT_VEC3_PROPERTY(PointLight, "position", position)
        .WEFT_VEC3_PROPERTY(PointLight, "color", color)
        .def_property(
            "intensity", [](const PointLight& l) { return l.intensity; },
            [](PointLight& l, float v) { setChecked(l, [&](PointLight& x) { x.intensity = v; }); })
        .def_property(
            "attenuation", [=](const PointLight& l) { return terms(l.attenuation); },
            [=](PointLight& l, py::handle v) {
                const Attenuation a = attenuationOf(v, l.attenuation.radius);
                setChecked(l, [&](PointLight& x) { x.attenuation = a; });
            })
        .def_property(
            "radius", [](const PointLight& l) { return l.attenuation.radius; },
            [](PointLight& l, float v) {
                setChecked(l, [&](PointLight& x) { x.attenuation.radius = v; });
            })
        .def_readwrite("cast_shadows", &PointLight::castShadows)
        .def_property(
            "shadow_near", [](const PointLight& l) { return l.shadowNear; },
            [](PointLight& l, float v) { setChecked(l, [&](PointLight& x) { x.shadowNear = v; }); })
        .def(
            "attenuation_at",
            [](const PointLight& l, float d) {
                if (!(d >= 0.0f && std::isfinite(d)))
                    throw InvalidArgument(
                        "PointLight.attenuation_at: distance must be finite and >= 0, "
                        "got " +
                        std::to_string(d));
                return l.attenuation(d);
            },
            py::arg("distance"), "a(d) at a distance from the light.")
        .def("__repr__", [](const PointLight& l) {
            return "<weft.PointLight position=" + vecRepr(l.position) +
                   " color=" + vecRepr(l.color) + " intensity=" + std::to_string(l.intensity) +
                   (l.castShadows ? " shadows>" : ">");
        });

    py::class_<SpotLight>(
        m, "SpotLight",
        "Light into a cone around `direction`: full intensity within inner_angle of the axis,\n"
        "smooth falloff to zero at outer_angle (half-angles, radians), distance attenuation as\n"
        "PointLight, an optional `cookie` texture projected over the cone (RGB modulates).")
        .def(py::init([=](py::handle position, py::handle direction, py::handle color,
                          float intensity, float inner, float outer, py::handle attenuation,
                          float radius, std::shared_ptr<Texture> cookie, bool shadows,
                          float shadowNear) {
                 SpotLight l;
                 l.position = toVec3(position, "position");
                 l.direction = toVec3(direction, "direction");
                 l.color = toVec3(color, "color");
                 l.intensity = intensity;
                 l.innerAngle = inner;
                 l.outerAngle = outer;
                 l.attenuation = attenuationOf(attenuation, radius);
                 l.cookie = cookie;
                 l.castShadows = shadows;
                 l.shadowNear = shadowNear;
                 l.validate();
                 return l;
             }),
             py::arg("position") = py::make_tuple(0, 2, 0),
             py::arg("direction") = py::make_tuple(0, -1, 0),
             py::arg("color") = py::make_tuple(1, 1, 1), py::arg("intensity") = 1.0f,
             py::arg("inner_angle") = 0.35f, py::arg("outer_angle") = 0.5f,
             py::arg("attenuation") = py::make_tuple(1, 0, 0), py::arg("radius") = 0.0f,
             py::arg("cookie") = nullptr, py::arg("cast_shadows") = true,
             py::arg("shadow_near") = 0.05f,
             "A spot light at `position` shining along `direction`, full inside inner_angle "
             "and falling smoothly to zero at outer_angle (radians); attenuation and radius as "
             "PointLight; an optional cookie Texture projected through the cone.")
        .WEFT_VEC3_PROPERTY(SpotLight, "position", position)
        .WEFT_VEC3_PROPERTY(SpotLight, "direction", direction)
        .WEFT_VEC3_PROPERTY(SpotLight, "color", color)
        .def_property(
            "intensity", [](const SpotLight& l) { return l.intensity; },
            [](SpotLight& l, float v) { setChecked(l, [&](SpotLight& x) { x.intensity = v; }); })
        .def_property(
            "inner_angle", [](const SpotLight& l) { return l.innerAngle; },
            [](SpotLight& l, float v) { setChecked(l, [&](SpotLight& x) { x.innerAngle = v; }); })
        .def_property(
            "outer_angle", [](const SpotLight& l) { return l.outerAngle; },
            [](SpotLight& l, float v) { setChecked(l, [&](SpotLight& x) { x.outerAngle = v; }); })
        .def_property(
            "attenuation", [=](const SpotLight& l) { return terms(l.attenuation); },
            [=](SpotLight& l, py::handle v) {
                const Attenuation a = attenuationOf(v, l.attenuation.radius);
                setChecked(l, [&](SpotLight& x) { x.attenuation = a; });
            })
        .def_property(
            "radius", [](const SpotLight& l) { return l.attenuation.radius; },
            [](SpotLight& l, float v) {
                setChecked(l, [&](SpotLight& x) { x.attenuation.radius = v; });
            })
        .def_property(
            "cookie", [](const SpotLight& l) { return std::const_pointer_cast<Texture>(l.cookie); },
            [](SpotLight& l, std::shared_ptr<Texture> t) { l.cookie = t; })
        .def_readwrite("cast_shadows", &SpotLight::castShadows)
        .def_property(
            "shadow_near", [](const SpotLight& l) { return l.shadowNear; },
            [](SpotLight& l, float v) { setChecked(l, [&](SpotLight& x) { x.shadowNear = v; }); })
        .def("__repr__", [](const SpotLight& l) {
            return "<weft.SpotLight position=" + vecRepr(l.position) +
                   " direction=" + vecRepr(l.direction) + " color=" + vecRepr(l.color) +
                   " intensity=" + std::to_string(l.intensity) + (l.cookie ? " cookie" : "") +
                   (l.castShadows ? " shadows>" : ">");
        });
}

} // namespace weft::py_bind
