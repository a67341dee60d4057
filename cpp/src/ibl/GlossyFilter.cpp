// Glossy prefiltering: exact and importance-sampled Phong lobes, the GGX split-sum chain and its
// DFG table. Sampled filters read each sample from the mip level matching its solid angle.
#include <weft/IblFilter.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <weft/Error.h>

#include "CubeTexels.h"
#include "GgxPlan.h"
#include "GgxSamples.h"
#include "IblParallel.h"
#include "IblValidate.h"

namespace weft {

namespace {

constexpr float kPi = 3.14159265358979f;

void requireShininess(float s) {
    if (!(s >= 0.0f && s <= 1e6f)) throw InvalidArgument("shininess must be in [0, 1e6]");
}

// Mip level whose texel solid angle matches a sample's, 1 / (n pdf) (Krivanek & Colbert 2008,
// without their +1 bias: 3-4x lower error on smooth environments in the benchmark, and a tiny
// sun still stays bounded); `texelSolidAngle` is the level-0 texel solid angle.
float sampleLod(float pdf, int samples, float texelSolidAngle) {
    const float omegaS = 1.0f / (float(samples) * std::max(pdf, 1e-12f));
    return std::max(0.0f, 0.5f * std::log2(omegaS / texelSolidAngle));
}

template <class Fn> void fillLevel(CubeMap& out, int level, Fn fn) {
    const int size = out.levelSize(level);
    iblParallelFor(6 * size, [&](int begin, int end) {
        for (int row = begin; row < end; ++row) {
            const int f = row / size, j = row % size;
            for (int i = 0; i < size; ++i) {
                const glm::vec3 c = fn(cubeTexelDirection(f, i, j, size));
                float* p = out.texel(f, i, j, level);
                p[0] = c.x;
                p[1] = c.y;
                p[2] = c.z;
            }
        }
    });
}

// GGX half vector around +Z for a uniform point u and alpha.
glm::vec3 ggxHalf(const glm::vec2& u, float alpha) {
    const float a2 = alpha * alpha;
    const float cosT = std::sqrt((1.0f - u.y) / (1.0f + (a2 - 1.0f) * u.y));
    const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT));
    const float phi = 2.0f * kPi * u.x;
    return {sinT * std::cos(phi), sinT * std::sin(phi), cosT};
}

float ggxD(float nh, float alpha) {
    const float a2 = alpha * alpha;
    const float d = nh * nh * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * d * d);
}

} // namespace

glm::vec2 hammersley(unsigned i, unsigned n) {
    unsigned bits = i;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return {float(i) / float(n), float(bits) * 2.3283064365386963e-10f};
}

CubeMap phongExact(const CubeMap& radiance, float shininess, int size, int sourceSize) {
    requireCube(radiance, "radiance cube map");
    requireShininess(shininess);
    requireCount(size, 1024, "output size");
    requireCount(sourceSize, 1024, "source size");
    requireAffordable(36.0 * size * size * sourceSize * sourceSize, "exact Phong convolution");
    const CubeTexels t = cubeTexels(reducedCube(radiance, sourceSize));
    const float cosMin = shininess > 0.0f ? std::pow(1e-6f, 1.0f / shininess) : 0.0f;
    CubeMap out(size);
    fillLevel(out, 0, [&](const glm::vec3& d) {
        double r = 0.0, g = 0.0, b = 0.0, w = 0.0;
        for (size_t k = 0; k < t.size(); ++k) {
            const float c = d.x * t.x[k] + d.y * t.y[k] + d.z * t.z[k];
            if (c <= cosMin || c <= 0.0f) continue;
            const double lobe = std::pow(double(c), double(shininess));
            r += lobe * t.r[k];
            g += lobe * t.g[k];
            b += lobe * t.b[k];
            w += lobe * t.dw[k];
        }
        return w > 0.0 ? glm::vec3(float(r / w), float(g / w), float(b / w)) : glm::vec3(0.0f);
    });
    return out;
}

CubeMap phongSampled(const CubeMap& radiance, float shininess, int size, int samples) {
    requireCube(radiance, "radiance cube map");
    requireShininess(shininess);
    requireCount(size, 1024, "output size");
    requireCount(samples, 1 << 20, "sample count");
    requireAffordable(6.0 * size * size * samples * 16.0, "sampled Phong convolution");
    const CubeMap chain = withMips(radiance);
    const float texelOmega = 4.0f * kPi / (6.0f * float(radiance.size()) * float(radiance.size()));
    std::vector<glm::vec3> local(static_cast<size_t>(samples));
    std::vector<float> lods(static_cast<size_t>(samples));
    for (int k = 0; k < samples; ++k) {
        const glm::vec2 u = hammersley(unsigned(k), unsigned(samples));
        const float cosT = std::pow(1.0f - u.y, 1.0f / (shininess + 1.0f));
        const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT));
        const float phi = 2.0f * kPi * u.x;
        local[size_t(k)] = {sinT * std::cos(phi), sinT * std::sin(phi), cosT};
        const float pdf = (shininess + 1.0f) / (2.0f * kPi) * std::pow(cosT, shininess);
        lods[size_t(k)] = sampleLod(pdf, samples, texelOmega);
    }
    CubeMap out(size);
    fillLevel(out, 0, [&](const glm::vec3& n) {
        glm::vec3 t, b;
        tangentFrame(n, t, b);
        glm::vec3 acc(0.0f);
        for (int k = 0; k < samples; ++k) {
            const glm::vec3& l = local[size_t(k)];
            acc += chain.sampleLod(l.x * t + l.y * b + l.z * n, lods[size_t(k)]);
        }
        return acc / float(samples);
    });
    return out;
}

float ggxLevelAlpha(int m, int levels) {
    const float rough = levels > 1 ? float(m) / float(levels - 1) : 0.0f;
    return std::max(rough * rough, 1e-3f);
}

float ggxMirrorLod(int sourceSize, int size) {
    return std::max(0.0f, std::log2(float(sourceSize) / float(size)));
}

std::vector<GgxSample> ggxSamples(float alpha, int samples, float texelSolidAngle) {
    std::vector<GgxSample> out(static_cast<size_t>(samples));
    for (int k = 0; k < samples; ++k) {
        const glm::vec3 h = ggxHalf(hammersley(unsigned(k), unsigned(samples)), alpha);
        out[size_t(k)] = {h, sampleLod(ggxD(h.z, alpha) * 0.25f, samples, texelSolidAngle)};
    }
    return out;
}

CubeMap prefilterGgx(const CubeMap& radiance, int size, int levels, int samples) {
    requireGgxArguments(radiance, size, levels, samples);
    const GgxPlan plan = ggxPlan(radiance, size, levels, samples);
    CubeMap out(size);
    std::copy(plan.mirror.data(), plan.mirror.data() + plan.mirror.floatCount(), out.data());
    out.buildMips(); // allocates the chain; levels 1 .. levels-1 are overwritten below
    out.keepLevels(levels);
    for (int m = 1; m < levels; ++m) {
        const GgxLevelPlan& p = plan.level[size_t(m)];
        const float alpha2 = p.alpha * p.alpha;
        fillLevel(out, m, [&](const glm::vec3& n) {
            glm::vec3 t, b;
            tangentFrame(n, t, b);
            glm::vec3 acc(0.0f);
            float wsum = 0.0f;
            for (const GgxSample& s : p.samples) {
                const glm::vec3& hl = s.h;
                const glm::vec3 h = hl.x * t + hl.y * b + hl.z * n;
                const glm::vec3 l = 2.0f * hl.z * h - n; // reflect V = N about H
                const float nl = glm::dot(n, l);
                if (nl <= 0.0f) continue;
                acc += nl * plan.clamped.sampleLod(l, s.lod);
                wsum += nl;
            }
            glm::vec3 exact(0.0f);
            for (const GgxPoint& q : p.points)
                exact += ggxPointWeight(glm::dot(n, q.dir), alpha2) * q.power;
            return (wsum > 0.0f ? acc / wsum : glm::vec3(0.0f)) + exact * p.invNorm;
        });
    }
    return out;
}

std::vector<float> dfgLut(int size, int samples) {
    requireCount(size, 1024, "DFG table size");
    requireCount(samples, 1 << 20, "sample count");
    requireAffordable(double(size) * size * samples * 10.0, "DFG table");
    std::vector<float> out(size_t(size) * size * 2);
    iblParallelFor(size, [&](int begin, int end) {
        for (int j = begin; j < end; ++j) {
            const float rough = (float(j) + 0.5f) / float(size);
            const float alpha = rough * rough;
            const float k = alpha * 0.5f;
            for (int i = 0; i < size; ++i) {
                const float nv = (float(i) + 0.5f) / float(size);
                const glm::vec3 v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
                double a = 0.0, bsum = 0.0;
                for (int s = 0; s < samples; ++s) {
                    const glm::vec3 h = ggxHalf(hammersley(unsigned(s), unsigned(samples)), alpha);
                    const float vh = glm::dot(v, h);
                    const glm::vec3 l = 2.0f * vh * h - v;
                    const float nl = l.z, nh = h.z;
                    if (nl <= 0.0f || vh <= 0.0f) continue;
                    const float g = (nv / (nv * (1.0f - k) + k)) * (nl / (nl * (1.0f - k) + k));
                    const float gVis = g * vh / (nh * nv);
                    const float fc = std::pow(1.0f - vh, 5.0f);
                    a += (1.0f - fc) * gVis;
                    bsum += fc * gVis;
                }
                out[(size_t(j) * size + i) * 2] = float(a / samples);
                out[(size_t(j) * size + i) * 2 + 1] = float(bsum / samples);
            }
        }
    });
    return out;
}

namespace {

// The unpolarised Fresnel reflectance at cos c of the dielectric whose normal-incidence
// reflectance is f0 (Walter et al. 2007, "Microfacet models for refraction", eq. 22).
double dielectricFresnel(double c, double f0) {
    const double r = std::sqrt(std::clamp(f0, 0.0, 0.999));
    const double eta = (1.0 + r) / (1.0 - r);
    const double g = std::sqrt(eta * eta - 1.0 + c * c);
    const double a = (g - c) / (g + c), b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

// Smith's G1 of GGX with alpha^2 = a2 at cos c (Walter et al. 2007, eq. 34).
double smithG1(double c, double a2) {
    return 2.0 / (1.0 + std::sqrt(1.0 + a2 * (1.0 / (c * c) - 1.0)));
}

} // namespace

double coatAlbedo(double cosView, double alpha, double f0, int samples) {
    auto inUnit = [](double x) { return std::isfinite(x) && x >= 0.0 && x <= 1.0; };
    if (!inUnit(cosView) || !inUnit(alpha) || !inUnit(f0))
        throw InvalidArgument("coat_albedo: cos_view, alpha and f0 must be in [0, 1]");
    requireCount(samples, 1 << 20, "sample count");
    const double nv = std::max(cosView, 1e-4), a2 = alpha * alpha;
    const glm::dvec3 v(std::sqrt(1.0 - nv * nv), 0.0, nv);
    const double g1v = smithG1(nv, a2);
    double sum = 0.0;
    for (int s = 0; s < samples; ++s) {
        const glm::dvec3 h(ggxHalf(hammersley(unsigned(s), unsigned(samples)), float(alpha)));
        const double vh = glm::dot(v, h), nl = 2.0 * vh * h.z - nv;
        if (vh <= 0.0 || nl <= 0.0) continue;
        // f (n.l) over the density of l, D (n.h) / (4 v.h)
        sum += dielectricFresnel(vh, f0) * smithG1(nl, a2) * g1v * vh / (nv * h.z);
    }
    return sum / samples;
}

std::vector<float> coatAlbedoTable(int cosines, int roughness, int f0s, int samples) {
    requireCount(cosines, 1024, "table size");
    requireCount(roughness, 1024, "table size");
    requireCount(f0s, 1024, "table size");
    if (cosines < 2 || roughness < 2 || f0s < 2)
        throw InvalidArgument("coat albedo table: at least 2 values per axis");
    std::vector<float> out(size_t(cosines) * size_t(roughness) * size_t(f0s));
    iblParallelFor(f0s, [&](int begin, int end) {
        for (int k = begin; k < end; ++k) {
            const double w = double(k) / (f0s - 1);
            for (int j = 0; j < roughness; ++j) {
                const double r = double(j) / (roughness - 1);
                for (int i = 0; i < cosines; ++i) {
                    const double c = double(i) / (cosines - 1);
                    out[(size_t(k) * roughness + size_t(j)) * cosines + size_t(i)] =
                        float(coatAlbedo(c * c, r * r, w * w, samples));
                }
            }
        }
    });
    return out;
}

} // namespace weft
