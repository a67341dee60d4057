#pragma once
// Blinn-Phong material of SPEC eq. 2.10: P = (I_A K_A + I_D K_D a) * T + I_S K_S a, or with
// specularModel = Ggx a GGX coat over the same diffuse terms.
#include <glm/glm.hpp>

#include <weft/Texture.h>

namespace weft {

/// A material's specular terms (Material::specularModel).
enum class SpecularModel {
    /// The seed's: the lights' highlight K_S (n.h)^s (SPEC eq. 2.10: unnormalised, no Fresnel,
    /// masking or n.l), the environment reflection weighted by Schlick's F(n.v) (SPEC §1.3).
    BlinnPhong,
    /// A GGX coat, what a path tracer draws: the lights' highlight is the microfacet lobe whose
    /// prefiltered radiance the environment reflection reads (so a light and an environment's
    /// sun give one highlight), K_D's light plus
    ///   pi L (n.l) F(v.h) D(n.h) G1(n.l) G1(n.v) / (4 (n.l)(n.v)),
    /// GGX D and separable Smith G1 of alpha = sqrt(2 / (s + 2)), Schlick's F of F0 =
    /// `reflectivity`, or without one 8 K_S / (s + 2) (the F0 whose peak at normal incidence is
    /// the Blinn-Phong highlight's K_S), with the dielectric's exact Fresnel; and the reflection
    /// is weighted by the coat's directional albedo (split sum, Karis 2013) instead of F(n.v).
    /// Walter et al. 2007, "Microfacet models for refraction through rough surfaces".
    Ggx,
};

struct Material {
    glm::vec3 ka{1.0f};        // ambient coefficient K_A
    glm::vec3 kd{1.0f};        // diffuse coefficient K_D
    glm::vec3 ks{0.0f};        // specular coefficient K_S
    float shininess = 32.0f;   // Blinn-Phong exponent n, > 0
    glm::vec3 baseColor{1.0f}; // multiplies the texture: T = baseColor * texture(uv)
    TexturePtr texture;        // base-colour texture (sRGB), none = white
    /// Per-texel exponent (a fitted BTF's exponent map, SPEC §3.5): when > 0, the specular
    /// map's alpha a holds the exponent log-encoded, e = shininess (shininessMax / shininess)^a
    /// (8 bits spread the ratio's logarithm evenly: constant relative precision, which is what
    /// the lobe width ~ 1/sqrt(e) needs). Needs a specular map and shininessMax >= shininess.
    /// 0 = the specular map's alpha is unused and `shininess` holds everywhere.
    float shininessMax = 0.0f;
    /// Tangent-space normal map (linear, not sRGB): n = texel / 255 * 2 - 1 (eq. 2.11) in the
    /// frame of computeTangents(); none = the interpolated vertex normal.
    TexturePtr normalMap;
    /// Scale of the normal map's x and y before normalisation (glTF's normalTexture.scale),
    /// > 0: n = normalise((texel / 255 * 2 - 1) * (s, s, 1)). A fitted BTF's mildly tilted
    /// normals stored as x / s, y / s use all 8 bits (s = their largest |x|, |y|).
    float normalScale = 1.0f;
    /// Specular map: its RGB (linear) multiplies K_S per texel; none = 1.
    TexturePtr specularMap;
    /// Ambient map (linear): its RGB replaces the scene's ambient I_A per texel (a BTF fit's
    /// I_A map, SPEC §3.2); none = the scene's ambient.
    TexturePtr ambientMap;
    /// The ambient map is the ambient radiance itself: the ambient term is K_A * map, not
    /// multiplied by T (a fitted BTF's constant term ρ·a, which 8 bits hold far better than
    /// the product of two quantised maps when ρ is tiny and a large). Needs an ambient map.
    bool ambientMapIsRadiance = false;
    /// Specular highlights use the interpolated vertex normal instead of the normal-mapped one
    /// (the BTF fit's n_s = (0, 0, 1), seed eq. 4.30).
    bool specularVertexNormal = false;
    /// Alpha test: fragments whose base-texture alpha is below this are discarded, also from
    /// shadow maps (holes cast holes). 0 = opaque.
    float alphaCutoff = 0.0f;
    /// Both faces are drawn; the back face is shaded with the flipped normal (cloth).
    bool twoSided = false;
    /// Environment reflection (SPEC §1.3, §4.4), used when the scene has an environment: F0 of
    /// Schlick's Fresnel per channel in [0, 1]; the reflection is the GGX-prefiltered
    /// environment in R = 2(n.v)n - v at the roughness of `shininess` (Renderer.h). 0 = none.
    glm::vec3 reflectivity{0.0f};
    /// Weight of the environment's diffuse light K_D T E(n) / pi (SH9 irradiance), >= 0.
    float environmentDiffuse = 0.0f;
    /// The reflection (weighted by `reflectivity`'s Fresnel) is a cube captured from this
    /// instance's origin (RenderSettings::probeSize), not the environment: one capture per scene,
    /// from the first instance with this flag; it is captured again only when the scene changes.
    bool dynamicReflection = false;
    /// The seed's decal material (SPEC §4.4): the base texture's alpha is the gloss, not
    /// opacity; the environment lighting becomes T * lerp(specular, diffuse, alpha). Not with
    /// an alpha cutoff.
    bool glossInAlpha = false;
    /// A phantom (SPEC §4.5, AR): a stand-in for a real object, invisible except for the shadows
    /// it receives. It shows the background (Scene::setBackgroundImage, else the background
    /// colour) times its lit / unshadowed diffuse light, and hides what lies behind it.
    bool phantom = false;
    /// The specular terms: the seed's, or a GGX coat.
    SpecularModel specularModel = SpecularModel::BlinnPhong;

    /// Throws InvalidArgument for negative or non-finite coefficients or shininess <= 0.
    void validate() const;
};

} // namespace weft
