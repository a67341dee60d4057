// Bindings of hair in scenes and the renderer's hair settings (SPEC §5).
#include <cstring>

#include <pybind11/stl.h>

#include <weft/Debug.h>
#include <weft/Renderer.h>

#include "Convert.h"
#include "Fields.h"

namespace weft::py_bind {

namespace {

const char* const kPrimitives[] = {"lines", "ribbons"}; // HairPrimitive's order

// Python names of OitWeight, in its order (7 .. 10); 'eq7' .. 'eq10' are accepted too.
const char* const kOitWeightNames[] = {"near_quadratic", "near_cubic", "far_quartic", "ndc_cubic"};

OitWeight weightOf(const std::string& s) {
    for (int eq = 7; eq <= 10; ++eq)
        if (s == kOitWeightNames[eq - 7] || s == "eq" + std::to_string(eq)) return OitWeight(eq);
    throw InvalidArgument("hair_oit_weight must be 'near_quadratic', 'near_cubic', 'far_quartic' "
                          "or 'ndc_cubic' (or 'eq7' .. 'eq10'; got '" +
                          s + "')");
}

} // namespace

void bindHairRender(py::module_& m) {
    py::class_<Scene, std::shared_ptr<Scene>> scene(m.attr("Scene"));
    scene
        .def(
            "add_hair",
            [](Scene& s, std::shared_ptr<HairStrands> strands, std::optional<HairMaterial> material,
               py::object transform, bool castShadows) {
                const glm::mat4 t =
                    transform.is_none() ? glm::mat4(1.0f) : toMat4(transform, "transform");
                return s.addHair(strands, material.value_or(HairMaterial{}), t, castShadows);
            },
            py::arg("strands"), py::arg("material") = py::none(), py::arg("transform") = py::none(),
            py::arg("cast_shadows") = true,
            "Adds hair (weft.HairStrands, drawn with a weft.HairMaterial); returns its hair id.\n"
            "The strands must not change afterwards: the renderer uploads them once.")
        .def(
            "set_hair_transform",
            [](Scene& s, uint32_t id, py::handle t) {
                s.setHairTransform(id, toMat4(t, "transform"));
            },
            py::arg("id"), py::arg("transform"),
            "Sets the 4x4 model matrix of the hair instance with this id.")
        .def("set_hair_material", &Scene::setHairMaterial, py::arg("id"), py::arg("material"),
             "Replaces the HairMaterial of the hair instance with this id.")
        .def_property_readonly("hair_count", [](const Scene& s) { return s.hairs().size(); });

    using S = RenderSettings;
    py::class_<Renderer> renderer(m.attr("Renderer"));
    defSettingProperties(
        renderer, [](const Renderer& r) { return r.settings(); },
        [](Renderer& r, const S& s) { r.setSettings(s); },
        std::make_tuple(
            enumField(
                "hair_primitive", &S::hairPrimitive, kPrimitives,
                "'lines' (1 pixel) or 'ribbons' (camera-facing, hair_width * thickness wide)."),
            field("hair_width", &S::hairWidth,
                  "Ribbon width per unit of strand thickness (world units)."),
            field("hair_dom", &S::hairDeepOpacity,
                  "Deep opacity maps for shadow-casting directional lights (else the shadow "
                  "map)."),
            field<std::string, S>(
                "hair_dom_spacing",
                [](const S& s) { return std::string(s.hairDomLogSpacing ? "log" : "linear"); },
                [](S& s, const std::string& k) {
                    if (k != "linear" && k != "log")
                        throw InvalidArgument("hair_dom_spacing must be 'linear' or 'log' (got '" +
                                              k + "')");
                    s.hairDomLogSpacing = k == "log";
                },
                "DOM layer spacing: 'linear' (d, 2d, 3d) or 'log' (d, 3d, 7d)."),
            field("hair_dom_layer_size", &S::hairDomLayerSize,
                  "DOM layer size d (world units); 0: the hair's depth extent / 3 (log: / 7)."),
            field("hair_dom_size", &S::hairDomSize,
                  "Texels per side of each deep opacity map, in [16, 8192]."),
            field("hair_transparency", &S::hairTransparency,
                  "Weighted blended OIT for hair with transparency > 0 (else drawn opaque)."),
            field<std::string, S>(
                "hair_oit_weight",
                [](const S& s) { return std::string(kOitWeightNames[int(s.hairOitWeight) - 7]); },
                [](S& s, const std::string& v) { s.hairOitWeight = weightOf(v); },
                "WBOIT depth weight (McGuire & Bavoil 2013, eq. 7-10): 'near_quadratic', "
                "'near_cubic', 'far_quartic' or 'ndc_cubic' ('eq7' .. 'eq10' also accepted).")));
    renderer.def(
        "hair_dom_map",
        [](const Renderer& r, int light) {
            const HairDomInfo i = debug::hairDeepOpacity(r, light);
            py::dict d;
            d["opacity"] = arrayOf<float>(i.texels, {i.size, i.size, 4});
            d["direction"] = fromVec3(i.direction);
            d["center"] = fromVec3(i.center);
            d["extent"] = i.extent;
            d["near"] = i.zNear;
            d["far"] = i.zFar;
            d["layer_size"] = i.layerSize;
            d["spacing"] = i.logSpacing ? "log" : "linear";
            d["resolution"] = i.size;
            return d;
        },
        py::arg("light_index") = 0,
        "The last frame's deep opacity map of a directional light: 'opacity' (size, size, 4):\n"
        "layers 0-2 (each including those before) and z0 as stored depth (near..far -> 0..1,\n"
        "1 where no hair), with the light grid (direction, center, extent, resolution) of\n"
        "weft.reference.hair_shadow.LightGrid, near/far and layer_size d in world units.");
}

} // namespace weft::py_bind
