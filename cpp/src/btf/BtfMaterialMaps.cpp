// BtfMaterialMaps: validation, conversion from the linear fit, evaluation and per-sample errors.
#include <weft/BtfFit.h>
#include <weft/Error.h>

#include <cmath>

#include "btf/BtfModel.h"
#include "btf/BtfParallel.h"

namespace weft {

namespace {

void requireMap(const std::vector<float>& map, size_t size, const char* name, bool optional) {
    if (optional && map.empty()) return;
    if (map.size() != size)
        throw InvalidArgument(std::string("material map '") + name + "' must have " +
                              std::to_string(size) + " values, has " + std::to_string(map.size()));
    for (float v : map)
        if (!std::isfinite(v))
            throw InvalidArgument(std::string("material map '") + name + "' must be finite");
}

} // namespace

void BtfMaterialMaps::validate() const {
    if (width <= 0 || height <= 0) throw InvalidArgument("material size must be positive");
    const size_t texels = size_t(width) * size_t(height);
    requireMap(normal, texels * 3, "normal", false);
    requireMap(albedo, texels * 3, "albedo", false);
    requireMap(ambient, texels * 3, "ambient", false);
    requireMap(specular, texels * 3, "specular", true);
    requireMap(exponentMap, texels, "exponent", true);
    if (!(exponent >= 0.0f) || !std::isfinite(exponent) || exponent > 1e6f)
        throw InvalidArgument("specular exponent must be in [0, 1e6]");
    for (float e : exponentMap)
        if (e < 0.0f || e > 1e6f) throw InvalidArgument("specular exponents must be in [0, 1e6]");
}

BtfMaterialMaps btfMaterialFromLinear(const BtfLinearFit& fit) {
    BtfMaterialMaps maps;
    maps.width = fit.width;
    maps.height = fit.height;
    const size_t texels = size_t(fit.width) * size_t(fit.height);
    maps.normal.resize(texels * 3);
    maps.albedo.resize(texels * 3);
    maps.ambient.resize(texels * 3);
    for (size_t i = 0; i < texels; ++i) {
        const float* n = &fit.normal[i * 3];
        const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        const float scale = len > 1e-12f ? len : 1.0f;
        for (int k = 0; k < 3; ++k) {
            maps.normal[i * 3 + k] = len > 1e-12f ? n[k] / len : (k == 2 ? 1.0f : 0.0f);
            maps.albedo[i * 3 + k] = fit.texture[i * 3 + k] * scale;
            maps.ambient[i * 3 + k] = fit.ambient[i * 3 + k] / scale;
        }
    }
    return maps;
}

glm::vec3 btfHalfVector(glm::vec3 l, glm::vec3 v) {
    const glm::vec3 h = l + v;
    const float len = glm::length(h);
    return len > 1e-12f ? h / len : glm::vec3(0, 0, 1);
}

void btfEvaluateSample(const BtfMaterialMaps& maps, glm::vec3 l, glm::vec3 v,
                       const uint8_t* visible, size_t begin, size_t end, float* const out[3]) {
    const glm::vec3 h = btfHalfVector(l, v);
    const bool spec = !maps.specular.empty();
    const float flatDot = std::max(h.z, 0.0f);
    for (size_t i = begin; i < end; ++i) {
        const float* n = &maps.normal[i * 3];
        const float vis = visible ? float(visible[i]) : 1.0f;
        const float nl = n[0] * l.x + n[1] * l.y + n[2] * l.z;
        const float d = (maps.clampDiffuse ? std::max(nl, 0.0f) : nl) * vis;
        float g = 0.0f;
        // clampDiffuse is the renderer's model: no highlight where n·l <= 0 either
        if (spec && (!maps.clampDiffuse || nl > 0.0f)) {
            const float u = maps.flatSpecularNormal
                                ? flatDot
                                : std::max(n[0] * h.x + n[1] * h.y + n[2] * h.z, 0.0f);
            const float e = maps.exponentMap.empty() ? maps.exponent : maps.exponentMap[i];
            g = vis * (u > 0.0f ? std::pow(u, e) : 0.0f);
        }
        for (int c = 0; c < 3; ++c) {
            float p = maps.albedo[i * 3 + c] * (maps.ambient[i * 3 + c] + d);
            if (spec) p += maps.specular[i * 3 + c] * g;
            out[c][i] = p;
        }
    }
}

std::vector<double> btfSampleErrors(const BtfSamples& samples, const BtfMaterialMaps& maps,
                                    std::vector<float>* reconstruction, int threads) {
    maps.validate();
    if (maps.width != samples.width() || maps.height != samples.height())
        throw InvalidArgument("material and samples differ in size");
    const size_t texels = samples.texels();
    const int count = samples.count();
    if (reconstruction) reconstruction->assign(texels * 3 * size_t(count), 0.0f);
    std::vector<double> errors(size_t(count), 0.0);
    btfParallelFor(count, threads, [&](int s0, int s1) {
        std::vector<float> scratch(reconstruction ? 0 : texels * 3);
        for (int s = s0; s < s1; ++s) {
            float* base =
                reconstruction ? reconstruction->data() + size_t(s) * 3 * texels : scratch.data();
            float* const out[3] = {base, base + texels, base + 2 * texels};
            btfEvaluateSample(maps, samples.light(s), samples.view(s), nullptr, 0, texels, out);
            double sum = 0.0;
            for (int c = 0; c < 3; ++c) {
                const float* p = samples.plane(s, c);
                for (size_t i = 0; i < texels; ++i) {
                    const double r = double(out[c][i]) - p[i];
                    sum += r * r;
                }
            }
            errors[size_t(s)] = sum / double(texels * 3);
        }
    });
    return errors;
}

} // namespace weft
