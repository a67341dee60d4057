// Specular map from the residual of the θ_l = 0 sample and the exponent search (SPEC §3.3).
//
// With r_s the residual of the linear reconstruction and K the specular map, the total squared
// error of exponent e is E(e) = Σ r² - 2 Σ_s,t g_st(e) α_st + Σ_s,t g_st(e)² β_t with
// α_st = Σ_c r_stc K_tc, β_t = Σ_c K_tc² and g = max(n_s·h, 0)^e. For n_s = (0, 0, 1) g depends
// on the sample only, so E(e) = R - 2 Σ_s g_s A_s + B Σ_s g_s² after one pass (A_s = Σ_t α_st):
// every integer exponent costs O(samples). For the fitted normal each candidate costs one pass
// over the precomputed log(n·h) and α.
#include <weft/BtfFit.h>
#include <weft/Error.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "btf/BtfModel.h"
#include "btf/BtfParallel.h"

namespace weft {

namespace {

int specularSampleIndex(const BtfSamples& samples) {
    int fallback = -1;
    for (int s = 0; s < samples.count(); ++s) {
        const BtfAngles& a = samples.angles()[size_t(s)];
        if (a.thetaLight != 0.0f) continue;
        if (a.thetaView == 0.0f) return s;
        if (fallback < 0) fallback = s;
    }
    if (fallback < 0)
        throw InvalidArgument("the specular fit needs a sample with θ_l = 0 (none present)");
    return fallback;
}

std::vector<int> logCandidates(int maxExponent, int count) {
    std::vector<int> out;
    for (int k = 0; k < count; ++k) {
        const int e = int(std::lround(std::exp(std::log(double(maxExponent)) * k / (count - 1))));
        if (out.empty() || e != out.back()) out.push_back(e);
    }
    return out;
}

struct Residuals {
    double total = 0.0;         // Σ r²
    std::vector<float> alpha;   // α_st, [sample][texel]
    std::vector<float> beta;    // β_t
    std::vector<float> logDot;  // log max(n·h, 0) per [sample][texel] (fitted-normal variant)
};

Residuals residuals(const BtfSamples& samples, const BtfMaterialMaps& linear, bool needLogDot,
                    int threads) {
    const size_t texels = samples.texels();
    const int count = samples.count();
    Residuals r;
    r.alpha.resize(texels * size_t(count));
    r.beta.resize(texels);
    for (size_t t = 0; t < texels; ++t) {
        const float* k = &linear.specular[t * 3];
        r.beta[t] = k[0] * k[0] + k[1] * k[1] + k[2] * k[2];
    }
    if (needLogDot) r.logDot.resize(texels * size_t(count));
    std::vector<double> partial(size_t(count), 0.0);
    BtfMaterialMaps diffuse = linear;
    diffuse.specular.clear();
    btfParallelFor(count, threads, [&](int s0, int s1) {
        std::vector<float> scratch(texels * 3);
        float* const out[3] = {scratch.data(), scratch.data() + texels,
                               scratch.data() + 2 * texels};
        for (int s = s0; s < s1; ++s) {
            btfEvaluateSample(diffuse, samples.light(s), samples.view(s), nullptr, 0, texels, out);
            const glm::vec3 h = btfHalfVector(samples.light(s), samples.view(s));
            float* alpha = r.alpha.data() + size_t(s) * texels;
            double sum = 0.0;
            for (size_t t = 0; t < texels; ++t) {
                float a = 0.0f;
                for (int c = 0; c < 3; ++c) {
                    const float res = samples.plane(s, c)[t] - out[c][t];
                    sum += double(res) * res;
                    a += res * linear.specular[t * 3 + c];
                }
                alpha[t] = a;
                if (needLogDot) {
                    const float* n = &linear.normal[t * 3];
                    const float u = n[0] * h.x + n[1] * h.y + n[2] * h.z;
                    r.logDot[size_t(s) * texels + t] =
                        u > 0.0f ? std::log(u) : -std::numeric_limits<float>::infinity();
                }
            }
            partial[size_t(s)] = sum;
        }
    });
    for (double p : partial) r.total += p;
    return r;
}

// E(e) for the fitted-normal variant: one pass over logDot and alpha.
double fittedError(const Residuals& r, size_t texels, int count, double e, int threads) {
    std::vector<double> partial(size_t(count), 0.0);
    btfParallelFor(count, threads, [&](int s0, int s1) {
        for (int s = s0; s < s1; ++s) {
            const float* ld = r.logDot.data() + size_t(s) * texels;
            const float* a = r.alpha.data() + size_t(s) * texels;
            double sum = 0.0;
            for (size_t t = 0; t < texels; ++t) {
                const float g = std::exp(float(e) * ld[t]);
                sum += g * (g * r.beta[t] - 2.0f * a[t]);
            }
            partial[size_t(s)] = sum;
        }
    });
    double total = r.total;
    for (double p : partial) total += p;
    return total;
}

} // namespace

BtfSpecularFit fitBtfSpecular(const BtfSamples& samples, const BtfLinearFit& fit,
                              const BtfSpecularOptions& options) {
    if (options.maxExponent < 2 || options.maxExponent > 1000000)
        throw InvalidArgument("maxExponent must be 2..1000000");
    if (fit.width != samples.width() || fit.height != samples.height())
        throw InvalidArgument("linear fit and samples differ in size");
    samples.requireFinite();
    const size_t texels = samples.texels();
    const int count = samples.count();
    BtfSpecularFit out;
    out.specularSample = specularSampleIndex(samples);
    out.maps = btfMaterialFromLinear(fit);
    out.maps.flatSpecularNormal = options.flatSpecularNormal;

    // Specular map: residual of the θ_l = 0 sample against the linear reconstruction.
    {
        std::vector<float> lin(texels * 3);
        float* const planes[3] = {lin.data(), lin.data() + texels, lin.data() + 2 * texels};
        const int s = out.specularSample;
        btfEvaluateSample(out.maps, samples.light(s), samples.view(s), nullptr, 0, texels, planes);
        out.maps.specular.resize(texels * 3);
        for (size_t t = 0; t < texels; ++t)
            for (int c = 0; c < 3; ++c)
                out.maps.specular[t * 3 + c] = samples.plane(s, c)[t] - planes[c][t];
    }
    const Residuals r = residuals(samples, out.maps, !options.flatSpecularNormal, options.threads);
    const int maxE = options.maxExponent;
    out.curve.assign(size_t(maxE), std::numeric_limits<double>::quiet_NaN());

    if (options.flatSpecularNormal) {
        std::vector<double> a(static_cast<size_t>(count), 0.0), logg(a.size());
        double b = 0.0;
        for (float v : r.beta) b += v;
        for (int s = 0; s < count; ++s) {
            const float* alpha = r.alpha.data() + size_t(s) * texels;
            double sum = 0.0;
            for (size_t t = 0; t < texels; ++t) sum += alpha[t];
            a[size_t(s)] = sum;
            const double hz = btfHalfVector(samples.light(s), samples.view(s)).z;
            logg[size_t(s)] = hz > 0 ? std::log(hz) : -std::numeric_limits<double>::infinity();
        }
        for (int e = 1; e <= maxE; ++e) {
            double err = r.total;
            for (int s = 0; s < count; ++s) {
                const double g = std::exp(e * logg[size_t(s)]);
                err += g * (g * b - 2.0 * a[size_t(s)]);
            }
            out.curve[size_t(e - 1)] = err;
        }
    } else {
        // Log-spaced grid, then a golden-section search over the integers around the best.
        const std::vector<int> grid = logCandidates(maxE, 48);
        auto eval = [&](int e) {
            double& slot = out.curve[size_t(e - 1)];
            if (std::isnan(slot)) slot = fittedError(r, texels, count, e, options.threads);
            return slot;
        };
        size_t best = 0;
        for (size_t k = 0; k < grid.size(); ++k)
            if (eval(grid[k]) < eval(grid[best])) best = k;
        int lo = grid[best > 0 ? best - 1 : 0], hi = grid[std::min(best + 1, grid.size() - 1)];
        while (hi - lo > 2) {
            const int m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
            if (eval(m1) <= eval(m2)) hi = m2;
            else lo = m1;
        }
        for (int e = lo; e <= hi; ++e) eval(e);
    }
    int bestE = 1;
    for (int e = 1; e <= maxE; ++e)
        if (!std::isnan(out.curve[size_t(e - 1)]) &&
            out.curve[size_t(e - 1)] < out.curve[size_t(bestE - 1)])
            bestE = e;
    out.maps.exponent = float(bestE);

    if (options.perTexel) {
        std::vector<int> grid = logCandidates(maxE, 64);
        grid.push_back(bestE); // never worse than the global exponent
        std::sort(grid.begin(), grid.end());
        grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
        out.maps.exponentMap.assign(texels, float(bestE));
        std::vector<float> flatG(grid.size() * size_t(count)); // g_s(e) for n_s = (0, 0, 1)
        for (int s = 0; s < count; ++s) {
            const float hz = std::max(btfHalfVector(samples.light(s), samples.view(s)).z, 0.0f);
            for (size_t k = 0; k < grid.size(); ++k)
                flatG[k * size_t(count) + size_t(s)] = std::pow(hz, float(grid[k]));
        }
        btfParallelFor(int((texels + 1023) / 1024), options.threads, [&](int b0, int b1) {
            for (size_t t = size_t(b0) * 1024; t < std::min(texels, size_t(b1) * 1024); ++t) {
                double bestErr = std::numeric_limits<double>::infinity();
                for (size_t k = 0; k < grid.size(); ++k) {
                    const int e = grid[k];
                    double err = 0.0;
                    for (int s = 0; s < count; ++s) {
                        const size_t st = size_t(s) * texels + t;
                        const float g = options.flatSpecularNormal
                                            ? flatG[k * size_t(count) + size_t(s)]
                                            : std::exp(float(e) * r.logDot[st]);
                        err += g * (g * r.beta[t] - 2.0f * r.alpha[st]);
                    }
                    if (err < bestErr) {
                        bestErr = err;
                        out.maps.exponentMap[t] = float(e);
                    }
                }
            }
        });
    }
    return out;
}

} // namespace weft
