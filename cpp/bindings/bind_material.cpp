// Bindings of Texture and Material.
#include <cmath>
#include <string>

#include <pybind11/stl.h>

#include <weft/Scene.h>

#include "Convert.h"
#include "Fields.h"

namespace weft::py_bind {
namespace {

const char* const kSpecularModels[] = {"blinn_phong", "ggx"};

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

    const auto fields = std::make_tuple(
        field("ka", &Material::ka), field("kd", &Material::kd), field("ks", &Material::ks),
        field("shininess", &Material::shininess), field("base_color", &Material::baseColor),
        field("texture", &Material::texture), field("normal_map", &Material::normalMap),
        field("specular_map", &Material::specularMap),
        field("alpha_cutoff", &Material::alphaCutoff), field("ambient_map", &Material::ambientMap),
        field("specular_vertex_normal", &Material::specularVertexNormal),
        field("two_sided", &Material::twoSided,
              "Draw both faces; the back face uses the flipped normal (cloth: always)."),
        field("reflectivity", &Material::reflectivity),
        field("environment_diffuse", &Material::environmentDiffuse),
        field("dynamic_reflection", &Material::dynamicReflection,
              "Reflect a cube captured from this instance's origin (one per scene)."),
        field("gloss_in_alpha", &Material::glossInAlpha,
              "The base texture's alpha is the decal's gloss (SPEC 4.4): environment light\n"
              "= T * lerp(specular, diffuse, alpha)."),
        field("phantom", &Material::phantom,
              "A stand-in for a real object (AR): shows the background image times the\n"
              "shadows it receives (lit / unshadowed diffuse light), nothing else."),
        enumField(
            "specular_model", &Material::specularModel, kSpecularModels,
            "'blinn_phong': the seed's highlight K_S (n.h)^s (unnormalised) and environment\n"
            "reflection weighted by Schlick's F(n.v). 'ggx': a GGX coat of alpha =\n"
            "sqrt(2 / (shininess + 2)) and F0 = reflectivity (or else 8 ks / (shininess + 2)):\n"
            "the lights' highlight is its microfacet lobe (Smith masking, the dielectric's\n"
            "Fresnel), so a light and an environment's sun agree, and the reflection is\n"
            "weighted by its directional albedo."),
        field("normal_scale", &Material::normalScale,
              "Scale of the normal map's x and y before normalisation (glTF), > 0."),
        field("shininess_max", &Material::shininessMax,
              "> 0: the specular map's alpha a holds the exponent per texel,\n"
              "shininess * (shininess_max / shininess)^a; 0: unused."),
        field("ambient_map_is_radiance", &Material::ambientMapIsRadiance,
              "The ambient term is ka * ambient_map (not times T or the scene's ambient)."));
    py::class_<Material> material(
        m, "Material",
        "Blinn-Phong material: P = (I_A K_A + I_D K_D a) T + I_S K_S a (SPEC eq. 2.10).\n"
        "normal_map: tangent-space normal map (a linear Texture; x right, y up in the image,\n"
        "(128, 128, 255) flat); specular_map: its RGB multiplies ks; alpha_cutoff > 0 discards\n"
        "fragments whose base-texture alpha is below it, in the image and the shadow maps;\n"
        "ambient_map (linear) replaces the scene's ambient per texel; specular_vertex_normal\n"
        "evaluates the highlight with the unmapped normal (BTF n_s = (0, 0, 1), eq. 4.30);\n"
        "specular_model: 'blinn_phong' (the seed's highlight K_S (n.h)^s and Schlick-weighted\n"
        "reflection) or 'ggx' (a GGX coat, what a path tracer draws).");
    defInit(material, validated<Material>, fields,
            "A material with the coefficients, textures and flags the class description lists "
            "(colours as RGB triples in [0, 1] or more).");
    defProperties(material, fields);
    material.def("__repr__", [](const Material& x) {
        return "<weft.Material kd=" + vecRepr(x.kd) + " ks=" + vecRepr(x.ks) +
               " shininess=" + std::to_string(x.shininess) + (x.texture ? " textured>" : ">");
    });
}

} // namespace weft::py_bind
