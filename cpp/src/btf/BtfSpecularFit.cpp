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

#include "btf/BtfFiniteCheck.h"
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
    double total = 0.0;        // Σ r²
    std::vector<float> alpha;  // α_st, [sample][texel]
    std::vector<float> beta;   // β_t
    std::vector<float> logDot; // log max(n·h, 0) per [sample][texel] (fitted-normal variant)
};

// One pass over the samples, texel block by texel block (the block's maps stay in cache while
// all samples stream by): Σ r², α (stored when `storeAlpha`), A_s = Σ_t α_st into `alphaSums`,
// and log(n·h) for the fitted-normal variant. The linear model is P_c = base_c + m_c·l with
// base_c = ρ_c a_c and m_c = ρ_c n.
Residuals residuals(const BtfSamples& samples, const BtfMaterialMaps& linear, bool needLogDot,
                    bool storeAlpha, std::vector<double>& alphaSums, int threads) {
    constexpr int kBlock = 512;
    const size_t texels = samples.texels();
    const int count = samples.count();
    Residuals r;
    if (storeAlpha) r.alpha.resize(texels * size_t(count));
    if (needLogDot) r.logDot.resize(texels * size_t(count));
    r.beta.resize(texels);
    for (size_t t = 0; t < texels; ++t) {
        const float* k = &linear.specular[t * 3];
        r.beta[t] = k[0] * k[0] + k[1] * k[1] + k[2] * k[2];
    }
    const int blocks = int((texels + kBlock - 1) / kBlock);
    std::vector<double> partialR(size_t(blocks), 0.0), partialA(size_t(blocks) * size_t(count));
    std::vector<glm::vec3> halves(static_cast<size_t>(count));
    for (int s = 0; s < count; ++s)
        halves[size_t(s)] = btfHalfVector(samples.light(s), samples.view(s));
    btfParallelFor(blocks, threads, [&](int b0, int b1) {
        std::vector<float> coef(size_t(kBlock) * 15); // base[3], m[3][3], K[3] per texel
        for (int b = b0; b < b1; ++b) {
            const size_t begin = size_t(b) * kBlock;
            const int len = int(std::min<size_t>(kBlock, texels - begin));
            for (int i = 0; i < len; ++i) {
                const size_t t = begin + size_t(i);
                float* c = &coef[size_t(i) * 15];
                for (int ch = 0; ch < 3; ++ch) {
                    const float rho = linear.albedo[t * 3 + size_t(ch)];
                    c[ch] = rho * linear.ambient[t * 3 + size_t(ch)];
                    for (int k = 0; k < 3; ++k)
                        c[3 + ch * 3 + k] = rho * linear.normal[t * 3 + size_t(k)];
                    c[12 + ch] = linear.specular[t * 3 + size_t(ch)];
                }
            }
            double sumR = 0.0;
            for (int s = 0; s < count; ++s) {
                const glm::vec3 l = samples.light(s), h = halves[size_t(s)];
                const float* p[3] = {samples.plane(s, 0) + begin, samples.plane(s, 1) + begin,
                                     samples.plane(s, 2) + begin};
                float* alpha = storeAlpha ? r.alpha.data() + size_t(s) * texels + begin : nullptr;
                float sq = 0.0f, alphaSum = 0.0f;
                for (int i = 0; i < len; ++i) {
                    const float* c = &coef[size_t(i) * 15];
                    float a = 0.0f;
                    for (int ch = 0; ch < 3; ++ch) {
                        const float* m = c + 3 + ch * 3;
                        const float res = p[ch][i] - (c[ch] + m[0] * l.x + m[1] * l.y + m[2] * l.z);
                        sq += res * res;
                        a += res * c[12 + ch];
                    }
                    alphaSum += a;
                    if (alpha) alpha[i] = a;
                }
                if (needLogDot) {
                    float* ld = r.logDot.data() + size_t(s) * texels + begin;
                    for (int i = 0; i < len; ++i) {
                        const float* n = &linear.normal[(begin + size_t(i)) * 3];
                        const float u = n[0] * h.x + n[1] * h.y + n[2] * h.z;
                        ld[i] = u > 0.0f ? std::log(u) : -std::numeric_limits<float>::infinity();
                    }
                }
                sumR += sq;
                partialA[size_t(b) * size_t(count) + size_t(s)] = alphaSum;
            }
            partialR[size_t(b)] = sumR;
        }
    });
    alphaSums.assign(size_t(count), 0.0);
    for (int b = 0; b < blocks; ++b) {
        r.total += partialR[size_t(b)];
        for (int s = 0; s < count; ++s)
            alphaSums[size_t(s)] += partialA[size_t(b) * size_t(count) + size_t(s)];
    }
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
    std::vector<double> a; // A_s = Σ_t α_st
    const bool storeAlpha = !options.flatSpecularNormal || options.perTexel;
    const Residuals r =
        residuals(samples, out.maps, !options.flatSpecularNormal, storeAlpha, a, options.threads);
    requireFiniteFit(out.maps.specular, "specular fit", "specular map", samples);
    bool finite = std::isfinite(r.total);
    for (double v : a) finite = finite && std::isfinite(v);
    for (float v : r.beta) finite = finite && std::isfinite(v);
    if (!finite) throwBtfOverflow("specular fit", "residual", samples);
    const int maxE = options.maxExponent;
    out.curve.assign(size_t(maxE), std::numeric_limits<double>::quiet_NaN());

    if (options.flatSpecularNormal) {
        double b = 0.0;
        for (float v : r.beta) b += v;
        std::vector<double> g(a.size(), 1.0), hz(a.size());
        for (int s = 0; s < count; ++s)
            hz[size_t(s)] = std::max(btfHalfVector(samples.light(s), samples.view(s)).z, 0.0f);
        for (int e = 1; e <= maxE; ++e) {
            double err = r.total;
            for (size_t s = 0; s < g.size(); ++s) {
                g[s] *= hz[s]; // g_s(e) = hz_s^e, one product per candidate
                err += g[s] * (g[s] * b - 2.0 * a[s]);
            }
            if (!std::isfinite(err)) throwBtfOverflow("specular fit", "error curve", samples);
            out.curve[size_t(e - 1)] = err;
        }
    } else {
        // Log-spaced grid, then a golden-section search over the integers around the best.
        const std::vector<int> grid = logCandidates(maxE, 48);
        auto eval = [&](int e) {
            double& slot = out.curve[size_t(e - 1)];
            if (std::isnan(slot)) slot = fittedError(r, texels, count, e, options.threads);
            if (!std::isfinite(slot)) throwBtfOverflow("specular fit", "error curve", samples);
            return slot;
        };
        size_t best = 0;
        for (size_t k = 0; k < grid.size(); ++k)
            if (eval(grid[k]) < eval(grid[best])) best = k;
        int lo = grid[best > 0 ? best - 1 : 0], hi = grid[std::min(best + 1, grid.size() - 1)];
        while (hi - lo > 2) {
            const int m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
            if (eval(m1) <= eval(m2))
                hi = m2;
            else
                lo = m1;
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
