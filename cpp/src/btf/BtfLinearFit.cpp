// The seed's linear least-squares fit (SPEC §3.2, eq. 4.22), exploiting that all texels share
// the light directions.
//
// Per texel the unknowns are (n, a_r, a_g, a_b) and the equations t_c (l_s·n) + t_c a_c = p_sc.
// With centred lights l~ = l - mean(l) and a~_c = a_c + mean(l)·n the normal equations decouple:
//   (Σ_c t_c²) C n = Σ_c t_c Σ_s p_sc l~_s,   C = Σ_s l~_s l~_sᵀ (shared by every texel),
//   a~_c = Σ_s p_sc / (N t_c).
// So one pass over the samples accumulates Σ p and Σ p l~ per texel and channel (T comes from
// the same sums), and each texel costs one 3x3 back substitution with the shared Cholesky
// factor of C. Centring also removes the cancellation of the uncentred form in float32.
// The robust option re-solves each texel's weighted 6x6 system in its reduced 3x3 form (IRLS).
#include <weft/BtfFit.h>
#include <weft/Error.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "btf/BtfParallel.h"
#include "btf/BtfFiniteCheck.h"
#include "btf/Cholesky3.h"

namespace weft {

namespace {

constexpr int kBlock = 256; // texels per accumulation block (12 x 1 KiB of accumulators)

struct LightFrame {
    glm::dvec3 mean{0.0};
    std::vector<glm::vec3> centred;
    Cholesky3 factor;
};

LightFrame lightFrame(const BtfSamples& samples) {
    LightFrame f;
    const int n = samples.count();
    if (n < 4) throw InvalidArgument("the linear BTF fit needs at least 4 samples, got " +
                                     std::to_string(n));
    for (int s = 0; s < n; ++s) f.mean += glm::dvec3(samples.light(s));
    f.mean /= double(n);
    double c[3][3] = {};
    for (int s = 0; s < n; ++s) {
        const glm::dvec3 d = glm::dvec3(samples.light(s)) - f.mean;
        f.centred.emplace_back(d);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) c[i][j] += d[i] * d[j];
    }
    if (!f.factor.factor(c, 1e-9))
        throw InvalidArgument("the light directions are coplanar (with the constant term): the "
                              "normal is not determined by these samples");
    return f;
}

// The memory-bound pass: Σ p and Σ p l~ per texel and channel for texels [begin, begin + len).
// Rows of four samples are fused so the accumulators (in L1) are loaded and stored once per
// four samples. Built for AVX2 and for the baseline, picked at load time (function
// multiversioning on x86-64 GCC/Clang).
#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target_clones("avx2", "default")))
#endif
void accumulateBlock(const float* values, size_t texels, const glm::vec3* lights, int samples,
                     size_t begin, int len, float acc[3][4][kBlock]) {
    for (int c = 0; c < 3; ++c) {
        float* __restrict a0 = acc[c][0];
        float* __restrict ax = acc[c][1];
        float* __restrict ay = acc[c][2];
        float* __restrict az = acc[c][3];
        for (int i = 0; i < len; ++i) a0[i] = ax[i] = ay[i] = az[i] = 0.0f;
        auto row = [&](int s) { return values + (size_t(s) * 3 + size_t(c)) * texels + begin; };
        int s = 0;
        for (; s + 4 <= samples; s += 4) {
            const float* __restrict p0 = row(s);
            const float* __restrict p1 = row(s + 1);
            const float* __restrict p2 = row(s + 2);
            const float* __restrict p3 = row(s + 3);
            const glm::vec3 l0 = lights[s], l1 = lights[s + 1], l2 = lights[s + 2],
                            l3 = lights[s + 3];
            for (int i = 0; i < len; ++i) {
                const float v0 = p0[i], v1 = p1[i], v2 = p2[i], v3 = p3[i];
                a0[i] += (v0 + v1) + (v2 + v3);
                ax[i] += (v0 * l0.x + v1 * l1.x) + (v2 * l2.x + v3 * l3.x);
                ay[i] += (v0 * l0.y + v1 * l1.y) + (v2 * l2.y + v3 * l3.y);
                az[i] += (v0 * l0.z + v1 * l1.z) + (v2 * l2.z + v3 * l3.z);
            }
        }
        for (; s < samples; ++s) {
            const float* __restrict p = row(s);
            const glm::vec3 l = lights[s];
            for (int i = 0; i < len; ++i) {
                a0[i] += p[i];
                ax[i] += p[i] * l.x;
                ay[i] += p[i] * l.y;
                az[i] += p[i] * l.z;
            }
        }
    }
}

struct TexelSums {
    double p[3];     // Σ_s p_sc
    double q[3][3];  // Σ_s p_sc l~_s
};

void solveTexel(const TexelSums& sums, const float t[3], int n, const LightFrame& frame,
                float darkThreshold, float* normalOut, float* ambientOut, int& darkChannels,
                bool& darkTexel) {
    double tt = 0.0, rhs[3] = {0, 0, 0};
    bool lit[3];
    for (int c = 0; c < 3; ++c) {
        lit[c] = std::fabs(t[c]) > darkThreshold;
        if (!lit[c]) continue;
        tt += double(t[c]) * t[c];
        for (int k = 0; k < 3; ++k) rhs[k] += double(t[c]) * sums.q[c][k];
    }
    darkTexel = tt == 0.0;
    if (darkTexel) {
        normalOut[0] = normalOut[1] = 0.0f;
        normalOut[2] = 1.0f;
        for (int c = 0; c < 3; ++c) ambientOut[c] = 0.0f;
        darkChannels += 3;
        return;
    }
    double nv[3];
    frame.factor.solve(rhs, nv);
    for (int k = 0; k < 3; ++k) normalOut[k] = float(nv[k] / tt);
    const double shift = (frame.mean.x * nv[0] + frame.mean.y * nv[1] + frame.mean.z * nv[2]) / tt;
    double litSum = 0.0;
    int litCount = 0;
    for (int c = 0; c < 3; ++c) {
        if (!lit[c]) continue;
        ambientOut[c] = float(sums.p[c] / (double(n) * t[c]) - shift);
        litSum += ambientOut[c];
        ++litCount;
    }
    for (int c = 0; c < 3; ++c) {
        if (lit[c]) continue;
        ambientOut[c] = float(litSum / litCount); // no equations: take the lit channels' value
        ++darkChannels;
    }
}

// Reweighted solve of one texel: Tukey biweight on the RGB residual norm, samples with
// n·l <= 0 dropped. Returns nothing; refines normal/ambient in place.
void robustTexel(const BtfSamples& samples, size_t texel, const float t[3], int iterations,
                 float darkThreshold, float* normal, float* ambient) {
    const int n = samples.count();
    std::vector<double> residual(static_cast<size_t>(n)), sorted, weight(residual.size(), 1.0);
    bool lit[3];
    double tt = 0.0;
    for (int c = 0; c < 3; ++c) {
        lit[c] = std::fabs(t[c]) > darkThreshold;
        if (lit[c]) tt += double(t[c]) * t[c];
    }
    if (tt == 0.0) return;
    for (int it = 0; it < iterations; ++it) {
        for (int s = 0; s < n; ++s) {
            const glm::vec3 l = samples.light(s);
            const double nl = double(normal[0]) * l.x + double(normal[1]) * l.y +
                              double(normal[2]) * l.z;
            double e2 = 0.0;
            for (int c = 0; c < 3; ++c) {
                const double r = t[c] * (nl + ambient[c]) - samples.plane(s, c)[texel];
                e2 += r * r;
            }
            residual[size_t(s)] = std::sqrt(e2);
            weight[size_t(s)] = nl > 0.0 ? 1.0 : 0.0;
        }
        sorted = residual;
        std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
        const double sigma = 1.4826 * sorted[size_t(n / 2)];
        if (!(sigma > 1e-12)) return; // already exact
        const double cut = 4.685 * sigma;
        double w = 0.0, sl[3] = {}, ll[3][3] = {}, p[3] = {}, q[3][3] = {};
        for (int s = 0; s < n; ++s) {
            const double u = residual[size_t(s)] / cut;
            const double ws = u < 1.0 ? weight[size_t(s)] * (1 - u * u) * (1 - u * u) : 0.0;
            if (ws == 0.0) continue;
            const glm::dvec3 l(samples.light(s));
            w += ws;
            for (int i = 0; i < 3; ++i) {
                sl[i] += ws * l[i];
                for (int j = 0; j < 3; ++j) ll[i][j] += ws * l[i] * l[j];
            }
            for (int c = 0; c < 3; ++c) {
                const double pc = ws * samples.plane(s, c)[texel];
                p[c] += pc;
                for (int i = 0; i < 3; ++i) q[c][i] += pc * l[i];
            }
        }
        if (w <= 0.0) return;
        double m[3][3], rhs[3] = {0, 0, 0};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) m[i][j] = ll[i][j] - sl[i] * sl[j] / w;
        for (int c = 0; c < 3; ++c) {
            if (!lit[c]) continue;
            for (int i = 0; i < 3; ++i) rhs[i] += t[c] * (q[c][i] - sl[i] * p[c] / w) / tt;
        }
        Cholesky3 f;
        if (!f.factor(m, 1e-9)) return; // too few inliers to pin the normal: keep the last one
        double nv[3];
        f.solve(rhs, nv);
        for (int i = 0; i < 3; ++i) normal[i] = float(nv[i]);
        const double sn = sl[0] * nv[0] + sl[1] * nv[1] + sl[2] * nv[2];
        for (int c = 0; c < 3; ++c)
            if (lit[c]) ambient[c] = float((p[c] / t[c] - sn) / w);
    }
}

BtfLinearFit solve(const BtfSamples& samples, const std::vector<float>* texture,
                   const BtfLinearOptions& options) {
    samples.requireFinite();
    if (!(options.darkThreshold >= 0.0f) || !std::isfinite(options.darkThreshold))
        throw InvalidArgument("darkThreshold must be finite and >= 0");
    if (options.robustIterations < 1 || options.robustIterations > 100)
        throw InvalidArgument("robustIterations must be 1..100");
    const LightFrame frame = lightFrame(samples);
    const size_t texels = samples.texels();
    const int n = samples.count();
    BtfLinearFit fit;
    fit.width = samples.width();
    fit.height = samples.height();
    if (texture) {
        if (texture->size() != texels * 3)
            throw InvalidArgument("texture must have (height, width, 3) values");
        for (float v : *texture)
            if (!std::isfinite(v)) throw InvalidArgument("texture must be finite");
        fit.texture = *texture;
    } else {
        fit.texture.assign(texels * 3, 0.0f);
    }
    fit.normal.assign(texels * 3, 0.0f);
    fit.ambient.assign(texels * 3, 0.0f);
    fit.dark.assign(texels, 0);
    const int blocks = int((texels + kBlock - 1) / kBlock);
    std::vector<int> darkChannels(size_t(blocks), 0);

    btfParallelFor(blocks, options.threads, [&](int b0, int b1) {
        alignas(64) float acc[3][4][kBlock];
        for (int b = b0; b < b1; ++b) {
            const size_t begin = size_t(b) * kBlock;
            const int len = int(std::min<size_t>(kBlock, texels - begin));
            accumulateBlock(samples.values().data(), texels, frame.centred.data(), n, begin, len,
                            acc);
            for (int i = 0; i < len; ++i) {
                const size_t texel = begin + size_t(i);
                TexelSums sums;
                float* t = fit.texture.data() + texel * 3;
                for (int c = 0; c < 3; ++c) {
                    sums.p[c] = acc[c][0][i];
                    for (int k = 0; k < 3; ++k) sums.q[c][k] = acc[c][k + 1][i];
                    if (!texture) t[c] = float(sums.p[c] / n);
                }
                bool darkTexel = false;
                float* nOut = fit.normal.data() + texel * 3;
                float* aOut = fit.ambient.data() + texel * 3;
                solveTexel(sums, t, n, frame, options.darkThreshold, nOut, aOut,
                           darkChannels[size_t(b)], darkTexel);
                fit.dark[texel] = darkTexel;
                if (options.robust && !darkTexel)
                    robustTexel(samples, texel, t, options.robustIterations,
                                options.darkThreshold, nOut, aOut);
            }
        }
    });
    requireFiniteFit(fit.texture, "linear fit", "texture", samples);
    requireFiniteFit(fit.normal, "linear fit", "normal map", samples);
    requireFiniteFit(fit.ambient, "linear fit", "ambient map", samples);
    for (int d : darkChannels) fit.darkChannels += d;
    for (uint8_t d : fit.dark) fit.darkTexels += d;
    fit.darkChannels -= 3 * fit.darkTexels;
    return fit;
}

} // namespace

BtfLinearFit fitBtfLinear(const BtfSamples& samples, const BtfLinearOptions& options) {
    return solve(samples, nullptr, options);
}

BtfLinearFit solveBtfLinear(const BtfSamples& samples, const std::vector<float>& texture,
                            const BtfLinearOptions& options) {
    return solve(samples, &texture, options);
}

} // namespace weft
