// The seed's linear least-squares fit (SPEC §3.2, eq. 4.22), exploiting that all texels share
// the light directions.
//
// Per texel the unknowns are (n, a_r, a_g, a_b) and the equations t_c (l_s·n) + t_c a_c = p_sc.
// With centred lights l~ = l - mean(l) and a~_c = a_c + mean(l)·n the normal equations decouple:
//   (Σ_c t_c²) C n = Σ_c t_c Σ_s p_sc l~_s,   C = Σ_s l~_s l~_sᵀ (shared by every texel),
//   a~_c = Σ_s p_sc / (N t_c).
// So one pass over the samples accumulates Σ p and Σ p l~ per texel and channel (T comes from
// the same sums), and each texel costs one product with the shared C⁻¹, done for a block of
// texels at a time in SIMD float (texels with a dark channel, or beyond float range, take the
// scalar double path).
// Centring also removes the cancellation of the uncentred form in float32. The same pass is the
// finiteness check: a NaN or inf in any sample makes its texel's Σ p non-finite, so the samples
// are not read a second time for it. The robust option re-solves each texel's weighted 6x6
// system in its reduced 3x3 form (IRLS).
#include <weft/BtfFit.h>
#include <weft/Error.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>

#include "btf/BtfFiniteCheck.h"
#include "btf/BtfParallel.h"
#include "btf/Cholesky3.h"

namespace weft {

namespace {

// Texels per accumulation block: rows of 4 KiB (a page) are long enough to stream, and one
// channel's four accumulator rows (16 KiB) stay in L1 while the 81 sample rows go by.
constexpr int kBlock = 1024;

struct LightFrame {
    glm::dvec3 mean{0.0};
    std::vector<glm::vec3> centred;
    Cholesky3 factor;
    float inverse[3][3] = {}; // C⁻¹ (symmetric), for the SIMD per-texel solve
};

LightFrame lightFrame(const BtfSamples& samples) {
    LightFrame f;
    const int n = samples.count();
    if (n < 4)
        throw InvalidArgument("the linear BTF fit needs at least 4 samples, got " +
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
    for (int k = 0; k < 3; ++k) {
        double e[3] = {0, 0, 0}, column[3];
        e[k] = 1.0;
        f.factor.solve(e, column);
        for (int i = 0; i < 3; ++i) f.inverse[i][k] = float(column[i]);
    }
    return f;
}

// The four rows from sample s of channel c, where the accumulation goes after its current group
// (rolling over to the next channel, then to the next block). Used to prefetch: a block reads
// 243 rows of 4 KiB at strides of a whole plane, too short and too scattered for the hardware
// prefetcher to follow, which left the pass waiting on memory.
struct NextRows {
    const float* row[4] = {nullptr, nullptr, nullptr, nullptr};
    int len = 0; // texels to prefetch (0: nothing follows)
};

NextRows nextRows(const float* values, size_t texels, int samples, int c, int s, size_t begin,
                  int len) {
    NextRows next;
    if (s >= samples) {
        s = 0;
        if (++c == 3) {
            c = 0;
            begin += size_t(len);
            if (begin >= texels) return next;
            len = int(std::min<size_t>(kBlock, texels - begin));
        }
    }
    next.len = len;
    for (int k = 0; k < 4; ++k) // fewer than four rows left: repeat the last one
        next.row[k] =
            values + (size_t(std::min(s + k, samples - 1)) * 3 + size_t(c)) * texels + begin;
    return next;
}

// One cache line (16 floats) of each following row. Unrolled and unconditional: GCC deletes a
// loop or a branch that holds nothing but prefetches.
inline void prefetchLine(const NextRows& next, int i) {
    __builtin_prefetch(next.row[0] + i, 0, 3);
    __builtin_prefetch(next.row[1] + i, 0, 3);
    __builtin_prefetch(next.row[2] + i, 0, 3);
    __builtin_prefetch(next.row[3] + i, 0, 3);
}

// The memory-bound pass: Σ p and Σ p l~ per texel and channel for texels [begin, begin + len).
// Rows of four samples are fused so the accumulators (in L1) are loaded and stored once per
// four samples, and the following rows are prefetched while these are summed. Built for AVX2
// and for the baseline, picked at load time (function multiversioning on x86-64 GCC/Clang).
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
            const NextRows next = nextRows(values, texels, samples, c, s + 4, begin, len);
            auto sum4 = [&](int i) {
                const float v0 = p0[i], v1 = p1[i], v2 = p2[i], v3 = p3[i];
                a0[i] += (v0 + v1) + (v2 + v3);
                ax[i] += (v0 * l0.x + v1 * l1.x) + (v2 * l2.x + v3 * l3.x);
                ay[i] += (v0 * l0.y + v1 * l1.y) + (v2 * l2.y + v3 * l3.y);
                az[i] += (v0 * l0.z + v1 * l1.z) + (v2 * l2.z + v3 * l3.z);
            };
            const int prefetched = std::min(len, next.len) / 16 * 16;
            int i = 0;
            for (; i < prefetched; i += 16) {
                prefetchLine(next, i);
                for (int j = i; j < i + 16; ++j) sum4(j);
            }
            for (; i < len; ++i) sum4(i);
        }
        for (; s < samples; ++s) {
            const float* __restrict p = row(s);
            const glm::vec3 l = lights[s];
            const NextRows next = nextRows(values, texels, samples, c, s + 1, begin, len);
            auto sum1 = [&](int i) {
                a0[i] += p[i];
                ax[i] += p[i] * l.x;
                ay[i] += p[i] * l.y;
                az[i] += p[i] * l.z;
            };
            const int prefetched = std::min(len, next.len) / 16 * 16;
            int i = 0;
            for (; i < prefetched; i += 16) {
                prefetchLine(next, i);
                for (int j = i; j < i + 16; ++j) sum1(j);
            }
            for (; i < len; ++i) sum1(i);
        }
    }
}

// The per-texel solve of a block in float SIMD, all texels at once: T (the mean, unless given),
// n = C⁻¹ Σ_c t_c q_c / Σ_c t_c², I_A,c = Σ p_c / (N t_c) - mean(l)·n. Writes planar results to
// `out` (nx, ny, nz, a_r, a_g, a_b) from `t` (T per channel); flags in `scalar` the texels that
// solveTexel redoes in double: a channel below the dark threshold, or Σ t² or a result outside
// float's normal range. Returns false when a Σ p is not finite. (__restrict: without it GCC
// gives up on versioning the loop for its 25 memory streams and does not vectorise it.)
#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target_clones("avx2", "default")))
#endif
bool solveBlock(const float (*__restrict acc)[4][kBlock], int len, int samples,
                const float inverse[3][3], const glm::vec3 mean, float darkThreshold,
                const float (*__restrict t)[kBlock], float (*__restrict out)[kBlock],
                int32_t* __restrict scalar) {
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < len; ++i)
            if (!(std::fabs(acc[c][0][i]) <= FLT_MAX)) return false;
    const float n = float(samples);
    const float i00 = inverse[0][0], i01 = inverse[0][1], i02 = inverse[0][2];
    const float i11 = inverse[1][1], i12 = inverse[1][2], i22 = inverse[2][2];
    for (int i = 0; i < len; ++i) {
        const float p0 = acc[0][0][i], p1 = acc[1][0][i], p2 = acc[2][0][i];
        const float t0 = t[0][i], t1 = t[1][i], t2 = t[2][i];
        // Bitwise, not &&: a branch would stop the loop from being vectorised.
        const bool lit = (std::fabs(t0) > darkThreshold) & (std::fabs(t1) > darkThreshold) &
                         (std::fabs(t2) > darkThreshold);
        const float rx = t0 * acc[0][1][i] + t1 * acc[1][1][i] + t2 * acc[2][1][i];
        const float ry = t0 * acc[0][2][i] + t1 * acc[1][2][i] + t2 * acc[2][2][i];
        const float rz = t0 * acc[0][3][i] + t1 * acc[1][3][i] + t2 * acc[2][3][i];
        const float tt = t0 * t0 + t1 * t1 + t2 * t2;
        const float inv = 1.0f / tt;
        const float nx = (i00 * rx + i01 * ry + i02 * rz) * inv;
        const float ny = (i01 * rx + i11 * ry + i12 * rz) * inv;
        const float nz = (i02 * rx + i12 * ry + i22 * rz) * inv;
        const float shift = mean.x * nx + mean.y * ny + mean.z * nz;
        out[0][i] = nx;
        out[1][i] = ny;
        out[2][i] = nz;
        const float a0 = p0 / (n * t0) - shift, a1 = p1 / (n * t1) - shift,
                    a2 = p2 / (n * t2) - shift;
        out[3][i] = a0;
        out[4][i] = a1;
        out[5][i] = a2;
        // Σ t² leaves float's range for samples beyond ~1e19 (or below ~1e-19 with a zero dark
        // threshold), where double still has room.
        const bool finite = (tt >= FLT_MIN) & (tt <= FLT_MAX) & (std::fabs(nx) <= FLT_MAX) &
                            (std::fabs(ny) <= FLT_MAX) & (std::fabs(nz) <= FLT_MAX) &
                            (std::fabs(a0) <= FLT_MAX) & (std::fabs(a1) <= FLT_MAX) &
                            (std::fabs(a2) <= FLT_MAX);
        scalar[i] = (lit & finite) ? 0 : 1;
    }
    return true;
}

struct TexelSums {
    double p[3];    // Σ_s p_sc
    double q[3][3]; // Σ_s p_sc l~_s
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
            const double nl =
                double(normal[0]) * l.x + double(normal[1]) * l.y + double(normal[2]) * l.z;
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
    checkThreads(options.threads);
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

    const glm::vec3 mean(frame.mean);
    btfParallelFor(blocks, options.threads, [&](int b0, int b1) {
        alignas(64) float acc[3][4][kBlock];
        alignas(64) float t[3][kBlock];
        alignas(64) float out[6][kBlock];
        int32_t scalar[kBlock];
        for (int b = b0; b < b1; ++b) {
            const size_t begin = size_t(b) * kBlock;
            const int len = int(std::min<size_t>(kBlock, texels - begin));
            accumulateBlock(samples.values().data(), texels, frame.centred.data(), n, begin, len,
                            acc);
            float* tex = fit.texture.data() + begin * 3;
            for (int c = 0; c < 3; ++c) {
                if (texture) {
                    for (int i = 0; i < len; ++i) t[c][i] = tex[i * 3 + c];
                } else { // the mean, rounded once from double as the scalar path does
                    for (int i = 0; i < len; ++i) t[c][i] = float(double(acc[c][0][i]) / n);
                }
            }
            if (!solveBlock(acc, len, n, frame.inverse, mean, options.darkThreshold, t, out,
                            scalar)) {
                samples.requireFinite(); // throws when a sample is NaN/inf
                throwBtfOverflow("linear fit", "sum of samples", samples);
            }
            for (int i = 0; i < len; ++i) {
                const size_t texel = begin + size_t(i);
                float* nOut = fit.normal.data() + texel * 3;
                float* aOut = fit.ambient.data() + texel * 3;
                for (int c = 0; c < 3; ++c) {
                    if (!texture) tex[i * 3 + c] = t[c][i];
                    nOut[c] = out[c][i];
                    aOut[c] = out[3 + c][i];
                }
                bool darkTexel = false;
                if (scalar[i]) { // a channel without equations, or float overflow
                    TexelSums sums;
                    for (int c = 0; c < 3; ++c) {
                        sums.p[c] = acc[c][0][i];
                        for (int k = 0; k < 3; ++k) sums.q[c][k] = acc[c][k + 1][i];
                    }
                    solveTexel(sums, tex + i * 3, n, frame, options.darkThreshold, nOut, aOut,
                               darkChannels[size_t(b)], darkTexel);
                }
                fit.dark[texel] = darkTexel;
                if (options.robust && !darkTexel)
                    robustTexel(samples, texel, tex + i * 3, options.robustIterations,
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
