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

void BlinnPhongTexel::updateSquares() {
    for (int c = 0; c < 3; ++c) squares[c] = 0.0;
    for (size_t i = 0; i < values.size(); ++i) squares[i % 3] += double(values[i]) * values[i];
}

glm::dvec3 BlinnPhongTexel::normal(double u, double v) const {
    return glm::normalize(n0 + u * t1 + v * t2);
}

namespace {

// Sums over the samples of products of the basis Φ = (d, 1, g), its derivatives ∂d_j (j = u, v;
// ∂d/∂η = 0), ∂g_j (j = u, v, η) and the data: everything Kaufman's JᵀJ and the gradient need,
// independent of the channel, so a channel costs O(1) instead of O(samples).
struct Evaluation {
    BlinnPhongResult result;
    double b[3][3] = {};          // Φᵀ p_c per channel
    double sdd[2][2] = {}, sdg[2][3] = {}, sgg[3][3] = {};
    double pd[3][2] = {}, pg[3][3] = {}; // Φᵀ ∂d, Φᵀ ∂g
    double yd[3][2] = {}, yg[3][3] = {}; // p_cᵀ ∂d, p_cᵀ ∂g
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
    ev = Evaluation();
    const glm::dvec3 w = tx.n0 + theta[0] * tx.t1 + theta[1] * tx.t2;
    const double len = glm::length(w);
    const glm::dvec3 nrm = w / len;
    const glm::dvec3 dn[2] = {(tx.t1 - nrm * glm::dot(nrm, tx.t1)) / len,
                              (tx.t2 - nrm * glm::dot(nrm, tx.t2)) / len};
    const double e = std::exp(theta[2]);
    double G[3][3] = {};
    for (size_t s = 0; s < n; ++s) {
        const glm::dvec3 l(L[s]), h(H[s]);
        const double nl = glm::dot(nrm, l), nh = glm::dot(nrm, h);
        const double d = nl > 0 ? nl : 0.0;
        // float log/exp: twice as fast as double and far below the data's precision
        const double lg = nh > 0 ? double(std::log(float(nh))) : 0.0;
        const double g = nh > 0 ? double(std::exp(float(e * lg))) : 0.0;
        const double phi[3] = {d, 1.0, g};
        const double p[3] = {tx.values[s * 3], tx.values[s * 3 + 1], tx.values[s * 3 + 2]};
        for (int i = 0; i < 3; ++i) {
            for (int j = i; j < 3; ++j) G[i][j] += phi[i] * phi[j];
            for (int c = 0; c < 3; ++c) ev.b[c][i] += phi[i] * p[c];
        }
        if (!derivatives) continue;
        double dd[2], dg[3];
        for (int j = 0; j < 2; ++j) {
            dd[j] = nl > 0 ? glm::dot(l, dn[j]) : 0.0;
            dg[j] = nh > 0 ? e * g / nh * glm::dot(h, dn[j]) : 0.0;
        }
        dg[2] = g * e * lg;
        for (int j = 0; j < 2; ++j) {
            for (int q = 0; q < 2; ++q) ev.sdd[j][q] += dd[j] * dd[q];
            for (int q = 0; q < 3; ++q) ev.sdg[j][q] += dd[j] * dg[q];
        }
        for (int j = 0; j < 3; ++j)
            for (int q = 0; q < 3; ++q) ev.sgg[j][q] += dg[j] * dg[q];
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 2; ++j) ev.pd[i][j] += phi[i] * dd[j];
            for (int j = 0; j < 3; ++j) ev.pg[i][j] += phi[i] * dg[j];
        }
        for (int c = 0; c < 3; ++c) {
            for (int j = 0; j < 2; ++j) ev.yd[c][j] += p[c] * dd[j];
            for (int j = 0; j < 3; ++j) ev.yg[c][j] += p[c] * dg[j];
        }
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < i; ++j) G[i][j] = G[j][i];
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

} // namespace

BlinnPhongResult blinnPhongProject(const BlinnPhongTexel& texel, const double theta[3]) {
    Evaluation ev;
    evaluate(texel, theta, false, ev);
    return ev.result;
}

BlinnPhongResult blinnPhongBuiltin(const BlinnPhongTexel& tx, double eta0, double etaMin,
                                   double etaMax, int maxIterations) {
    Evaluation cur, trial;
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
            for (int j = 0; j < 3; ++j) {
                // r_cᵀ D_j = p_cᵀ D_j - x_cᵀ Φᵀ D_j
                double rD = k * cur.yg[c][j] + (j < 2 ? m * cur.yd[c][j] : 0.0);
                for (int i = 0; i < 3; ++i) rD -= x[i] * phiD[i][j];
                grad[j] -= rD;
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
