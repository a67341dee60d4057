// BTF maps -> the renderer's material, and back as the shader decodes it. Both go through one
// encoding (Encoded) so that what btfDrawnMaps returns is what the textures hold.
#include <weft/BtfRenderMaterial.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace weft {

namespace {

constexpr float kMinExponent = 1e-3f;    // Material.shininess must be > 0 (pow(0, 0) is undefined)
constexpr float kTinyAlbedo = 1e-30f;    // stands for a drawn albedo of 0 under an ambient term
constexpr float kMinNormalScale = 1e-3f; // flat maps: 8-bit 0.5 decodes to 0.0039 s, not 0

uint8_t quantise(float v) { return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

float decode(uint8_t q) { return float(q) / 255.0f; }

/// Per-channel maximum of an (H, W, 3) map, at least 0.
glm::vec3 channelMax(const std::vector<float>& values) {
    glm::vec3 m(0.0f);
    for (size_t i = 0; i < values.size(); ++i) m[int(i % 3)] = std::max(m[int(i % 3)], values[i]);
    return m;
}

/// Per-channel scale for the specular map: the maximum, unless the brightest texels lie more
/// than kSpecularFence times above the 99th percentile of the non-zero values, in which case
/// they are clipped to that fence. One needle lobe (k ~ 10^3 where the rest is ~0.1) would
/// otherwise set a scale that rounds every other texel's k to 0; the fence costs those rare
/// texels part of a lobe the samples barely see, and keeps 99% of them resolved to 1/510 of at
/// most 4x their own range.
constexpr float kSpecularFence = 4.0f;
glm::vec3 specularScale(const std::vector<float>& values) {
    glm::vec3 out = channelMax(values);
    for (int c = 0; c < 3; ++c) {
        std::vector<float> v;
        for (size_t i = size_t(c); i < values.size(); i += 3)
            if (values[i] > 0.0f) v.push_back(values[i]);
        if (v.size() < 100) continue; // too few for a percentile: the maximum
        const size_t k = v.size() * 99 / 100;
        std::nth_element(v.begin(), v.begin() + long(k), v.end());
        out[c] = std::min(out[c], kSpecularFence * v[k]);
    }
    return out;
}

/// The textures' bytes (RGBA8, alpha 255 unless it holds the exponent) and the material's scalars.
struct Encoded {
    int width = 0, height = 0;
    std::vector<uint8_t> base, normal, specular, ambient;
    glm::vec3 kd{0.0f}, ka{0.0f}, ks{0.0f};
    float normalScale = 1.0f;
    bool hasSpecular = false;
    bool exponentInAlpha = false;
    float shininess = 1.0f, shininessMax = 0.0f;
};

/// RGB of (H, W, 3) `values` as value / scale per channel (0 where the scale is 0).
std::vector<uint8_t> scaled(const std::vector<float>& values, glm::vec3 scale) {
    std::vector<uint8_t> out(values.size() / 3 * 4, 255);
    for (size_t t = 0; t < values.size() / 3; ++t)
        for (int c = 0; c < 3; ++c)
            out[t * 4 + size_t(c)] =
                scale[c] > 0.0f ? quantise(values[t * 3 + size_t(c)] / scale[c]) : uint8_t(0);
    return out;
}

/// The exponent map in the specular texture's alpha, log-encoded between the extremes of the
/// texels that draw a highlight (a texel with specular 0 needs no exponent precision).
void encodeExponentMap(const BtfMaterialMaps& maps, Encoded& e) {
    const size_t texels = maps.exponentMap.size();
    float lo = INFINITY, hi = 0.0f;
    for (int pass = 0; pass < 2 && !(lo <= hi); ++pass)
        for (size_t t = 0; t < texels; ++t) {
            const uint8_t* s = &e.specular[t * 4];
            if (pass == 0 && s[0] == 0 && s[1] == 0 && s[2] == 0) continue;
            const float x = std::max(maps.exponentMap[t], kMinExponent);
            lo = std::min(lo, x);
            hi = std::max(hi, x);
        }
    e.shininess = lo;
    if (!(hi > lo)) return; // one exponent: the scalar shininess, alpha unused
    e.exponentInAlpha = true;
    e.shininessMax = hi;
    const float range = std::log(hi / lo);
    for (size_t t = 0; t < texels; ++t) {
        const float x = std::max(maps.exponentMap[t], kMinExponent);
        e.specular[t * 4 + 3] = quantise(std::log(x / lo) / range);
    }
}

Encoded encode(const BtfMaterialMaps& maps) {
    maps.validate();
    Encoded e;
    e.width = maps.width;
    e.height = maps.height;
    const size_t texels = size_t(maps.width) * size_t(maps.height);
    e.kd = channelMax(maps.albedo);
    e.base = scaled(maps.albedo, e.kd);
    std::vector<float> constant(texels * 3);
    for (size_t i = 0; i < constant.size(); ++i)
        constant[i] = std::max(maps.albedo[i], 0.0f) * maps.ambient[i];
    e.ka = channelMax(constant);
    e.ambient = scaled(constant, e.ka);
    // x and y over their largest magnitude: fitted normals are mostly mildly tilted, and the
    // angular step of an 8-bit normal shrinks with the scale (Material::normalScale)
    e.normalScale = kMinNormalScale;
    for (size_t i = 0; i < maps.normal.size(); ++i)
        if (i % 3 != 2) e.normalScale = std::max(e.normalScale, std::fabs(maps.normal[i]));
    std::vector<float> half(texels * 3);
    for (size_t i = 0; i < half.size(); ++i)
        half[i] = maps.normal[i] / (i % 3 == 2 ? 1.0f : e.normalScale) * 0.5f + 0.5f;
    e.normal = scaled(half, glm::vec3(1.0f));
    e.shininess = std::max(maps.exponent, kMinExponent);
    e.hasSpecular = !maps.specular.empty();
    if (e.hasSpecular) {
        e.ks = specularScale(maps.specular);
        e.specular = scaled(maps.specular, e.ks);
        if (!maps.exponentMap.empty()) encodeExponentMap(maps, e);
    }
    return e;
}

TexturePtr texture(const std::vector<uint8_t>& rgba, int w, int h) {
    ImageU8 img(w, h, 4);
    img.pixels = rgba;
    return std::make_shared<Texture>(std::move(img), false, true);
}

} // namespace

Material btfRenderMaterial(const BtfMaterialMaps& maps) {
    const Encoded e = encode(maps);
    const int w = e.width, h = e.height;
    Material m;
    m.kd = e.kd;
    m.ka = e.ka;
    m.ks = e.ks;
    m.baseColor = glm::vec3(1.0f);
    m.shininess = e.shininess;
    m.texture = texture(e.base, w, h);
    m.normalMap = texture(e.normal, w, h);
    m.normalScale = e.normalScale;
    m.ambientMap = texture(e.ambient, w, h);
    m.ambientMapIsRadiance = true;
    if (e.hasSpecular) m.specularMap = texture(e.specular, w, h);
    m.shininessMax = e.exponentInAlpha ? e.shininessMax : 0.0f;
    m.specularVertexNormal = maps.flatSpecularNormal;
    m.validate();
    return m;
}

BtfMaterialMaps btfDrawnMaps(const BtfMaterialMaps& maps) {
    const Encoded e = encode(maps);
    const size_t texels = size_t(e.width) * size_t(e.height);
    BtfMaterialMaps d;
    d.width = e.width;
    d.height = e.height;
    d.flatSpecularNormal = maps.flatSpecularNormal;
    d.clampDiffuse = true;
    d.exponent = e.shininess;
    d.normal.resize(texels * 3);
    d.albedo.resize(texels * 3);
    d.ambient.resize(texels * 3);
    if (e.hasSpecular) d.specular.resize(texels * 3);
    // The shader's exponent: shininess * 2^(alpha * log2(max / shininess)), FrameData's float.
    const float log2Ratio = e.exponentInAlpha ? std::log2(e.shininessMax / e.shininess) : 0.0f;
    if (e.hasSpecular && !maps.exponentMap.empty()) d.exponentMap.resize(texels);
    for (size_t t = 0; t < texels; ++t) {
        glm::vec3 m(0.0f);
        for (int c = 0; c < 3; ++c) m[c] = decode(e.normal[t * 4 + size_t(c)]) * 2.0f - 1.0f;
        m = glm::normalize(m * glm::vec3(e.normalScale, e.normalScale, 1.0f));
        for (int c = 0; c < 3; ++c) {
            const size_t i = t * 3 + size_t(c);
            d.normal[i] = m[c];
            const float rho = e.kd[c] * decode(e.base[t * 4 + size_t(c)]);
            const float constant = e.ka[c] * decode(e.ambient[t * 4 + size_t(c)]);
            d.albedo[i] = rho > 0.0f ? rho : (constant > 0.0f ? kTinyAlbedo : 0.0f);
            d.ambient[i] = d.albedo[i] > 0.0f ? constant / d.albedo[i] : 0.0f;
            if (e.hasSpecular) d.specular[i] = e.ks[c] * decode(e.specular[t * 4 + size_t(c)]);
        }
        if (!d.exponentMap.empty()) {
            const float alpha = decode(e.specular[t * 4 + 3]);
            d.exponentMap[t] =
                e.exponentInAlpha
                    ? std::min(e.shininess * std::exp2(alpha * log2Ratio), e.shininessMax)
                    : e.shininess;
        }
    }
    d.validate();
    return d;
}

} // namespace weft
