#include <weft/BtfRenderMaterial.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace weft {

namespace {

// (H, W, 3) floats -> linear RGBA8 texture of value * scale + offset.
TexturePtr texture(const std::vector<float>& values, int w, int h, float scale = 1.0f,
                   float offset = 0.0f) {
    ImageU8 img(w, h, 4);
    for (size_t t = 0; t < size_t(w) * size_t(h); ++t) {
        for (int c = 0; c < 3; ++c) {
            const float v = std::clamp(values[t * 3 + size_t(c)] * scale + offset, 0.0f, 1.0f);
            img.pixels[t * 4 + size_t(c)] = uint8_t(std::lround(v * 255.0f));
        }
        img.pixels[t * 4 + 3] = 255;
    }
    return std::make_shared<Texture>(std::move(img), false, true);
}

} // namespace

Material btfRenderMaterial(const BtfMaterialMaps& maps) {
    maps.validate();
    const int w = maps.width, h = maps.height;
    Material m;
    m.ka = m.kd = m.ks = glm::vec3(1.0f);
    m.shininess = std::max(maps.exponent, 1e-3f);
    m.texture = texture(maps.albedo, w, h);
    m.normalMap = texture(maps.normal, w, h, 0.5f, 0.5f);
    m.specularMap = maps.specular.empty() ? texture(std::vector<float>(maps.albedo.size(), 0.0f), w, h)
                                          : texture(maps.specular, w, h);
    m.ambientMap = texture(maps.ambient, w, h);
    m.specularVertexNormal = maps.flatSpecularNormal;
    m.validate();
    return m;
}

} // namespace weft
