// Built-in Levenberg-Marquardt for the per-texel Blinn-Phong fit by variable projection: the
// linear coefficients (m, b, k per channel) are eliminated, LM runs over (u, v, η) with
// Kaufman's approximation J_c = -P⊥ (∂Φ/∂θ) c_c of the projected residual's Jacobian.
#include <cmath>

#include "btf/BlinnPhongTexel.h"
#include "btf/Cholesky3.h"

namespace weft {

void BlinnPhongTexel::setSeedNormal(glm::vec3 n) {
    n0 = glm::normalize(glm::dvec3(n));
    const glm::dvec3 a = std::fabs(n0.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    t1 = glm::normalize(a - n0 * glm::dot(a, n0));
    t2 = glm::cross(n0, t1);
}

glm::dvec3 BlinnPhongTexel::normal(double u, double v) const {
    return glm::normalize(n0 + u * t1 + v * t2);
}

namespace {

struct Evaluation {
    BlinnPhongResult result;
    std::vector<double> d, g, dd[2], dg[3]; // basis values and derivatives per sample
    double gram[3][3] = {};
    Cholesky3 factor;
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

void evaluate(const BlinnPhongTexel& tx, const double theta[3], bool derivatives, Evaluation& ev) {
    const std::vector<glm::vec3>& L = *tx.lights;
    const std::vector<glm::vec3>& H = *tx.halves;
    const size_t n = L.size();
    ev.d.resize(n);
    ev.g.resize(n);
    for (auto& v : ev.dd) v.resize(derivatives ? n : 0);
    for (auto& v : ev.dg) v.resize(derivatives ? n : 0);
    const glm::dvec3 w = tx.n0 + theta[0] * tx.t1 + theta[1] * tx.t2;
    const double len = glm::length(w);
    const glm::dvec3 nrm = w / len;
    const glm::dvec3 dn[2] = {(tx.t1 - nrm * glm::dot(nrm, tx.t1)) / len,
                              (tx.t2 - nrm * glm::dot(nrm, tx.t2)) / len};
    const double e = std::exp(theta[2]);
    double G[3][3] = {}, b[3][3] = {}; // b[c] = Φᵀ p_c
    for (size_t s = 0; s < n; ++s) {
        const glm::dvec3 l(L[s]), h(H[s]);
        const double nl = glm::dot(nrm, l), nh = glm::dot(nrm, h);
        const double d = nl > 0 ? nl : 0.0;
        // float log/exp: twice as fast as double and far below the data's precision
        const double lg = nh > 0 ? double(std::log(float(nh))) : 0.0;
        const double g = nh > 0 ? double(std::exp(float(e * lg))) : 0.0;
        ev.d[s] = d;
        ev.g[s] = g;
        if (derivatives) {
            for (int j = 0; j < 2; ++j) {
                ev.dd[j][s] = nl > 0 ? glm::dot(l, dn[j]) : 0.0;
                ev.dg[j][s] = nh > 0 ? e * g / nh * glm::dot(h, dn[j]) : 0.0;
            }
            ev.dg[2][s] = g * e * lg;
        }
        const double phi[3] = {d, 1.0, g};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) G[i][j] += phi[i] * phi[j];
        for (int c = 0; c < 3; ++c) {
            const double p = tx.values[s * 3 + size_t(c)];
            for (int i = 0; i < 3; ++i) b[c][i] += phi[i] * p;
        }
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) ev.gram[i][j] = G[i][j];
    factorGram(G, ev.factor);
    for (int c = 0; c < 3; ++c) ev.factor.solve(b[c], ev.result.coef[c]);
    double cost = 0.0;
    for (size_t s = 0; s < n; ++s)
        for (int c = 0; c < 3; ++c) {
            const double* k = ev.result.coef[c];
            const double r = tx.values[s * 3 + size_t(c)] - (k[0] * ev.d[s] + k[1] + k[2] * ev.g[s]);
            cost += r * r;
        }
    for (int i = 0; i < 3; ++i) ev.result.theta[i] = theta[i];
    ev.result.cost = cost;
}

} // namespace

BlinnPhongResult blinnPhongProject(const BlinnPhongTexel& texel, const double theta[3]) {
    Evaluation ev;
    evaluate(texel, theta, false, ev);
    return ev.result;
}

BlinnPhongResult blinnPhongBuiltin(const BlinnPhongTexel& tx, double eta0, double etaMin,
                                   double etaMax, int maxIterations) {
    thread_local Evaluation cur, trial; // reused: no allocations per texel
    const double start[3] = {0.0, 0.0, std::min(std::max(eta0, etaMin), etaMax)};
    evaluate(tx, start, true, cur);
    double lambda = 1e-3;
    int done = 0; // accepted steps
    for (int it = 0; it < maxIterations; ++it) {
        const size_t n = cur.d.size();
        double jtj[3][3] = {}, grad[3] = {};
        for (int c = 0; c < 3; ++c) {
            const double m = cur.result.coef[c][0], k = cur.result.coef[c][2];
            double dd[3][3] = {}, phiD[3][3] = {}; // DᵀD, ΦᵀD (rows: basis, cols: θ_j)
            for (size_t s = 0; s < n; ++s) {
                const double D[3] = {m * cur.dd[0][s] + k * cur.dg[0][s],
                                     m * cur.dd[1][s] + k * cur.dg[1][s], k * cur.dg[2][s]};
                const double phi[3] = {cur.d[s], 1.0, cur.g[s]};
                const double r = tx.values[s * 3 + size_t(c)] -
                                 (m * cur.d[s] + cur.result.coef[c][1] + k * cur.g[s]);
                for (int j = 0; j < 3; ++j) {
                    grad[j] -= D[j] * r;
                    for (int q = 0; q < 3; ++q) {
                        dd[j][q] += D[j] * D[q];
                        phiD[j][q] += phi[j] * D[q];
                    }
                }
            }
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
            evaluate(tx, next, true, trial);
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
