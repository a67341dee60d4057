// Built-in Levenberg-Marquardt for the per-texel Blinn-Phong fit by variable projection: the
// linear coefficients (m, b, k per channel) are eliminated, LM runs over (u, v, η) with
// Kaufman's approximation J_c = -P⊥ (∂Φ/∂θ) c_c of the projected residual's Jacobian.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "btf/BlinnPhongTexel.h"
#include "btf/Cholesky3.h"

namespace weft {

void BlinnPhongTexel::setSeedNormal(glm::vec3 n) {
    n0 = glm::normalize(glm::dvec3(n));
    const glm::dvec3 a = std::fabs(n0.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    t1 = glm::normalize(a - n0 * glm::dot(a, n0));
    t2 = glm::cross(n0, t1);
}

void BlinnPhongTexel::updateSquares() {
    for (int c = 0; c < 3; ++c) squares[c] = 0.0;
    for (size_t i = 0; i < values.size(); ++i) squares[i % 3] += double(values[i]) * values[i];
}

BlinnPhongGeometry::BlinnPhongGeometry(const std::vector<glm::vec3>& lights,
                                       const std::vector<glm::vec3>& halves) {
    count = int(lights.size());
    padded = (count + kBlinnPhongLanes - 1) / kBlinnPhongLanes * kBlinnPhongLanes;
    for (int k = 0; k < 3; ++k) {
        l[k].assign(size_t(padded), 0.0f);
        h[k].assign(size_t(padded), 0.0f);
        for (int s = 0; s < count; ++s) {
            l[k][size_t(s)] = lights[size_t(s)][k];
            h[k][size_t(s)] = halves[size_t(s)][k];
        }
    }
}

void BlinnPhongTexel::prepare() {
    updateSquares();
    const size_t n = size_t(geometry->count), np = size_t(geometry->padded);
    planes.assign(3 * np, 0.0f);
    for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (size_t s = 0; s < n; ++s) {
            planes[size_t(c) * np + s] = values[s * 3 + size_t(c)];
            sum += values[s * 3 + size_t(c)];
        }
        sums[c] = sum;
    }
}

glm::dvec3 BlinnPhongTexel::normal(double u, double v) const {
    return glm::normalize(n0 + u * t1 + v * t2);
}

namespace {

// Four floats (one SSE register; 32-byte vectors without AVX get their comparisons
// scalarised): the per-sample work runs on the padded structure-of-arrays samples four at a
// time, with a polynomial log/exp instead of libm calls.
typedef float F8 __attribute__((vector_size(16)));
typedef int I8 __attribute__((vector_size(16)));
typedef double D4 __attribute__((vector_size(32)));
typedef float F4 __attribute__((vector_size(16)));
constexpr int kLanes = 4;
static_assert(kBlinnPhongLanes % kLanes == 0, "padding must hold whole vectors");

inline F8 load8(const float* p) {
    F8 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline void store8(float* p, F8 v) { std::memcpy(p, &v, sizeof v); }
inline F8 splat(float x) { return F8{x, x, x, x}; }
inline F8 select(I8 mask, F8 a) { return F8(I8(a) & mask); } // mask ? a : 0
inline F8 asFloat(I8 v) { return F8(v); }

// Natural log for x > 0 (Cephes logf: mantissa in [√½, √2), degree-8 polynomial; ~1 ulp).
inline F8 log8(F8 x) {
    I8 bits = I8(x);
    I8 ex = ((bits >> 23) & 0xff) - 126;
    F8 m = asFloat((bits & 0x007fffff) | 0x3f000000); // [0.5, 1)
    const I8 small = m < splat(0.707106781186547524f);
    ex = ex + small;                                   // small is -1 where true
    m = m + select(small, m) - splat(1.0f);
    const F8 z = m * m;
    F8 y = splat(7.0376836292e-2f);
    y = y * m + splat(-1.1514610310e-1f);
    y = y * m + splat(1.1676998740e-1f);
    y = y * m + splat(-1.2420140846e-1f);
    y = y * m + splat(1.4249322787e-1f);
    y = y * m + splat(-1.6668057665e-1f);
    y = y * m + splat(2.0000714765e-1f);
    y = y * m + splat(-2.4999993993e-1f);
    y = y * m + splat(3.3333331174e-1f);
    y = y * m * z;
    const F8 fe = __builtin_convertvector(ex, F8);
    y = y + fe * splat(-2.12194440e-4f) - splat(0.5f) * z;
    return m + y + fe * splat(0.693359375f);
}

// exp(x) for x <= 0 (Cephes expf: x = n ln2 + r, degree-5 polynomial; ~1 ulp); 0 below -87.
inline F8 exp8(F8 x) {
    const I8 alive = x > splat(-87.0f);
    x = x < splat(-87.0f) ? splat(-87.0f) : x;
    const F8 fx = x * splat(1.44269504088896341f) + splat(0.5f);
    I8 n = __builtin_convertvector(fx, I8); // truncation towards 0; fx > 0 only near x = 0
    F8 fn = __builtin_convertvector(n, F8);
    const I8 over = fn > fx;
    n = n + over;
    fn = __builtin_convertvector(n, F8);
    x = x - fn * splat(0.693359375f) - fn * splat(-2.12194440e-4f);
    const F8 z = x * x;
    F8 y = splat(1.9875691500e-4f);
    y = y * x + splat(1.3981999507e-3f);
    y = y * x + splat(8.3334519073e-3f);
    y = y * x + splat(4.1665795894e-2f);
    y = y * x + splat(1.6666665459e-1f);
    y = y * x + splat(5.0000001201e-1f);
    y = y * z + x + splat(1.0f);
    return select(alive, y * asFloat((n + 127) << 23));
}

inline double hsum(F8 v) {
    double s = 0.0;
    for (int i = 0; i < kLanes; ++i) s += double(v[i]);
    return s;
}

// Sums over the samples of products of the basis Φ = (d, 1, g), its derivatives ∂d_j (j = u, v;
// ∂d/∂η = 0), ∂g_j (j = u, v, η) and the residuals r_c = p_c - Φ x_c: everything Kaufman's JᵀJ
// and the gradient need, independent of the channel, so a channel costs O(1) instead of
// O(samples). Per sample d, g, log(n·h) are kept for the derivative pass.
struct Evaluation {
    BlinnPhongResult result;
    double b[3][3] = {};          // Φᵀ p_c per channel
    double sdd[2][2] = {}, sdg[2][3] = {}, sgg[3][3] = {};
    double pd[3][2] = {}, pg[3][3] = {}; // Φᵀ ∂d, Φᵀ ∂g
    double rd[3][2] = {}, rg[3][3] = {}; // r_cᵀ ∂d, r_cᵀ ∂g
    bool derivatives = false;
    Cholesky3 factor;
    std::vector<float> d, g, lg; // per padded sample
    glm::dvec3 nrm{0, 0, 1}, dn[2];
    double e = 1.0;
};

// Solves the 3x3 Gram system with a tiny ridge when it is (nearly) singular.
bool factorGram(const double g[3][3], Cholesky3& f) {
    if (f.factor(g, 1e-12)) return true;
    double r[3][3];
    const double ridge = 1e-9 * (g[0][0] + g[1][1] + g[2][2]) + 1e-30;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r[i][j] = g[i][j] + (i == j ? ridge : 0.0);
    return f.factor(r, 0.0);
}

// The cost at θ: d, g per sample (float, far below the data's precision), Gram matrix and Φᵀp
// accumulated in double (the cost Σp² - Σ bᵀx cancels), the optimal x_c and the cost.
void evaluateCost(const BlinnPhongTexel& tx, const double theta[3], Evaluation& ev) {
    const BlinnPhongGeometry& geo = *tx.geometry;
    const int np = geo.padded;
    ev.derivatives = false;
    ev.d.resize(size_t(np));
    ev.g.resize(size_t(np));
    ev.lg.resize(size_t(np));
    const glm::dvec3 w = tx.n0 + theta[0] * tx.t1 + theta[1] * tx.t2;
    const double len = glm::length(w);
    ev.nrm = w / len;
    ev.dn[0] = (tx.t1 - ev.nrm * glm::dot(ev.nrm, tx.t1)) / len;
    ev.dn[1] = (tx.t2 - ev.nrm * glm::dot(ev.nrm, tx.t2)) / len;
    ev.e = std::exp(theta[2]);
    const F8 nx = splat(float(ev.nrm.x)), ny = splat(float(ev.nrm.y)), nz = splat(float(ev.nrm.z));
    const F8 ef = splat(float(ev.e));
    for (int s = 0; s < np; s += kLanes) {
        const F8 nl = nx * load8(&geo.l[0][s]) + ny * load8(&geo.l[1][s]) + nz * load8(&geo.l[2][s]);
        const F8 nh = nx * load8(&geo.h[0][s]) + ny * load8(&geo.h[1][s]) + nz * load8(&geo.h[2][s]);
        const I8 hpos = nh > splat(0.0f);
        const F8 lg = select(hpos, log8(hpos ? nh : splat(1.0f)));
        store8(&ev.d[size_t(s)], select(nl > splat(0.0f), nl));
        store8(&ev.lg[size_t(s)], lg);
        store8(&ev.g[size_t(s)], select(hpos, exp8(ef * lg)));
    }
    // float x float is exact in double: accumulate the products in double, four lanes at a time
    D4 sd{}, sg{}, sdd{}, sdg{}, sgg{}, sdp[3] = {}, sgp[3] = {};
    const float* p[3] = {&tx.planes[0], &tx.planes[size_t(np)], &tx.planes[2 * size_t(np)]};
    for (int s = 0; s < np; s += 4) {
        F4 d4, g4;
        std::memcpy(&d4, &ev.d[size_t(s)], sizeof d4);
        std::memcpy(&g4, &ev.g[size_t(s)], sizeof g4);
        const D4 dv = __builtin_convertvector(d4, D4), gv = __builtin_convertvector(g4, D4);
        sd += dv;
        sg += gv;
        sdd += dv * dv;
        sdg += dv * gv;
        sgg += gv * gv;
        for (int c = 0; c < 3; ++c) {
            F4 p4;
            std::memcpy(&p4, p[c] + s, sizeof p4);
            const D4 pv = __builtin_convertvector(p4, D4);
            sdp[c] += dv * pv;
            sgp[c] += gv * pv;
        }
    }
    auto sum4 = [](D4 v) { return (v[0] + v[1]) + (v[2] + v[3]); };
    double G[3][3];
    G[0][0] = sum4(sdd);
    G[0][1] = G[1][0] = sum4(sd);
    G[0][2] = G[2][0] = sum4(sdg);
    G[1][1] = double(geo.count);
    G[1][2] = G[2][1] = sum4(sg);
    G[2][2] = sum4(sgg);
    for (int c = 0; c < 3; ++c) {
        ev.b[c][0] = sum4(sdp[c]);
        ev.b[c][1] = tx.sums[c];
        ev.b[c][2] = sum4(sgp[c]);
    }
    factorGram(G, ev.factor);
    double cost = 0.0; // Σ p² - Σ_c b_cᵀ x_c at the least-squares solution
    for (int c = 0; c < 3; ++c) {
        ev.factor.solve(ev.b[c], ev.result.coef[c]);
        cost += tx.squares[c];
        for (int i = 0; i < 3; ++i) cost -= ev.b[c][i] * ev.result.coef[c][i];
    }
    for (int i = 0; i < 3; ++i) ev.result.theta[i] = theta[i];
    ev.result.cost = std::max(cost, 0.0);
}

// The derivative sums at the point of the last evaluateCost (float: no cancellation left, the
// residuals are formed per sample; LM needs JᵀJ and the gradient to a few digits only).
void evaluateDerivatives(const BlinnPhongTexel& tx, Evaluation& ev) {
    const BlinnPhongGeometry& geo = *tx.geometry;
    const int np = geo.padded;
    const F8 nx = splat(float(ev.nrm.x)), ny = splat(float(ev.nrm.y)), nz = splat(float(ev.nrm.z));
    F8 du[3], dv[3];
    for (int k = 0; k < 3; ++k) {
        du[k] = splat(float(ev.dn[0][k]));
        dv[k] = splat(float(ev.dn[1][k]));
    }
    const F8 ef = splat(float(ev.e));
    F8 x[3][3];
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 3; ++i) x[c][i] = splat(float(ev.result.coef[c][i]));
    // D = (∂d_u, ∂d_v, ∂g_u, ∂g_v, ∂g_η); sums DᵀD (15), (d, 1, g)ᵀD (15), r_cᵀD (15)
    F8 dd[5][5] = {}, phiD[3][5] = {}, rD[3][5] = {};
    const size_t n = size_t(np);
    for (int s = 0; s < np; s += kLanes) {
        const F8 lx = load8(&geo.l[0][s]), ly = load8(&geo.l[1][s]), lz = load8(&geo.l[2][s]);
        const F8 hx = load8(&geo.h[0][s]), hy = load8(&geo.h[1][s]), hz = load8(&geo.h[2][s]);
        const F8 d = load8(&ev.d[size_t(s)]), g = load8(&ev.g[size_t(s)]);
        const F8 lg = load8(&ev.lg[size_t(s)]);
        const F8 nl = nx * lx + ny * ly + nz * lz;
        const F8 nh = nx * hx + ny * hy + nz * hz;
        const I8 lpos = nl > splat(0.0f), hpos = nh > splat(0.0f);
        const F8 q = select(hpos, ef * g / (hpos ? nh : splat(1.0f)));
        F8 D[5];
        D[0] = select(lpos, lx * du[0] + ly * du[1] + lz * du[2]);
        D[1] = select(lpos, lx * dv[0] + ly * dv[1] + lz * dv[2]);
        D[2] = q * (hx * du[0] + hy * du[1] + hz * du[2]);
        D[3] = q * (hx * dv[0] + hy * dv[1] + hz * dv[2]);
        D[4] = g * ef * lg;
        const F8 phi[3] = {d, splat(1.0f), g};
        for (int j = 0; j < 5; ++j) {
            for (int q2 = j; q2 < 5; ++q2) dd[j][q2] += D[j] * D[q2];
            for (int i = 0; i < 3; ++i) phiD[i][j] += phi[i] * D[j];
        }
        for (int c = 0; c < 3; ++c) {
            const F8 r = load8(&tx.planes[size_t(c) * n + size_t(s)]) - x[c][0] * d - x[c][1] -
                         x[c][2] * g;
            for (int j = 0; j < 5; ++j) rD[c][j] += r * D[j];
        }
    }
    // padded samples: D = 0 there, so the constant basis adds nothing either
    double sdd5[5][5];
    for (int j = 0; j < 5; ++j)
        for (int q2 = j; q2 < 5; ++q2) sdd5[j][q2] = sdd5[q2][j] = hsum(dd[j][q2]);
    for (int j = 0; j < 2; ++j) {
        for (int q2 = 0; q2 < 2; ++q2) ev.sdd[j][q2] = sdd5[j][q2];
        for (int q2 = 0; q2 < 3; ++q2) ev.sdg[j][q2] = sdd5[j][2 + q2];
    }
    for (int j = 0; j < 3; ++j)
        for (int q2 = 0; q2 < 3; ++q2) ev.sgg[j][q2] = sdd5[2 + j][2 + q2];
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 2; ++j) ev.pd[i][j] = hsum(phiD[i][j]);
        for (int j = 0; j < 3; ++j) ev.pg[i][j] = hsum(phiD[i][2 + j]);
    }
    for (int c = 0; c < 3; ++c) {
        for (int j = 0; j < 2; ++j) ev.rd[c][j] = hsum(rD[c][j]);
        for (int j = 0; j < 3; ++j) ev.rg[c][j] = hsum(rD[c][2 + j]);
    }
    ev.derivatives = true;
}

void evaluate(const BlinnPhongTexel& tx, const double theta[3], bool derivatives, Evaluation& ev) {
    evaluateCost(tx, theta, ev);
    if (derivatives) evaluateDerivatives(tx, ev);
}

} // namespace

BlinnPhongResult blinnPhongProject(const BlinnPhongTexel& texel, const double theta[3]) {
    Evaluation ev;
    evaluate(texel, theta, false, ev);
    return ev.result;
}

BlinnPhongResult blinnPhongBuiltin(const BlinnPhongTexel& tx, double eta0, double etaMin,
                                   double etaMax, int maxIterations) {
    // per-thread scratch: no allocation per texel once the sample arrays have their size
    static thread_local Evaluation cur, trial;
    const double start[3] = {0.0, 0.0, std::min(std::max(eta0, etaMin), etaMax)};
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
            double sol[3][3]; // G⁻¹ ΦᵀD, column per θ_j
            for (int q = 0; q < 3; ++q) {
                const double col[3] = {phiD[0][q], phiD[1][q], phiD[2][q]};
                cur.factor.solve(col, sol[q]);
            }
            for (int j = 0; j < 3; ++j)
                for (int q = 0; q < 3; ++q) {
                    double proj = 0.0;
                    for (int i = 0; i < 3; ++i) proj += phiD[i][j] * sol[q][i];
                    jtj[j][q] += dd[j][q] - proj;
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
                const double stepSize = std::sqrt(step[0] * step[0] + step[1] * step[1] +
                                                  step[2] * step[2]);
                accepted = true;
                ++done;
                std::swap(cur, trial);
                lambda = std::max(lambda / 3.0, 1e-9);
                // Converged: the cost changes by less than 1e-6 of itself, or the step is below
                // 1e-6 (radians of normal tilt, relative exponent change).
                if (gain <= 1e-6 * cur.result.cost + 1e-20 || stepSize < 1e-6)
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
