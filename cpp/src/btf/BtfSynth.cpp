// Synthetic BTF rendering with optional cast shadows from a height field.
#include <weft/BtfSynth.h>
#include <weft/Error.h>

#include <cmath>

#include "btf/BtfModel.h"
#include "btf/BtfParallel.h"

namespace weft {

namespace {

float sampleHeight(const std::vector<float>& h, int w, int ht, float x, float y, bool wrap) {
    if (!wrap) {
        x = std::min(std::max(x, 0.0f), float(w - 1));
        y = std::min(std::max(y, 0.0f), float(ht - 1));
    }
    const float fx = std::floor(x), fy = std::floor(y);
    const float tx = x - fx, ty = y - fy;
    auto at = [&](int ix, int iy) {
        ix = ((ix % w) + w) % w;
        iy = ((iy % ht) + ht) % ht;
        return h[size_t(iy) * size_t(w) + size_t(ix)];
    };
    const int ix = int(fx), iy = int(fy);
    return (at(ix, iy) * (1 - tx) + at(ix + 1, iy) * tx) * (1 - ty) +
           (at(ix, iy + 1) * (1 - tx) + at(ix + 1, iy + 1) * tx) * ty;
}

// 1 where the ray from the texel towards l stays above the height field. Image x grows with +x,
// image rows grow with -y.
void visibility(const BtfShadowing& sh, int w, int h, float hmax, glm::vec3 l, size_t begin,
                size_t end, uint8_t* vis) {
    const float horiz = std::sqrt(l.x * l.x + l.y * l.y);
    for (size_t i = begin; i < end; ++i) {
        vis[i] = 1;
        if (horiz < 1e-6f) continue;
        const float dx = l.x / horiz, dy = -l.y / horiz, rise = l.z / horiz;
        const float x0 = float(i % size_t(w)), y0 = float(i / size_t(w));
        const float h0 = sh.height[i];
        for (float t = 0.5f;; t += 0.5f) {
            const float ray = h0 + rise * t;
            if (ray > hmax) break;
            const float x = x0 + dx * t, y = y0 + dy * t;
            if (!sh.wrap && (x < 0 || y < 0 || x > float(w - 1) || y > float(h - 1))) break;
            if (sampleHeight(sh.height, w, h, x, y, sh.wrap) > ray + 1e-4f) {
                vis[i] = 0;
                break;
            }
        }
    }
}

} // namespace

BtfSamples renderBtf(const BtfMaterialMaps& maps, const std::vector<BtfAngles>& angles,
                     const BtfShadowing& shadowing, int threads) {
    maps.validate();
    BtfSamples out(maps.width, maps.height, angles);
    const size_t texels = out.texels();
    const bool shadows = !shadowing.height.empty();
    float hmax = 0.0f;
    if (shadows) {
        if (shadowing.height.size() != texels)
            throw InvalidArgument("height field must have (height, width) values");
        hmax = shadowing.height[0];
        for (float v : shadowing.height) {
            if (!std::isfinite(v)) throw InvalidArgument("height field must be finite");
            hmax = std::max(hmax, v);
        }
    }
    btfParallelFor(out.count(), threads, [&](int s0, int s1) {
        std::vector<uint8_t> vis(shadows ? texels : 0);
        for (int s = s0; s < s1; ++s) {
            if (shadows)
                visibility(shadowing, maps.width, maps.height, hmax, out.light(s), 0, texels,
                           vis.data());
            float* const planes[3] = {out.plane(s, 0), out.plane(s, 1), out.plane(s, 2)};
            btfEvaluateSample(maps, out.light(s), out.view(s), shadows ? vis.data() : nullptr, 0,
                              texels, planes);
        }
    });
    return out;
}

} // namespace weft
