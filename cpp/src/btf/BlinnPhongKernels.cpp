// The per-sample SIMD kernels of the built-in Blinn-Phong fit (BlinnPhongKernels.h).
#include "btf/BlinnPhongKernels.h"

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace weft {

namespace {

// The per-sample work runs on the padded structure-of-arrays samples W floats at a time (GCC
// vector extensions), with polynomial log/exp instead of libm calls: W = 4 (SSE, or any 16-byte
// SIMD) everywhere, W = 8 in copies compiled for AVX2 + FMA and for AVX-512VL, chosen at run
// time on x86-64.
// (32-byte vectors compiled without AVX get their comparisons scalarised.)
// The 8-lane helpers take and return 32-byte vectors but are always inlined into the AVX2
// functions, so no call ever crosses the ABI GCC warns about.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
template <int W> struct Vec;
template <> struct Vec<4> {
    typedef float F __attribute__((vector_size(16)));
    typedef int I __attribute__((vector_size(16)));
};
template <> struct Vec<8> {
    typedef float F __attribute__((vector_size(32)));
    typedef int I __attribute__((vector_size(32)));
};
typedef double D4 __attribute__((vector_size(32)));
typedef float F4 __attribute__((vector_size(16)));
static_assert(kBlinnPhongLanes % 8 == 0, "padding must hold whole vectors");

#define WEFT_INLINE inline __attribute__((always_inline))

template <class F> WEFT_INLINE F load(const float* p) {
    F v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
template <class F> WEFT_INLINE void store(float* p, F v) { std::memcpy(p, &v, sizeof v); }
template <class F> WEFT_INLINE F splat(float x) { return F{} + x; }
// mask ? a : 0
template <class F, class I> WEFT_INLINE F select(I mask, F a) { return F(I(a) & mask); }

// Natural log for x > 0 (Cephes logf: mantissa in [√½, √2), degree-8 polynomial; ~1 ulp).
template <class F, class I> WEFT_INLINE F logv(F x) {
    const I bits = I(x);
    I ex = ((bits >> 23) & 0xff) - 126;
    F m = F((bits & 0x007fffff) | 0x3f000000); // [0.5, 1)
    const I small = m < splat<F>(0.707106781186547524f);
    ex = ex + small; // small is -1 where true
    m = m + select(small, m) - 1.0f;
    const F z = m * m;
    F y = splat<F>(7.0376836292e-2f);
    y = y * m - 1.1514610310e-1f;
    y = y * m + 1.1676998740e-1f;
    y = y * m - 1.2420140846e-1f;
    y = y * m + 1.4249322787e-1f;
    y = y * m - 1.6668057665e-1f;
    y = y * m + 2.0000714765e-1f;
    y = y * m - 2.4999993993e-1f;
    y = y * m + 3.3333331174e-1f;
    y = y * m * z;
    const F fe = __builtin_convertvector(ex, F);
    y = y + fe * -2.12194440e-4f - 0.5f * z;
    return m + y + fe * 0.693359375f;
}

// exp(x) for x <= 0 (Cephes expf: x = n ln2 + r, degree-5 polynomial; ~1 ulp); 0 below -87.
template <class F, class I> WEFT_INLINE F expv(F x) {
    const I alive = x > -87.0f;
    x = alive ? x : splat<F>(-87.0f);
    const F fx = x * 1.44269504088896341f + 0.5f;
    I n = __builtin_convertvector(fx, I); // truncation towards 0, so one too high when fx < 0
    n = n + (__builtin_convertvector(n, F) > fx);
    const F fn = __builtin_convertvector(n, F);
    x = x - fn * 0.693359375f - fn * -2.12194440e-4f;
    const F z = x * x;
    F y = splat<F>(1.9875691500e-4f);
    y = y * x + 1.3981999507e-3f;
    y = y * x + 8.3334519073e-3f;
    y = y * x + 4.1665795894e-2f;
    y = y * x + 1.6666665459e-1f;
    y = y * x + 5.0000001201e-1f;
    y = y * z + x + 1.0f;
    return select(alive, y * F((n + 127) << 23));
}

// The sum of a vector's lanes in double: widened exactly, then added in pairs (a loop adding
// lane after lane was a tenth of the derivative pass).
WEFT_INLINE double hsum(typename Vec<4>::F v) {
    const D4 x = __builtin_convertvector(v, D4);
    return (x[0] + x[2]) + (x[1] + x[3]);
}
WEFT_INLINE double hsum(typename Vec<8>::F v) {
    const D4 x = __builtin_convertvector(__builtin_shufflevector(v, v, 0, 1, 2, 3), D4) +
                 __builtin_convertvector(__builtin_shufflevector(v, v, 4, 5, 6, 7), D4);
    return (x[0] + x[2]) + (x[1] + x[3]);
}

// d = w max(n·l, 0), g = w [n·l > 0] max(n_s·h, 0)^e, log(n_s·h) per sample; then the Gram and
// Φᵀp sums in double (float x float is exact in double; the cost Σp² - Σ bᵀx cancels). The
// constant column of Φ is w, and w² = w, so the sums need no other weighting.
template <int W> WEFT_INLINE void costKernel(const CostInput& in, CostSums& out) {
    typedef typename Vec<W>::F F;
    typedef typename Vec<W>::I I;
    const BlinnPhongGeometry& geo = *in.geo;
    const int np = geo.padded;
    const F nx = splat<F>(in.n[0]), ny = splat<F>(in.n[1]), nz = splat<F>(in.n[2]);
    const F ef = splat<F>(in.e);
    const bool flat = geo.flatSpecular;
    for (int s = 0; s < np; s += W) {
        const F w = load<F>(in.w + s);
        const F nl =
            nx * load<F>(&geo.l[0][s]) + ny * load<F>(&geo.l[1][s]) + nz * load<F>(&geo.l[2][s]);
        if (!in.specular) { // Lambert + ambient: the diffuse term alone
            store(in.d + s, select(nl > 0.0f, nl) * w);
            store(in.lg + s, F{});
            store(in.g + s, F{});
            continue;
        }
        const F nh = flat ? load<F>(&geo.h[2][s])
                          : nx * load<F>(&geo.h[0][s]) + ny * load<F>(&geo.h[1][s]) +
                                nz * load<F>(&geo.h[2][s]);
        const I lpos = nl > 0.0f;
        const I hpos = nh > 0.0f;
        const F lg =
            flat ? load<F>(&geo.logHz[s]) : select(hpos, logv<F, I>(hpos ? nh : splat<F>(1.0f)));
        store(in.d + s, select(lpos, nl) * w);
        store(in.lg + s, lg);
        store(in.g + s, select(hpos & lpos, expv<F, I>(ef * lg)) * w);
    }
    D4 sd{}, sg{}, sdd{}, sdg{}, sgg{}, sdp[3] = {}, sgp[3] = {};
    for (int s = 0; s < np; s += 4) {
        const D4 dv = __builtin_convertvector(load<F4>(in.d + s), D4);
        const D4 gv = __builtin_convertvector(load<F4>(in.g + s), D4);
        sd += dv;
        sg += gv;
        sdd += dv * dv;
        sdg += dv * gv;
        sgg += gv * gv;
        for (int c = 0; c < 3; ++c) {
            const D4 pv = __builtin_convertvector(load<F4>(in.p[c] + s), D4);
            sdp[c] += dv * pv;
            sgp[c] += gv * pv;
        }
    }
    auto sum4 = [](D4 v) { return (v[0] + v[1]) + (v[2] + v[3]); };
    out.sd = sum4(sd);
    out.sg = sum4(sg);
    out.sdd = sum4(sdd);
    out.sdg = sum4(sdg);
    out.sgg = sum4(sgg);
    for (int c = 0; c < 3; ++c) {
        out.sdp[c] = sum4(sdp[c]);
        out.sgp[c] = sum4(sgp[c]);
    }
}

// float sums: no cancellation left (the residuals are formed per sample) and LM needs JᵀJ and
// the gradient to a few digits only. Padded and left-out samples have D = 0 (d and g carry w;
// ∂d needs it explicitly), so r_cᵀD and ΦᵀD need no weighting either.
// Flat (n_s = (0,0,1)): the highlight does not move with n, so ∂g_u = ∂g_v = 0 and their sums
// (exact zeros) are skipped, 40% of the pass.
template <int W, bool Flat> WEFT_INLINE void derivKernel(const DerivInput& in, DerivSums& out) {
    typedef typename Vec<W>::F F;
    typedef typename Vec<W>::I I;
    const BlinnPhongGeometry& geo = *in.geo;
    const int np = geo.padded;
    const F nx = splat<F>(in.n[0]), ny = splat<F>(in.n[1]), nz = splat<F>(in.n[2]);
    F du[3], dv[3];
    for (int k = 0; k < 3; ++k) {
        du[k] = splat<F>(in.dn[0][k]);
        dv[k] = splat<F>(in.dn[1][k]);
    }
    const F ef = splat<F>(in.e);
    constexpr bool flat = Flat;
    constexpr bool use[5] = {true, true, !Flat, !Flat, true};
    F x[3][3];
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 3; ++i) x[c][i] = splat<F>(in.x[c][i]);
    F dd[5][5] = {}, phiD[3][5] = {}, rD[3][5] = {};
    for (int s = 0; s < np; s += W) {
        const F lx = load<F>(&geo.l[0][s]), ly = load<F>(&geo.l[1][s]), lz = load<F>(&geo.l[2][s]);
        const F hx = load<F>(&geo.h[0][s]), hy = load<F>(&geo.h[1][s]), hz = load<F>(&geo.h[2][s]);
        const F d = load<F>(in.d + s), g = load<F>(in.g + s), lg = load<F>(in.lg + s);
        const F w = load<F>(in.w + s);
        const F nl = nx * lx + ny * ly + nz * lz;
        const F nh = nx * hx + ny * hy + nz * hz;
        const I lpos = nl > 0.0f, hpos = nh > 0.0f;
        // g = 0 where n·l <= 0 or n·h <= 0 (the renderer's gate), so q is too; with n_s = (0,0,1)
        // the highlight does not move with n
        const F q = flat ? F{} : select(hpos, ef * g / (hpos ? nh : splat<F>(1.0f)));
        F D[5];
        D[0] = select(lpos, lx * du[0] + ly * du[1] + lz * du[2]) * w;
        D[1] = select(lpos, lx * dv[0] + ly * dv[1] + lz * dv[2]) * w;
        D[2] = q * (hx * du[0] + hy * du[1] + hz * du[2]);
        D[3] = q * (hx * dv[0] + hy * dv[1] + hz * dv[2]);
        D[4] = g * ef * lg;
        for (int j = 0; j < 5; ++j) {
            if (!use[j]) continue;
            for (int k = j; k < 5; ++k)
                if (use[k]) dd[j][k] += D[j] * D[k];
            phiD[0][j] += d * D[j];
            phiD[1][j] += D[j];
            phiD[2][j] += g * D[j];
        }
        for (int c = 0; c < 3; ++c) {
            const F r = load<F>(in.p[c] + s) - x[c][0] * d - x[c][1] * w - x[c][2] * g;
            for (int j = 0; j < 5; ++j)
                if (use[j]) rD[c][j] += r * D[j];
        }
    }
    for (int j = 0; j < 5; ++j) {
        for (int k = j; k < 5; ++k) out.dd[j][k] = out.dd[k][j] = hsum(dd[j][k]);
        for (int i = 0; i < 3; ++i) {
            out.phiD[i][j] = hsum(phiD[i][j]);
            out.rD[i][j] = hsum(rD[i][j]);
        }
    }
}

// log x where x > 0, else 0, with the cost kernel's code: the n_s = (0,0,1) logs of h_z are
// the values the kernel would compute per evaluation.
template <int W> WEFT_INLINE void logKernel(const float* x, float* out, int n) {
    typedef typename Vec<W>::F F;
    typedef typename Vec<W>::I I;
    for (int s = 0; s < n; s += W) {
        const F v = load<F>(x + s);
        const I pos = v > 0.0f;
        store(out + s, select(pos, logv<F, I>(pos ? v : splat<F>(1.0f))));
    }
}

void costGeneric(const CostInput& in, CostSums& out) { costKernel<4>(in, out); }
void derivGeneric(const DerivInput& in, DerivSums& out) {
    if (in.geo->flatSpecular)
        derivKernel<4, true>(in, out);
    else
        derivKernel<4, false>(in, out);
}
void logGeneric(const float* x, float* out, int n) { logKernel<4>(x, out, n); }
#if defined(__GNUC__) && defined(__x86_64__)
// The same 8-lane code where AVX-512VL is there: its 32 vector registers hold the derivative
// pass's 45 accumulators that spill to the stack with AVX2's 16 (same instructions otherwise,
// so the same results to the bit).
#define WEFT_KERNELS(suffix, isa)                                                                  \
    __attribute__((target(isa))) void cost##suffix(const CostInput& in, CostSums& out) {           \
        costKernel<8>(in, out);                                                                    \
    }                                                                                              \
    __attribute__((target(isa))) void deriv##suffix(const DerivInput& in, DerivSums& out) {        \
        if (in.geo->flatSpecular)                                                                  \
            derivKernel<8, true>(in, out);                                                         \
        else                                                                                       \
            derivKernel<8, false>(in, out);                                                        \
    }                                                                                              \
    __attribute__((target(isa))) void log##suffix(const float* x, float* out, int n) {             \
        logKernel<8>(x, out, n);                                                                   \
    }
WEFT_KERNELS(Avx2, "avx2,fma")
WEFT_KERNELS(Avx512, "avx2,fma,avx512f,avx512vl")
#undef WEFT_KERNELS
enum class Isa { Generic, Avx2, Avx512 };
// What the CPU has, capped by WEFT_BTF_SIMD=generic|avx2 (for comparisons and tests).
Isa isa() {
    __builtin_cpu_init();
    const char* cap = std::getenv("WEFT_BTF_SIMD");
    if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma") ||
        (cap && std::strcmp(cap, "generic") == 0))
        return Isa::Generic;
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                   !(cap && std::strcmp(cap, "avx2") == 0)
               ? Isa::Avx512
               : Isa::Avx2;
}
template <class Fn> Fn pick(Fn generic, Fn avx2, Fn avx512) {
    switch (isa()) {
    case Isa::Avx512: return avx512;
    case Isa::Avx2: return avx2;
    default: return generic;
    }
}
void (*chooseCost())(const CostInput&, CostSums&) {
    return pick(costGeneric, costAvx2, costAvx512);
}
void (*chooseDeriv())(const DerivInput&, DerivSums&) {
    return pick(derivGeneric, derivAvx2, derivAvx512);
}
void (*chooseLog())(const float*, float*, int) { return pick(logGeneric, logAvx2, logAvx512); }
#else
void (*chooseLog())(const float*, float*, int) { return logGeneric; }
void (*chooseCost())(const CostInput&, CostSums&) { return costGeneric; }
void (*chooseDeriv())(const DerivInput&, DerivSums&) { return derivGeneric; }
#endif

void (*const costFn)(const CostInput&, CostSums&) = chooseCost();
void (*const derivFn)(const DerivInput&, DerivSums&) = chooseDeriv();
void (*const logFn)(const float*, float*, int) = chooseLog();

} // namespace

void blinnPhongCost(const CostInput& in, CostSums& out) { costFn(in, out); }
void blinnPhongDeriv(const DerivInput& in, DerivSums& out) { derivFn(in, out); }
void blinnPhongLog(const float* x, float* out, int n) { logFn(x, out, n); }

} // namespace weft
