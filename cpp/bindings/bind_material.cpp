// Bindings of Texture and Material.
#include <cmath>
#include <string>

#include <pybind11/stl.h>

#include <weft/Scene.h>

#include "Convert.h"
#include "ValueProperty.h"

namespace weft::py_bind {
namespace {

const char* const kSpecularModels[] = {"blinn_phong", "ggx"};

std::string specularModelName(SpecularModel m) { return kSpecularModels[int(m)]; }

SpecularModel specularModelOf(const std::string& name) {
    for (int i = 0; i < 2; ++i)
        if (name == kSpecularModels[i]) return SpecularModel(i);
    throw InvalidArgument("Material.specular_model must be 'blinn_phong' or 'ggx' (got '" + name +
                          "')");
}

} // namespace

void bindMaterial(py::module_& m) {
    py::class_<Texture, std::shared_ptr<Texture>>(
        m, "Texture",
        "An RGBA8 texture (sRGB colour by default), uploaded to the GPU on first use.")
        .def(py::init([](py::handle image, bool srgb, bool mipmaps) {
                 return std::make_shared<Texture>(fromNumpy(image), srgb, mipmaps);
             }),
             py::arg("image"), py::arg("srgb") = true, py::arg("mipmaps") = true,
             "A texture from a uint8 (H, W, 4) or (H, W, 3) image; srgb: the colours are sRGB- "
             "encoded (base colour), False for data (normal, specular maps).")
        .def_static(
            "load",
            [](const std::string& path, bool srgb, bool mipmaps) {
                return std::make_shared<Texture>(loadPng(path), srgb, mipmaps);
            },
            py::arg("path"), py::arg("srgb") = true, py::arg("mipmaps") = true,
            "Loads an image file as a Texture (srgb, mipmaps as for the constructor). Raises "
            "IoError naming the file.")
        .def_property_readonly("width", [](const Texture& t) { return t.image().width; })
        .def_property_readonly("height", [](const Texture& t) { return t.image().height; })
        .def_property_readonly("srgb", &Texture::srgb)
        .def_property_readonly("mipmaps", &Texture::mipmaps)
        .def_property_readonly("image", [](const Texture& t) { return toNumpy(t.image()); })
        .def("__repr__", [](const Texture& t) {
            return "<weft.Texture " + std::to_string(t.image().width) + "x" +
                   std::to_string(t.image().height) + (t.srgb() ? " sRGB" : " linear") + ">";
        });

    py::class_<Material>(
        m, "Material",
        "Blinn-Phong material: P = (I_A K_A + I_D K_D a) T + I_S K_S a (SPEC eq. 2.10).\n"
        "normal_map: tangent-space normal map (a linear Texture; x right, y up in the image,\n"
        "(128, 128, 255) flat); specular_map: its RGB multiplies ks; alpha_cutoff > 0 discards\n"
        "fragments whose base-texture alpha is below it, in the image and the shadow maps;\n"
        "ambient_map (linear) replaces the scene's ambient per texel; specular_vertex_normal\n"
        "evaluates the highlight with the unmapped normal (BTF n_s = (0, 0, 1), eq. 4.30);\n"
        "specular_model: 'blinn_phong' (the seed's highlight K_S (n.h)^s and Schlick-weighted\n"
        "reflection) or 'ggx' (a GGX coat, what a path tracer draws).")
        .def(py::init([](py::handle ka, py::handle kd, py::handle ks, float shininess,
                         py::handle baseColor, std::shared_ptr<Texture> texture,
                         std::shared_ptr<Texture> normalMap, std::shared_ptr<Texture> specularMap,
                         float alphaCutoff, std::shared_ptr<Texture> ambientMap,
                         bool specularVertexNormal, bool twoSided, py::handle reflectivity,
                         float environmentDiffuse, bool dynamicReflection, bool glossInAlpha,
                         bool phantom, const std::string& specularModel) {
                 Material mat;
                 mat.ka = toVec3(ka, "ka");
                 mat.kd = toVec3(kd, "kd");
                 mat.ks = toVec3(ks, "ks");
                 mat.shininess = shininess;
                 mat.baseColor = toVec3(baseColor, "base_color");
                 mat.texture = texture;
                 mat.normalMap = normalMap;
                 mat.specularMap = specularMap;
                 mat.alphaCutoff = alphaCutoff;
                 mat.ambientMap = ambientMap;
                 mat.specularVertexNormal = specularVertexNormal;
                 mat.twoSided = twoSided;
                 mat.reflectivity = toVec3(reflectivity, "reflectivity");
                 mat.environmentDiffuse = environmentDiffuse;
                 mat.dynamicReflection = dynamicReflection;
                 mat.glossInAlpha = glossInAlpha;
                 mat.phantom = phantom;
                 mat.specularModel = specularModelOf(specularModel);
                 mat.validate();
                 return mat;
             }),
             py::arg("ka") = py::make_tuple(1, 1, 1), py::arg("kd") = py::make_tuple(1, 1, 1),
             py::arg("ks") = py::make_tuple(0, 0, 0), py::arg("shininess") = 32.0f,
             py::arg("base_color") = py::make_tuple(1, 1, 1), py::arg("texture") = nullptr,
             py::arg("normal_map") = nullptr, py::arg("specular_map") = nullptr,
             py::arg("alpha_cutoff") = 0.0f, py::arg("ambient_map") = nullptr,
             py::arg("specular_vertex_normal") = false, py::arg("two_sided") = false,
             py::arg("reflectivity") = py::make_tuple(0, 0, 0),
             py::arg("environment_diffuse") = 0.0f, py::arg("dynamic_reflection") = false,
             py::arg("gloss_in_alpha") = false, py::arg("phantom") = false,
             py::arg("specular_model") = specularModelName(Material{}.specularModel),
             "A material with the coefficients, textures and flags the class description lists "
             "(colours as RGB triples in [0, 1] or more).")
        .WEFT_VEC3_PROPERTY(Material, "ka", ka)
        .WEFT_VEC3_PROPERTY(Material, "kd", kd)
        .WEFT_VEC3_PROPERTY(Material, "ks", ks)
        .WEFT_VEC3_PROPERTY(Material, "base_color", baseColor)
        .def_property(
            "shininess", [](const Material& x) { return x.shininess; },
            [](Material& x, float v) { setChecked(x, [&](Material& y) { y.shininess = v; }); })
        .def_property(
            "texture",
            [](const Material& x) { return std::const_pointer_cast<Texture>(x.texture); },
            [](Material& x, std::shared_ptr<Texture> t) { x.texture = t; })
        .def_property(
            "normal_map",
            [](const Material& x) { return std::const_pointer_cast<Texture>(x.normalMap); },
            [](Material& x, std::shared_ptr<Texture> t) {
                setChecked(x, [&](Material& y) { y.normalMap = t; });
            })
        .def_property(
            "specular_map",
            [](const Material& x) { return std::const_pointer_cast<Texture>(x.specularMap); },
            [](Material& x, std::shared_ptr<Texture> t) { x.specularMap = t; })
        .def_property(
            "ambient_map",
            [](const Material& x) { return std::const_pointer_cast<Texture>(x.ambientMap); },
            [](Material& x, std::shared_ptr<Texture> t) {
                setChecked(x, [&](Material& y) { y.ambientMap = t; });
            })
        .def_readwrite("specular_vertex_normal", &Material::specularVertexNormal)
        .def_readwrite("two_sided", &Material::twoSided,
                       "Draw both faces; the back face uses the flipped normal (cloth: always).")
        .WEFT_VEC3_PROPERTY(Material, "reflectivity", reflectivity)
        .def_property(
            "environment_diffuse", [](const Material& x) { return x.environmentDiffuse; },
            [](Material& x, float v) {
                setChecked(x, [&](Material& y) { y.environmentDiffuse = v; });
            })
        .def_property(
            "dynamic_reflection", [](const Material& x) { return x.dynamicReflection; },
            [](Material& x, bool v) {
                setChecked(x, [&](Material& y) { y.dynamicReflection = v; });
            },
            "Reflect a cube captured from this instance's origin (one per scene).")
        .def_property(
            "gloss_in_alpha", [](const Material& x) { return x.glossInAlpha; },
            [](Material& x, bool v) { setChecked(x, [&](Material& y) { y.glossInAlpha = v; }); },
            "The base texture's alpha is the decal's gloss (SPEC 4.4): environment light\n"
            "= T * lerp(specular, diffuse, alpha).")
        .def_property(
            "phantom", [](const Material& x) { return x.phantom; },
            [](Material& x, bool v) { setChecked(x, [&](Material& y) { y.phantom = v; }); },
            "A stand-in for a real object (AR): shows the background image times the\n"
            "shadows it receives (lit / unshadowed diffuse light), nothing else.")
        .def_property(
            "specular_model", [](const Material& x) { return specularModelName(x.specularModel); },
            [](Material& x, const std::string& v) { x.specularModel = specularModelOf(v); },
            "'blinn_phong': the seed's highlight K_S (n.h)^s (unnormalised) and environment\n"
            "reflection weighted by Schlick's F(n.v). 'ggx': a GGX coat of alpha =\n"
            "sqrt(2 / (shininess + 2)) and F0 = reflectivity (or else 8 ks / (shininess + 2)):\n"
            "the lights' highlight is its microfacet lobe (Smith masking, the dielectric's\n"
            "Fresnel), so a light and an environment's sun agree, and the reflection is\n"
            "weighted by its directional albedo.")
        .def_property(
            "alpha_cutoff", [](const Material& x) { return x.alphaCutoff; },
            [](Material& x, float v) { setChecked(x, [&](Material& y) { y.alphaCutoff = v; }); })
        .def_property(
            "normal_scale", [](const Material& x) { return x.normalScale; },
            [](Material& x, float v) { setChecked(x, [&](Material& y) { y.normalScale = v; }); },
            "Scale of the normal map's x and y before normalisation (glTF), > 0.")
        .def_property(
            "shininess_max", [](const Material& x) { return x.shininessMax; },
            [](Material& x, float v) { setChecked(x, [&](Material& y) { y.shininessMax = v; }); },
            "> 0: the specular map's alpha a holds the exponent per texel,\n"
            "shininess * (shininess_max / shininess)^a; 0: unused.")
        .def_property(
            "ambient_map_is_radiance", [](const Material& x) { return x.ambientMapIsRadiance; },
            [](Material& x, bool v) {
                setChecked(x, [&](Material& y) { y.ambientMapIsRadiance = v; });
            },
            "The ambient term is ka * ambient_map (not times T or the scene's ambient).")
        .def("__repr__", [](const Material& x) {
            return "<weft.Material kd=" + vecRepr(x.kd) + " ks=" + vecRepr(x.ks) +
                   " shininess=" + std::to_string(x.shininess) + (x.texture ? " textured>" : ">");
        });
}

} // namespace weft::py_bind
