// Built-in Levenberg-Marquardt for the per-texel Blinn-Phong fit by variable projection: the
// linear coefficients (m, b, k per channel) are eliminated by non-negative least squares, LM
// runs over (u, v, η) with Kaufman's approximation J_c = -P⊥ (∂Φ/∂θ) c_c of the projected
// residual's Jacobian, P⊥ projecting out the columns of Φ whose coefficient is free (> 0).
// The per-sample SIMD passes it calls are in BlinnPhongKernels.cpp.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "btf/BlinnPhongKernels.h"
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
    // the seven sums in one pass: each is a chain of dependent additions, so side by side
    // they overlap (in turn they waited on each other; each sum's order is unchanged)
    double u = 0.0, sum[3] = {0, 0, 0}, sq[3] = {0, 0, 0};
    for (size_t s = 0; s < n; ++s) {
        u += weights[s];
        for (int c = 0; c < 3; ++c) {
            const double v = double(p[size_t(c) * np + s]) * weights[s];
            sum[c] += v;
            sq[c] += v * v;
        }
    }
    used = u;
    for (int c = 0; c < 3; ++c) {
        sums[c] = sum[c];
        squares[c] = sq[c];
    }
}

glm::dvec3 BlinnPhongTexel::normal(double u, double v) const {
    return glm::normalize(n0 + u * t1 + v * t2);
}

BlinnPhongGeometry::BlinnPhongGeometry(const std::vector<glm::vec3>& lights,
                                       const std::vector<glm::vec3>& halves) {
    static std::atomic<unsigned long long> next{0};
    id = ++next;
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
    blinnPhongLog(h[2].data(), logHz.data(), padded);
}

namespace {

// Sums over the samples of products of the basis Φ = (d, 1, g), its derivatives ∂d_j (j = u, v;
// ∂d/∂η = 0), ∂g_j (j = u, v, η) and the residuals r_c = p_c - Φ x_c: everything Kaufman's JᵀJ
// and the gradient need, independent of the channel, so a channel costs O(1) instead of
// O(samples). Per sample d, g, log(n·h) are kept for the derivative pass.
struct Evaluation {
    BlinnPhongResult result;
    double b[3][3] = {};      // Φᵀ p_c per channel
    double gram[3][3] = {};   // ΦᵀΦ
    double inv[3][3][3] = {}; // per channel: (Φ_FᵀΦ_F)⁻¹ on the free coefficients F, else 0
    double sdd[2][2] = {}, sdg[2][3] = {}, sgg[3][3] = {};
    double pd[3][2] = {}, pg[3][3] = {}; // Φᵀ ∂d, Φᵀ ∂g
    double rd[3][2] = {}, rg[3][3] = {}; // r_cᵀ ∂d, r_cᵀ ∂g
    std::vector<float> d, g, lg;         // per padded sample
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
            if (!(mask & (1 << i)) && g[i][0] * y[0] + g[i][1] * y[1] + g[i][2] * y[2] - b[i] < 0.0)
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
    // without the highlight column the NNLS keeps k = 0 (its Gram entries are 0), and every
    // derivative sum of g is multiplied by k or projected out with it
    CostInput in{tx.geometry, {plane(tx, 0), plane(tx, 1), plane(tx, 2)},
                 tx.weights,  {float(ev.nrm.x), float(ev.nrm.y), float(ev.nrm.z)},
                 float(ev.e), ev.d.data(),
                 ev.g.data(), ev.lg.data(),
                 tx.specular};
    CostSums sums;
    blinnPhongCost(in, sums);
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
    DerivInput in{tx.geometry,
                  {plane(tx, 0), plane(tx, 1), plane(tx, 2)},
                  tx.weights,
                  ev.d.data(),
                  ev.g.data(),
                  ev.lg.data(),
                  {float(ev.nrm.x), float(ev.nrm.y), float(ev.nrm.z)},
                  {{float(ev.dn[0].x), float(ev.dn[0].y), float(ev.dn[0].z)},
                   {float(ev.dn[1].x), float(ev.dn[1].y), float(ev.dn[1].z)}},
                  float(ev.e),
                  {}};
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 3; ++i) in.x[c][i] = float(ev.result.coef[c][i]);
    DerivSums s;
    blinnPhongDeriv(in, s);
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
                     std::vector<double>& g, bool specular) {
    // the cost kernel with every sample used: the same single-precision terms the fit saw
    // (libm's scalar powf, underflowing through its errno path, was 10% of a shadowed fit)
    const BlinnPhongGeometry& geo = *tx.geometry;
    // The terms depend on the geometry and the kernel's inputs (normal, exponent) alone, and a
    // texel asks for those of one fit twice (its classification, then whether its lobe is
    // seen): the last ones are kept.
    struct Memo {
        std::vector<float> d, g, lg;
        unsigned long long geometry = 0;
        float n[3] = {0, 0, 0}, e = 0;
        bool flat = false, specular = false;
    };
    static thread_local Memo memo;
    Memo& m = memo;
    const glm::dvec3 nd = tx.normal(theta[0], theta[1]);
    const float n[3] = {float(nd.x), float(nd.y), float(nd.z)}, e = float(std::exp(theta[2]));
    if (m.geometry == geo.id && m.flat == geo.flatSpecular && m.specular == specular &&
        m.n[0] == n[0] && m.n[1] == n[1] && m.n[2] == n[2] && m.e == e) {
        d.assign(m.d.begin(), m.d.begin() + geo.count);
        g.assign(m.g.begin(), m.g.begin() + geo.count);
        return;
    }
    const size_t np = size_t(geo.padded);
    m.d.resize(np);
    m.g.resize(np);
    m.lg.resize(np);
    CostInput in{&geo,
                 {plane(tx, 0), plane(tx, 1), plane(tx, 2)},
                 geo.ones.data(),
                 {n[0], n[1], n[2]},
                 e,
                 m.d.data(),
                 m.g.data(),
                 m.lg.data(),
                 specular};
    CostSums unused;
    blinnPhongCost(in, unused);
    m.geometry = geo.id;
    m.flat = geo.flatSpecular;
    m.specular = specular;
    for (int i = 0; i < 3; ++i) m.n[i] = n[i];
    m.e = e;
    d.assign(m.d.begin(), m.d.begin() + geo.count);
    g.assign(m.g.begin(), m.g.begin() + geo.count);
}

BlinnPhongResult blinnPhongProject(const BlinnPhongTexel& texel, const double theta[3]) {
    static thread_local Evaluation scratch; // its sample arrays allocated once per thread
    Evaluation& ev = scratch;
    evaluate(texel, theta, false, ev);
    ev.result.iterations = 0;
    return ev.result;
}

// The search stops where a step gains less than this share of the cost: over 243 residuals at
// the noise, 0.07 of one unit of χ², far below what moves a parameter by a fraction of its
// standard error. 1e-6 took 30-50% more iterations for a deviation 0.07% lower; 1e-4 took 5%
// more time than 3e-4 for the same errors against the truth on 160 held-out datasets (seeds
// 200-239, PNG and JPEG, with and without cast shadows), and 1e-3 began to lose accuracy on
// JPEG (worst seed's mean normal error 3.41 -> 3.54°).
constexpr double kStop = 3e-4;

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
        // a step that assumed η free (which crawls along the bound for many iterations); held
        // everywhere when the range is one point (BtfNonlinearOptions::fixedExponent)
        const double eta = cur.result.theta[2];
        if (etaMax <= etaMin || (eta >= etaMax - 1e-12 && grad[2] < 0.0) ||
            (eta <= etaMin + 1e-12 && grad[2] > 0.0)) {
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
                if (decrement <= kStop * cur.result.cost + 1e-20) break;
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
                const double stepSize =
                    std::sqrt(step[0] * step[0] + step[1] * step[1] + taken * taken);
                accepted = true;
                ++done;
                std::swap(cur, trial);
                // Damping by the gain ratio ρ = gain / the gain the damped model predicted
                // (Nielsen 1999): λ shrinks by up to 3 where the model held (ρ near 1), less or
                // grows where it did not; a rejected step multiplies it by 10. With a fixed /3
                // and x4, the fits of shadowed data (a first fit still uses its shadowed samples:
                // residuals far above the noise, where Kaufman's JᵀJ describes the cost poorly)
                // rejected 0.81 steps per step taken, mostly in runs from a λ too small; now
                // 0.42, with the same accuracy against the truth (BENCHMARKS.md, btf).
                const double st[3] = {step[0], step[1], taken};
                double predicted = 0.0; // Σr² drop: -2 gradᵀs - sᵀJᵀJ s = sᵀ(λ diag s - grad)
                for (int i = 0; i < 3; ++i)
                    predicted += st[i] * (lambda * jtj[i][i] * st[i] - grad[i]);
                const double rho = predicted > 0.0 ? gain / predicted : 1.0;
                const double t = 2.0 * rho - 1.0;
                lambda = std::max(lambda * std::max(1.0 / 3.0, 1.0 - t * t * t), 1e-9);
                // Converged: the cost changes by less than kStop of itself, or the step is
                // below 1e-6 (radians of normal tilt, relative exponent change).
                if (gain <= kStop * cur.result.cost + 1e-20 || stepSize < 1e-6)
                    it = maxIterations;
                else
                    evaluateDerivatives(tx, cur);
            } else {
                lambda *= 10.0;
            }
        }
        if (!accepted) break;
    }
    cur.result.iterations = done;
    return cur.result;
}

} // namespace weft
