// Built-in Levenberg-Marquardt for the per-texel Blinn-Phong fit by variable projection: the
// linear coefficients (m, b, k per channel) are eliminated by non-negative least squares, LM
// runs over (u, v, η) with Kaufman's approximation J_c = -P⊥ (∂Φ/∂θ) c_c of the projected
// residual's Jacobian, P⊥ projecting out the columns of Φ whose coefficient is free (> 0).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "btf/BlinnPhongTexel.h"
#include "btf/Cholesky3.h"

namespace weft {

void BlinnPhongTexel::setSeedNormal(glm::vec3 n) {
    // n = normalise(u, v, 1): every (u, v) is a normal of the upper hemisphere, so the search
    // never leaves the physical space and needs no bound on the normal.
    n0 = glm::dvec3(0, 0, 1);
    t1 = glm::dvec3(1, 0, 0);
    t2 = glm::dvec3(0, 1, 0);
    glm::dvec3 s(n);
    const double len = glm::length(s);
    s = len > 1e-12 && std::isfinite(len) ? s / len : glm::dvec3(0, 0, 1);
    const double z = std::max(s.z, 0.05);
    start[0] = s.x / z;
    start[1] = s.y / z;
}

void BlinnPhongTexel::updateSquares() {
    for (int c = 0; c < 3; ++c) squares[c] = 0.0;
    for (size_t i = 0; i < values.size(); ++i) squares[i % 3] += double(values[i]) * values[i];
}

void BlinnPhongTexel::prepare() {
    const size_t n = size_t(geometry->count), np = size_t(geometry->padded);
    planeStore.assign(3 * np, 0.0f);
    for (int c = 0; c < 3; ++c)
        for (size_t s = 0; s < n; ++s) planeStore[size_t(c) * np + s] = values[s * 3 + size_t(c)];
    setPlanes(planeStore.data());
}

void BlinnPhongTexel::setPlanes(const float* p, const float* w) {
    planes = p;
    weights = w ? w : geometry->ones.data();
    const size_t n = size_t(geometry->count), np = size_t(geometry->padded);
    used = 0.0;
    for (size_t s = 0; s < n; ++s) used += weights[s];
    for (int c = 0; c < 3; ++c) {
        double sum = 0.0, sq = 0.0;
        for (size_t s = 0; s < n; ++s) {
            const double v = double(p[size_t(c) * np + s]) * weights[s];
            sum += v;
            sq += v * v;
        }
        sums[c] = sum;
        squares[c] = sq;
    }
}

glm::dvec3 BlinnPhongTexel::normal(double u, double v) const {
    return glm::normalize(n0 + u * t1 + v * t2);
}

namespace {

// The per-sample work runs on the padded structure-of-arrays samples W floats at a time (GCC
// vector extensions), with polynomial log/exp instead of libm calls: W = 4 (SSE, or any 16-byte
// SIMD) everywhere, W = 8 in a copy compiled for AVX2 + FMA and chosen at run time on x86-64.
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
    ex = ex + small;                            // small is -1 where true
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

template <class F> WEFT_INLINE double hsum(F v) {
    double s = 0.0;
    for (size_t i = 0; i < sizeof(F) / sizeof(float); ++i) s += double(v[i]);
    return s;
}

struct CostInput {
    const BlinnPhongGeometry* geo;
    const float* p[3]; // planes
    const float* w;    // sample weights
    float n[3], e;
    float *d, *g, *lg; // out, per padded sample
};
struct CostSums {
    double sd, sg, sdd, sdg, sgg, sdp[3], sgp[3];
};

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
        const F nl = nx * load<F>(&geo.l[0][s]) + ny * load<F>(&geo.l[1][s]) +
                     nz * load<F>(&geo.l[2][s]);
        const F nh = flat ? load<F>(&geo.h[2][s])
                          : nx * load<F>(&geo.h[0][s]) + ny * load<F>(&geo.h[1][s]) +
                                nz * load<F>(&geo.h[2][s]);
        const I lpos = nl > 0.0f;
        const I hpos = nh > 0.0f;
        const F lg = flat ? load<F>(&geo.logHz[s])
                          : select(hpos, logv<F, I>(hpos ? nh : splat<F>(1.0f)));
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

struct DerivInput {
    const BlinnPhongGeometry* geo;
    const float* p[3];
    const float* w;
    const float *d, *g, *lg;
    float n[3], dn[2][3], e, x[3][3];
};
// D = (∂d_u, ∂d_v, ∂g_u, ∂g_v, ∂g_η): DᵀD, (d, 1, g)ᵀD, r_cᵀD with r_c = p_c - Φ x_c.
struct DerivSums {
    double dd[5][5], phiD[3][5], rD[3][5];
};

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
    if (in.geo->flatSpecular) derivKernel<4, true>(in, out);
    else derivKernel<4, false>(in, out);
}
void logGeneric(const float* x, float* out, int n) { logKernel<4>(x, out, n); }
void (*chooseCost())(const CostInput&, CostSums&);
void (*chooseDeriv())(const DerivInput&, DerivSums&);
void (*chooseLog())(const float*, float*, int);

#if defined(__GNUC__) && defined(__x86_64__)
__attribute__((target("avx2,fma"))) void costAvx2(const CostInput& in, CostSums& out) {
    costKernel<8>(in, out);
}
__attribute__((target("avx2,fma"))) void derivAvx2(const DerivInput& in, DerivSums& out) {
    if (in.geo->flatSpecular) derivKernel<8, true>(in, out);
    else derivKernel<8, false>(in, out);
}
__attribute__((target("avx2,fma"))) void logAvx2(const float* x, float* out, int n) {
    logKernel<8>(x, out, n);
}
bool haveAvx2() {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}
void (*chooseCost())(const CostInput&, CostSums&) { return haveAvx2() ? costAvx2 : costGeneric; }
void (*chooseDeriv())(const DerivInput&, DerivSums&) {
    return haveAvx2() ? derivAvx2 : derivGeneric;
}
void (*chooseLog())(const float*, float*, int) { return haveAvx2() ? logAvx2 : logGeneric; }
#else
void (*chooseLog())(const float*, float*, int) { return logGeneric; }
void (*chooseCost())(const CostInput&, CostSums&) { return costGeneric; }
void (*chooseDeriv())(const DerivInput&, DerivSums&) { return derivGeneric; }
#endif

// WEFT_BTF_SIMD=generic forces the 4-lane code (for comparisons and tests).
bool forceGeneric() {
    const char* v = std::getenv("WEFT_BTF_SIMD");
    return v && std::strcmp(v, "generic") == 0;
}
void (*const costFn)(const CostInput&, CostSums&) = forceGeneric() ? costGeneric : chooseCost();
void (*const derivFn)(const DerivInput&, DerivSums&) =
    forceGeneric() ? derivGeneric : chooseDeriv();
void (*const logFn)(const float*, float*, int) = forceGeneric() ? logGeneric : chooseLog();

} // namespace

BlinnPhongGeometry::BlinnPhongGeometry(const std::vector<glm::vec3>& lights,
                                       const std::vector<glm::vec3>& halves) {
    count = int(lights.size());
    padded = (count + kBlinnPhongLanes - 1) / kBlinnPhongLanes * kBlinnPhongLanes;
    ones.assign(size_t(padded), 0.0f);
    std::fill(ones.begin(), ones.begin() + count, 1.0f);
    for (int k = 0; k < 3; ++k) {
        l[k].assign(size_t(padded), 0.0f);
        h[k].assign(size_t(padded), 0.0f);
        for (int s = 0; s < count; ++s) {
            l[k][size_t(s)] = lights[size_t(s)][k];
            h[k][size_t(s)] = halves[size_t(s)][k];
        }
    }
    logHz.assign(size_t(padded), 0.0f);
    logFn(h[2].data(), logHz.data(), padded);
}

namespace {

// Sums over the samples of products of the basis Φ = (d, 1, g), its derivatives ∂d_j (j = u, v;
// ∂d/∂η = 0), ∂g_j (j = u, v, η) and the residuals r_c = p_c - Φ x_c: everything Kaufman's JᵀJ
// and the gradient need, independent of the channel, so a channel costs O(1) instead of
// O(samples). Per sample d, g, log(n·h) are kept for the derivative pass.
struct Evaluation {
    BlinnPhongResult result;
    double b[3][3] = {};          // Φᵀ p_c per channel
    double gram[3][3] = {};       // ΦᵀΦ
    double inv[3][3][3] = {};     // per channel: (Φ_FᵀΦ_F)⁻¹ on the free coefficients F, else 0
    double sdd[2][2] = {}, sdg[2][3] = {}, sgg[3][3] = {};
    double pd[3][2] = {}, pg[3][3] = {}; // Φᵀ ∂d, Φᵀ ∂g
    double rd[3][2] = {}, rg[3][3] = {}; // r_cᵀ ∂d, r_cᵀ ∂g
    std::vector<float> d, g, lg; // per padded sample
    glm::dvec3 nrm{0, 0, 1}, dn[2];
    double e = 1.0;
};

// Inverse of the submatrix of g on the coefficients in `mask` (bit i = coefficient i), written
// into inv (zeros elsewhere). False when that submatrix is (nearly) singular.
bool invertSubset(const double g[3][3], int mask, double inv[3][3]) {
    int idx[3], n = 0;
    for (int i = 0; i < 3; ++i)
        if (mask & (1 << i)) idx[n++] = i;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) inv[i][j] = 0.0;
    const double scale = std::max({g[0][0], g[1][1], g[2][2]});
    if (!(scale > 0.0) || !std::isfinite(scale)) return false;
    const double tiny = 1e-12 * scale;
    if (n == 1) {
        const double a = g[idx[0]][idx[0]];
        if (!(a > tiny)) return false;
        inv[idx[0]][idx[0]] = 1.0 / a;
        return true;
    }
    if (n == 2) {
        const int i = idx[0], j = idx[1];
        const double det = g[i][i] * g[j][j] - g[i][j] * g[i][j];
        if (!(det > tiny * std::max(g[i][i], g[j][j]))) return false;
        inv[i][i] = g[j][j] / det;
        inv[j][j] = g[i][i] / det;
        inv[i][j] = inv[j][i] = -g[i][j] / det;
        return true;
    }
    Cholesky3 f;
    if (!f.factor(g, 1e-12)) return false;
    for (int k = 0; k < 3; ++k) {
        const double e[3] = {double(k == 0), double(k == 1), double(k == 2)};
        double col[3];
        f.solve(e, col);
        for (int i = 0; i < 3; ++i) inv[i][k] = col[i];
    }
    return true;
}

// The inverses of G's principal submatrices, computed when first asked for: the three channels
// share G, so one evaluation inverts each subset at most once (per channel it was 19% of a fit).
struct SubsetInverses {
    const double (*g)[3];
    double inv[8][3][3];
    signed char state[8] = {0, 0, 0, 0, 0, 0, 0, 0}; // 0 not yet, 1 invertible, -1 singular
    explicit SubsetInverses(const double gram[3][3]) : g(gram) {}
    const double (*get(int mask))[3] {
        if (state[mask] == 0) state[mask] = invertSubset(g, mask, inv[mask]) ? 1 : -1;
        return state[mask] > 0 ? inv[mask] : nullptr;
    }
};

// Non-negative least squares for 3 coefficients: min Σp² - 2 bᵀx + xᵀGx over x >= 0. G is
// positive definite on every subset that inverts, so the optimum is the unique point meeting
// the KKT conditions: the unconstrained solution y on its free set F is positive there and the
// gradient G y - b is >= 0 on the coefficients held at 0. Free sets are tried in the order they
// occur (all free; no highlight; no ambient; diffuse only; ...), so the first test usually
// decides. Without a KKT point (a singular subset) the cheapest positive subset solution is
// taken, as an exhaustive search would. Returns the cost; x and inv (see Evaluation::inv)
// describe the optimum.
double nnls3(SubsetInverses& subsets, const double b[3], double squares, double x[3],
             double inv[3][3]) {
    static const int order[7] = {7, 3, 5, 1, 6, 2, 4};
    const double(*g)[3] = subsets.g;
    double best = squares;
    int bestMask = 0;
    x[0] = x[1] = x[2] = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) inv[i][j] = 0.0;
    for (int mask : order) {
        const double(*tmp)[3] = subsets.get(mask);
        if (!tmp) continue;
        double y[3], gain = 0.0;
        bool feasible = true;
        for (int i = 0; i < 3; ++i) {
            y[i] = tmp[i][0] * b[0] + tmp[i][1] * b[1] + tmp[i][2] * b[2];
            if ((mask & (1 << i)) && !(y[i] > 0.0)) feasible = false;
            gain += b[i] * y[i];
        }
        if (!feasible) continue;
        bool kkt = true;
        for (int i = 0; i < 3; ++i)
            if (!(mask & (1 << i)) &&
                g[i][0] * y[0] + g[i][1] * y[1] + g[i][2] * y[2] - b[i] < 0.0)
                kkt = false;
        if (squares - gain < best || bestMask == 0 || kkt) {
            best = squares - gain;
            bestMask = mask;
            for (int i = 0; i < 3; ++i) {
                x[i] = y[i];
                for (int j = 0; j < 3; ++j) inv[i][j] = tmp[i][j];
            }
        }
        if (kkt) break;
    }
    return std::max(best, 0.0);
}

const float* plane(const BlinnPhongTexel& tx, int c) {
    return tx.planes + size_t(c) * size_t(tx.geometry->padded);
}

// The cost at θ: the optimal x_c >= 0 for the basis there and Σ residual².
void evaluateCost(const BlinnPhongTexel& tx, const double theta[3], Evaluation& ev) {
    const size_t np = size_t(tx.geometry->padded);
    ev.d.resize(np);
    ev.g.resize(np);
    ev.lg.resize(np);
    const glm::dvec3 w = tx.n0 + theta[0] * tx.t1 + theta[1] * tx.t2;
    const double len = glm::length(w);
    ev.nrm = w / len;
    ev.dn[0] = (tx.t1 - ev.nrm * glm::dot(ev.nrm, tx.t1)) / len;
    ev.dn[1] = (tx.t2 - ev.nrm * glm::dot(ev.nrm, tx.t2)) / len;
    ev.e = std::exp(theta[2]);
    CostInput in{tx.geometry, {plane(tx, 0), plane(tx, 1), plane(tx, 2)}, tx.weights,
                 {float(ev.nrm.x), float(ev.nrm.y), float(ev.nrm.z)}, float(ev.e),
                 ev.d.data(), ev.g.data(), ev.lg.data()};
    CostSums sums;
    costFn(in, sums);
    if (!tx.specular) { // no highlight column: the NNLS keeps k = 0 (its Gram entry is 0)
        sums.sg = sums.sdg = sums.sgg = 0.0;
        for (int c = 0; c < 3; ++c) sums.sgp[c] = 0.0;
    }
    double(&G)[3][3] = ev.gram;
    G[0][0] = sums.sdd;
    G[0][1] = G[1][0] = sums.sd;
    G[0][2] = G[2][0] = sums.sdg;
    G[1][1] = tx.used;
    G[1][2] = G[2][1] = sums.sg;
    G[2][2] = sums.sgg;
    double cost = 0.0;
    SubsetInverses subsets(G);
    for (int c = 0; c < 3; ++c) {
        ev.b[c][0] = sums.sdp[c];
        ev.b[c][1] = tx.sums[c];
        ev.b[c][2] = sums.sgp[c];
        cost += nnls3(subsets, ev.b[c], tx.squares[c], ev.result.coef[c], ev.inv[c]);
    }
    for (int i = 0; i < 3; ++i) ev.result.theta[i] = theta[i];
    ev.result.cost = cost;
}

// The derivative sums at the point of the last evaluateCost.
void evaluateDerivatives(const BlinnPhongTexel& tx, Evaluation& ev) {
    DerivInput in{tx.geometry, {plane(tx, 0), plane(tx, 1), plane(tx, 2)}, tx.weights,
                  ev.d.data(), ev.g.data(), ev.lg.data(),
                  {float(ev.nrm.x), float(ev.nrm.y), float(ev.nrm.z)},
                  {{float(ev.dn[0].x), float(ev.dn[0].y), float(ev.dn[0].z)},
                   {float(ev.dn[1].x), float(ev.dn[1].y), float(ev.dn[1].z)}},
                  float(ev.e), {}};
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 3; ++i) in.x[c][i] = float(ev.result.coef[c][i]);
    DerivSums s;
    derivFn(in, s);
    for (int j = 0; j < 2; ++j) {
        for (int k = 0; k < 2; ++k) ev.sdd[j][k] = s.dd[j][k];
        for (int k = 0; k < 3; ++k) ev.sdg[j][k] = s.dd[j][2 + k];
    }
    for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) ev.sgg[j][k] = s.dd[2 + j][2 + k];
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 2; ++j) ev.pd[i][j] = s.phiD[i][j];
        for (int j = 0; j < 3; ++j) ev.pg[i][j] = s.phiD[i][2 + j];
    }
    for (int c = 0; c < 3; ++c) {
        for (int j = 0; j < 2; ++j) ev.rd[c][j] = s.rD[c][j];
        for (int j = 0; j < 3; ++j) ev.rg[c][j] = s.rD[c][2 + j];
    }
}

void evaluate(const BlinnPhongTexel& tx, const double theta[3], bool derivatives, Evaluation& ev) {
    evaluateCost(tx, theta, ev);
    if (derivatives) evaluateDerivatives(tx, ev);
}

} // namespace

void blinnPhongTerms(const BlinnPhongTexel& tx, const double theta[3], std::vector<double>& d,
                     std::vector<double>& g) {
    // the cost kernel with every sample used: the same single-precision terms the fit saw
    // (libm's scalar powf, underflowing through its errno path, was 10% of a shadowed fit)
    const BlinnPhongGeometry& geo = *tx.geometry;
    static thread_local std::vector<float> fd, fg, flg;
    const size_t np = size_t(geo.padded);
    fd.resize(np);
    fg.resize(np);
    flg.resize(np);
    const glm::dvec3 n = tx.normal(theta[0], theta[1]);
    CostInput in{&geo, {plane(tx, 0), plane(tx, 1), plane(tx, 2)}, geo.ones.data(),
                 {float(n.x), float(n.y), float(n.z)}, float(std::exp(theta[2])),
                 fd.data(), fg.data(), flg.data()};
    CostSums unused;
    costFn(in, unused);
    d.assign(fd.begin(), fd.begin() + geo.count);
    g.assign(fg.begin(), fg.begin() + geo.count);
}

BlinnPhongResult blinnPhongProject(const BlinnPhongTexel& texel, const double theta[3]) {
    Evaluation ev;
    evaluate(texel, theta, false, ev);
    return ev.result;
}

BlinnPhongResult blinnPhongBuiltin(const BlinnPhongTexel& tx, double eta0, double etaMin,
                                   double etaMax, int maxIterations) {
    // per-thread scratch: no allocation per texel once the sample arrays have their size
    static thread_local Evaluation cur, trial;
    const double start[3] = {tx.start[0], tx.start[1], std::min(std::max(eta0, etaMin), etaMax)};
    evaluate(tx, start, true, cur);
    double lambda = 1e-3;
    int done = 0; // accepted steps
    for (int it = 0; it < maxIterations; ++it) {
        double jtj[3][3] = {}, grad[3] = {};
        for (int c = 0; c < 3; ++c) {
            const double* x = cur.result.coef[c];
            const double m = x[0], k = x[2];
            double dd[3][3], phiD[3][3]; // DᵀD and ΦᵀD for D_j = m ∂d_j + k ∂g_j
            for (int j = 0; j < 3; ++j)
                for (int q = 0; q < 3; ++q) {
                    double v = k * k * cur.sgg[j][q];
                    if (j < 2 && q < 2) v += m * m * cur.sdd[j][q];
                    if (j < 2) v += m * k * cur.sdg[j][q];
                    if (q < 2) v += m * k * cur.sdg[q][j];
                    dd[j][q] = v;
                }
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    phiD[i][j] = k * cur.pg[i][j] + (j < 2 ? m * cur.pd[i][j] : 0.0);
            for (int j = 0; j < 3; ++j) // r_cᵀ D_j, D_j = m ∂d_j + k ∂g_j
                grad[j] -= k * cur.rg[c][j] + (j < 2 ? m * cur.rd[c][j] : 0.0);
            // Kaufman: JᵀJ = DᵀD - (Φ_FᵀD)ᵀ (Φ_FᵀΦ_F)⁻¹ Φ_FᵀD over the free coefficients F
            double sol[3][3]; // inv ΦᵀD, column per θ_j
            for (int q = 0; q < 3; ++q)
                for (int i = 0; i < 3; ++i)
                    sol[q][i] = cur.inv[c][i][0] * phiD[0][q] + cur.inv[c][i][1] * phiD[1][q] +
                                cur.inv[c][i][2] * phiD[2][q];
            for (int j = 0; j < 3; ++j)
                for (int q = 0; q < 3; ++q) {
                    double proj = 0.0;
                    for (int i = 0; i < 3; ++i) proj += phiD[i][j] * sol[q][i];
                    jtj[j][q] += dd[j][q] - proj;
                }
        }
        // η at a bound with the descent pointing out of the range: hold it there (active
        // set), so the step in (u, v) is the constrained optimum rather than the projection of
        // a step that assumed η free (which crawls along the bound for many iterations)
        const double eta = cur.result.theta[2];
        if ((eta >= etaMax - 1e-12 && grad[2] < 0.0) || (eta <= etaMin + 1e-12 && grad[2] > 0.0)) {
            for (int j = 0; j < 3; ++j) jtj[2][j] = jtj[j][2] = 0.0;
            jtj[2][2] = 1.0;
            grad[2] = 0.0;
        }
        // Converged when even the undamped Gauss-Newton step predicts a gain below the stopping
        // threshold (the decrement gradᵀ (JᵀJ)⁻¹ grad): near the optimum the single-precision
        // terms make the cost itself uncertain by about that much, and trial steps there were
        // rejected up to 8 times before giving up.
        {
            double a[3][3];
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) a[i][j] = jtj[i][j] + (i == j ? 1e-12 : 0.0);
            Cholesky3 f;
            if (f.factor(a, 1e-14)) {
                double gn[3];
                f.solve(grad, gn);
                const double decrement = grad[0] * gn[0] + grad[1] * gn[1] + grad[2] * gn[2];
                if (decrement <= 1e-4 * cur.result.cost + 1e-20) break;
            }
        }
        bool accepted = false;
        for (int attempt = 0; attempt < 8 && !accepted; ++attempt) {
            double a[3][3];
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    a[i][j] = jtj[i][j] + (i == j ? lambda * jtj[i][i] + 1e-12 : 0.0);
            Cholesky3 f;
            if (!f.factor(a, 1e-14)) {
                lambda *= 10.0;
                continue;
            }
            const double rhs[3] = {-grad[0], -grad[1], -grad[2]};
            double step[3];
            f.solve(rhs, step);
            double next[3] = {cur.result.theta[0] + step[0], cur.result.theta[1] + step[1],
                              std::min(std::max(cur.result.theta[2] + step[2], etaMin), etaMax)};
            evaluate(tx, next, false, trial); // derivatives only once accepted
            if (trial.result.cost < cur.result.cost) {
                const double gain = cur.result.cost - trial.result.cost;
                const double taken = next[2] - cur.result.theta[2]; // after the projection
                const double stepSize = std::sqrt(step[0] * step[0] + step[1] * step[1] +
                                                  taken * taken);
                accepted = true;
                ++done;
                std::swap(cur, trial);
                lambda = std::max(lambda / 3.0, 1e-9);
                // Converged: the cost changes by less than 1e-4 of itself (over 243 residuals
                // at the noise that is 0.02 of one unit of χ², far below what moves a parameter
                // by a fraction of its standard error; 1e-6 took 30-50% more iterations for a
                // deviation 0.07% lower), or the step is below 1e-6 (radians of normal tilt,
                // relative exponent change).
                if (gain <= 1e-4 * cur.result.cost + 1e-20 || stepSize < 1e-6)
                    it = maxIterations;
                else
                    evaluateDerivatives(tx, cur);
            } else {
                lambda *= 4.0;
            }
        }
        if (!accepted) break;
    }
    cur.result.iterations = done;
    return cur.result;
}

} // namespace weft
