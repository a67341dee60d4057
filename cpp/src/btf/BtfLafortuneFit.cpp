// Per-texel diffuse + Lafortune lobes (seed eq. 4.10/4.11) by variable projection: the model is
// linear in (m, b, ρ_1.., per channel) and nonlinear in θ = (u, v, C_x1, C_y1, η_1, ...), where
// n = normalise(u, v, 1) and e_j = exp(η_j). The physical space is kept by construction:
// n_z > 0, C_z = 1, η_j in [0, log 4096] (projected steps) and m, b, ρ_j >= 0 (non-negative
// least squares per channel; the projection of Kaufman's Jacobian uses the free coefficients).
// Every θ_k moves one basis function only, so Kaufman's JᵀJ and the gradient come from
// channel-independent sample sums as in the Blinn-Phong solver.
#include <weft/BtfNonlinear.h>
#include <weft/Error.h>

#include <algorithm>
#include <cmath>

#include "btf/BlinnPhongTexel.h"
#include "btf/BtfParallel.h"
#include "btf/BtfShadowClassify.h"

namespace weft {

namespace {

constexpr int kMaxBasis = 4, kMaxTheta = 8;

// Cholesky of a small symmetric matrix (n <= 8) with a relative pivot check.
struct CholeskyN {
    int n = 0;
    double l[kMaxTheta][kMaxTheta] = {};
    bool factor(const double a[kMaxTheta][kMaxTheta], int size, double relTol) {
        n = size;
        double scale = 0.0;
        for (int i = 0; i < n; ++i) scale = std::max(scale, a[i][i]);
        if (!(scale > 0.0) || !std::isfinite(scale)) return false;
        for (int j = 0; j < n; ++j) {
            double d = a[j][j];
            for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
            if (!(d > relTol * scale)) return false;
            l[j][j] = std::sqrt(d);
            for (int i = j + 1; i < n; ++i) {
                double v = a[i][j];
                for (int k = 0; k < j; ++k) v -= l[i][k] * l[j][k];
                l[i][j] = v / l[j][j];
            }
        }
        return true;
    }
    void solve(const double* b, double* x) const {
        double y[kMaxTheta];
        for (int i = 0; i < n; ++i) {
            double v = b[i];
            for (int k = 0; k < i; ++k) v -= l[i][k] * y[k];
            y[i] = v / l[i][i];
        }
        for (int i = n - 1; i >= 0; --i) {
            double v = y[i];
            for (int k = i + 1; k < n; ++k) v -= l[k][i] * x[k];
            x[i] = v / l[i][i];
        }
    }
};

struct Texel {
    const BtfSamples* samples = nullptr;
    const std::vector<glm::vec3>* views = nullptr;
    BlinnPhongTexel base;           // values, squares, normal frame
    const float* weights = nullptr; ///< per sample: 1 used, 0 left out (cast shadow); null: all
    bool fixedNormal = false;       ///< keep (u, v) at the seed's normal
    int lobes = 1;
    int basis() const { return 2 + lobes; }
    int params() const { return 2 + 3 * lobes; }
    static int basisOf(int k) { return k < 2 ? 0 : 2 + (k - 2) / 3; }
};

struct Eval {
    double theta[kMaxTheta] = {};
    double coef[3][kMaxBasis] = {};
    double cost = 0;
    double b[3][kMaxBasis] = {};
    double sdd[kMaxTheta][kMaxTheta] = {}, pd[kMaxBasis][kMaxTheta] = {}, yd[3][kMaxTheta] = {};
    double inv[3][kMaxBasis][kMaxBasis] = {}; // (G_FF)⁻¹ on the free coefficients F, else 0
};

// Non-negative least squares over M <= 4 coefficients: of the subsets whose unconstrained
// solution is positive, the cheapest is the optimum (the full set first: when its solution is
// feasible it is the answer). Returns the cost Σp² - bᵀx; x and inv describe the optimum.
double nnlsN(const double G[kMaxTheta][kMaxTheta], int M, const double* b, double squares,
             double* x, double inv[kMaxBasis][kMaxBasis]) {
    double best = squares;
    int bestMask = 0;
    for (int i = 0; i < M; ++i) x[i] = 0.0;
    for (int mask = (1 << M) - 1; mask >= 1; --mask) {
        int idx[kMaxBasis], n = 0;
        for (int i = 0; i < M; ++i)
            if (mask & (1 << i)) idx[n++] = i;
        double sub[kMaxTheta][kMaxTheta] = {}, rhs[kMaxTheta], y[kMaxTheta];
        for (int i = 0; i < n; ++i) {
            rhs[i] = b[idx[i]];
            for (int j = 0; j < n; ++j) sub[i][j] = G[idx[i]][idx[j]];
        }
        CholeskyN f;
        if (!f.factor(sub, n, 1e-12)) continue;
        f.solve(rhs, y);
        bool feasible = true;
        double gain = 0.0;
        for (int i = 0; i < n; ++i) {
            feasible = feasible && y[i] > 0.0;
            gain += rhs[i] * y[i];
        }
        if (feasible && (bestMask == 0 || squares - gain < best)) {
            best = squares - gain;
            bestMask = mask;
            for (int i = 0; i < M; ++i) x[i] = 0.0;
            for (int i = 0; i < n; ++i) x[idx[i]] = y[i];
            for (int i = 0; i < M; ++i)
                for (int j = 0; j < M; ++j) inv[i][j] = 0.0;
            for (int k = 0; k < n; ++k) {
                double e[kMaxTheta] = {}, col[kMaxTheta];
                e[k] = 1.0;
                f.solve(e, col);
                for (int i = 0; i < n; ++i) inv[idx[i]][idx[k]] = col[i];
            }
        }
        if (mask == (1 << M) - 1 && feasible) break;
    }
    if (bestMask == 0)
        for (int i = 0; i < M; ++i)
            for (int j = 0; j < M; ++j) inv[i][j] = 0.0;
    return std::max(best, 0.0);
}

void basisAt(const Texel& tx, const double* theta, const glm::dvec3& nrm, const glm::dvec3 dn[2],
             glm::dvec3 l, glm::dvec3 v, double* phi, double* delta) {
    const double nl = glm::dot(nrm, l);
    phi[0] = nl > 0 ? nl : 0.0;
    phi[1] = 1.0;
    for (int j = 0; j < 2; ++j) delta[j] = nl > 0 ? glm::dot(l, dn[j]) : 0.0;
    for (int j = 0; j < tx.lobes; ++j) {
        const double* t = theta + 2 + 3 * j;
        const double e = std::exp(t[2]);
        const double x = t[0] * l.x * v.x + t[1] * l.y * v.y + l.z * v.z;
        const double lx = x > 0 ? std::log(x) : 0.0;
        const double g = x > 0 ? std::exp(e * lx) : 0.0;
        phi[2 + j] = g;
        delta[2 + 3 * j] = x > 0 ? e * g / x * l.x * v.x : 0.0;
        delta[3 + 3 * j] = x > 0 ? e * g / x * l.y * v.y : 0.0;
        delta[4 + 3 * j] = g * e * lx;
    }
}

void evaluate(const Texel& tx, const double* theta, bool derivatives, Eval& ev) {
    const int M = tx.basis(), K = tx.params();
    ev = Eval();
    for (int k = 0; k < K; ++k) ev.theta[k] = theta[k];
    const BlinnPhongTexel& b = tx.base;
    const glm::dvec3 w = b.n0 + theta[0] * b.t1 + theta[1] * b.t2;
    const double len = glm::length(w);
    const glm::dvec3 nrm = w / len;
    const glm::dvec3 dn[2] = {(b.t1 - nrm * glm::dot(nrm, b.t1)) / len,
                              (b.t2 - nrm * glm::dot(nrm, b.t2)) / len};
    double G[kMaxTheta][kMaxTheta] = {}, squares[3] = {0, 0, 0};
    const int count = tx.samples->count();
    for (int s = 0; s < count; ++s) {
        if (tx.weights && !(tx.weights[s] > 0.0f)) continue; // left out (cast shadow)
        double phi[kMaxBasis], delta[kMaxTheta];
        basisAt(tx, theta, nrm, dn, glm::dvec3(tx.samples->light(s)),
                glm::dvec3((*tx.views)[size_t(s)]), phi, delta);
        const float* p = &b.values[size_t(s) * 3];
        for (int c = 0; c < 3; ++c) squares[c] += double(p[c]) * p[c];
        for (int i = 0; i < M; ++i) {
            for (int j = i; j < M; ++j) G[i][j] += phi[i] * phi[j];
            for (int c = 0; c < 3; ++c) ev.b[c][i] += phi[i] * p[c];
        }
        if (!derivatives) continue;
        for (int k = 0; k < K; ++k) {
            if (delta[k] == 0.0) continue;
            for (int q = 0; q < K; ++q) ev.sdd[k][q] += delta[k] * delta[q];
            for (int i = 0; i < M; ++i) ev.pd[i][k] += phi[i] * delta[k];
            for (int c = 0; c < 3; ++c) ev.yd[c][k] += p[c] * delta[k];
        }
    }
    for (int i = 0; i < M; ++i)
        for (int j = 0; j < i; ++j) G[i][j] = G[j][i];
    double cost = 0.0;
    for (int c = 0; c < 3; ++c) cost += nnlsN(G, M, ev.b[c], squares[c], ev.coef[c], ev.inv[c]);
    ev.cost = cost;
}

int solveTexel(const Texel& tx, double* theta, int maxIterations, double etaMax, Eval& cur) {
    const int M = tx.basis(), K = tx.params();
    Eval trial;
    evaluate(tx, theta, true, cur);
    double lambda = 1e-3;
    int done = 0;
    for (int it = 0; it < maxIterations; ++it) {
        double jtj[kMaxTheta][kMaxTheta] = {}, grad[kMaxTheta] = {};
        for (int c = 0; c < 3; ++c) {
            const double* x = cur.coef[c];
            double phiD[kMaxBasis][kMaxTheta];
            for (int i = 0; i < M; ++i)
                for (int k = 0; k < K; ++k) phiD[i][k] = x[Texel::basisOf(k)] * cur.pd[i][k];
            for (int k = 0; k < K; ++k) {
                double rD = x[Texel::basisOf(k)] * cur.yd[c][k];
                for (int i = 0; i < M; ++i) rD -= x[i] * phiD[i][k];
                grad[k] -= rD;
            }
            double sol[kMaxTheta][kMaxBasis]; // inv ΦᵀD, column per θ_q
            for (int q = 0; q < K; ++q)
                for (int i = 0; i < M; ++i) {
                    double v = 0.0;
                    for (int j = 0; j < M; ++j) v += cur.inv[c][i][j] * phiD[j][q];
                    sol[q][i] = v;
                }
            for (int k = 0; k < K; ++k)
                for (int q = 0; q < K; ++q) {
                    double proj = 0.0;
                    for (int i = 0; i < M; ++i) proj += phiD[i][k] * sol[q][i];
                    jtj[k][q] += x[Texel::basisOf(k)] * x[Texel::basisOf(q)] * cur.sdd[k][q] - proj;
                }
        }
        if (tx.fixedNormal) // the normal's rows and columns: identity, no gradient (no step)
            for (int k = 0; k < 2; ++k) {
                for (int q = 0; q < K; ++q) jtj[k][q] = jtj[q][k] = 0.0;
                jtj[k][k] = 1.0;
                grad[k] = 0.0;
            }
        bool accepted = false;
        for (int attempt = 0; attempt < 8 && !accepted; ++attempt) {
            double a[kMaxTheta][kMaxTheta], rhs[kMaxTheta], step[kMaxTheta];
            for (int i = 0; i < K; ++i) {
                rhs[i] = -grad[i];
                for (int j = 0; j < K; ++j)
                    a[i][j] = jtj[i][j] + (i == j ? lambda * jtj[i][i] + 1e-12 : 0.0);
            }
            CholeskyN f;
            if (!f.factor(a, K, 1e-14)) {
                lambda *= 10.0;
                continue;
            }
            f.solve(rhs, step);
            double next[kMaxTheta], size = 0.0;
            for (int k = 0; k < K; ++k) {
                next[k] = cur.theta[k] + step[k];
                size += step[k] * step[k];
            }
            for (int j = 0; j < tx.lobes; ++j)
                next[4 + 3 * j] = std::min(std::max(next[4 + 3 * j], 0.0), etaMax);
            evaluate(tx, next, true, trial);
            if (trial.cost < cur.cost) {
                const double gain = cur.cost - trial.cost;
                accepted = true;
                ++done;
                std::swap(cur, trial);
                lambda = std::max(lambda / 3.0, 1e-9);
                if (gain <= 1e-6 * cur.cost + 1e-20 || std::sqrt(size) < 1e-6) it = maxIterations;
            } else {
                lambda *= 4.0;
            }
        }
        if (!accepted) break;
    }
    for (int k = 0; k < K; ++k) theta[k] = cur.theta[k];
    return done;
}

// Cast shadows of the texel's samples for the fit (ev, theta) (BtfShadowClassify.h).
int classifyShadows(const Texel& tx, const double* theta, const Eval& ev,
                    const std::vector<float>& lz, std::vector<float>& weights, int& misfit) {
    const int count = tx.samples->count();
    const BlinnPhongTexel& b = tx.base;
    const glm::dvec3 w = b.n0 + theta[0] * b.t1 + theta[1] * b.t2;
    const glm::dvec3 nrm = glm::normalize(w);
    const glm::dvec3 dn[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
    const size_t n = static_cast<size_t>(count);
    std::vector<double> lit(n), diffuse(n), seen(n);
    double base = 0.0;
    for (int c = 0; c < 3; ++c) base += ev.coef[c][1];
    for (int s = 0; s < count; ++s) {
        double phi[kMaxBasis], delta[kMaxTheta];
        basisAt(tx, theta, nrm, dn, glm::dvec3(tx.samples->light(s)),
                glm::dvec3((*tx.views)[size_t(s)]), phi, delta);
        double l = 0.0, m = 0.0, p = 0.0;
        for (int c = 0; c < 3; ++c) {
            m += ev.coef[c][0] * phi[0];
            l += ev.coef[c][0] * phi[0];
            for (int j = 0; j < tx.lobes; ++j) l += ev.coef[c][2 + j] * phi[2 + j];
            p += b.values[size_t(s) * 3 + size_t(c)];
        }
        lit[size_t(s)] = l;
        diffuse[size_t(s)] = m;
        seen[size_t(s)] = p - base;
    }
    const std::vector<float> all(n, 1.0f);
    return classifyCastShadows(size_t(count), lit.data(), diffuse.data(), seen.data(), base,
                               lz.data(), tx.weights ? tx.weights : all.data(),
                               tx.params() + 3 * tx.basis() + 2, weights.data(), misfit);
}

void evaluateFit(const BtfLafortuneFit& fit, size_t t, glm::vec3 l, glm::vec3 v, float out[3]) {
    const float* n = &fit.normal[t * 3];
    const float nl = std::max(n[0] * l.x + n[1] * l.y + n[2] * l.z, 0.0f);
    for (int c = 0; c < 3; ++c) out[c] = fit.diffuse[t * 3 + c] * nl + fit.ambient[t * 3 + c];
    for (int j = 0; j < fit.lobes; ++j) {
        const float* sh = &fit.lobeShape[(t * size_t(fit.lobes) + size_t(j)) * 4];
        const float x = sh[0] * l.x * v.x + sh[1] * l.y * v.y + sh[2] * l.z * v.z;
        const float g = x > 0.0f ? std::pow(x, sh[3]) : 0.0f;
        for (int c = 0; c < 3; ++c)
            out[c] += fit.lobeAlbedo[(t * size_t(fit.lobes) + size_t(j)) * 3 + size_t(c)] * g;
    }
}

} // namespace

BtfLafortuneFit fitBtfLafortune(const BtfSamples& samples, const BtfMaterialMaps& seed, int lobes,
                                int maxIterations, int threads, bool visibility, bool fixedNormal) {
    seed.validate();
    samples.requireFinite();
    if (seed.width != samples.width() || seed.height != samples.height())
        throw InvalidArgument("seed material and samples differ in size");
    if (lobes < 1 || lobes > 2) throw InvalidArgument("Lafortune lobes must be 1 or 2");
    if (maxIterations < 1 || maxIterations > 1000)
        throw InvalidArgument("maxIterations must be 1..1000");
    const size_t texels = samples.texels();
    const int count = samples.count();
    std::vector<glm::vec3> views(static_cast<size_t>(count));
    for (int s = 0; s < count; ++s) views[size_t(s)] = samples.view(s);
    BtfLafortuneFit fit;
    fit.width = samples.width();
    fit.height = samples.height();
    fit.lobes = lobes;
    fit.normal.resize(texels * 3);
    fit.diffuse.resize(texels * 3);
    fit.ambient.resize(texels * 3);
    fit.lobeAlbedo.resize(texels * size_t(lobes) * 3);
    fit.lobeShape.resize(texels * size_t(lobes) * 4);
    std::vector<int> iterations(texels, 0);
    std::vector<float> lz(static_cast<size_t>(count));
    for (int s = 0; s < count; ++s) lz[size_t(s)] = samples.light(s).z;
    const double etaMax = std::log(4096.0);
    const int blocks = int((texels + 63) / 64);
    btfParallelFor(blocks, threads, [&](int b0, int b1) {
        Texel tx;
        tx.samples = &samples;
        tx.views = &views;
        tx.lobes = lobes;
        tx.fixedNormal = fixedNormal;
        tx.base.values.resize(size_t(count) * 3);
        Eval ev;
        std::vector<float> used(static_cast<size_t>(count)), next(static_cast<size_t>(count));
        for (size_t t = size_t(b0) * 64; t < std::min(texels, size_t(b1) * 64); ++t) {
            for (int s = 0; s < count; ++s)
                for (int c = 0; c < 3; ++c)
                    tx.base.values[size_t(s) * 3 + size_t(c)] = samples.plane(s, c)[t];
            tx.base.updateSquares();
            tx.base.setSeedNormal(
                glm::vec3(seed.normal[t * 3], seed.normal[t * 3 + 1], seed.normal[t * 3 + 2]));
            const float e0 = seed.exponentMap.empty() ? seed.exponent : seed.exponentMap[t];
            double theta[kMaxTheta] = {tx.base.start[0], tx.base.start[1]};
            for (int j = 0; j < lobes; ++j) {
                theta[2 + 3 * j] = -1.0; // mirror direction about +z
                theta[3 + 3 * j] = -1.0;
                theta[4 + 3 * j] =
                    j == 0 ? std::log(std::min(std::max(double(e0), 1.0), 4096.0)) : std::log(4.0);
            }
            tx.weights = nullptr;
            iterations[t] = solveTexel(tx, theta, maxIterations, etaMax, ev);
            if (visibility) {
                // as the Blinn-Phong fit: a texel with samples off its fit by more than the
                // noise is fitted again from its steep lights (θ_l <= 46°), then from every
                // sample not classified as shadowed, until the classification is stable
                int misfit = 0;
                classifyShadows(tx, theta, ev, lz, next, misfit);
                if (misfit > 0) {
                    for (int s = 0; s < count; ++s) next[size_t(s)] = lz[size_t(s)] >= 0.69f;
                    for (int round = 0; round < 5; ++round) {
                        used.swap(next);
                        tx.weights = used.data();
                        iterations[t] += solveTexel(tx, theta, maxIterations, etaMax, ev);
                        classifyShadows(tx, theta, ev, lz, next, misfit);
                        if (std::equal(next.begin(), next.end(), used.begin())) break;
                    }
                }
            }
            const glm::dvec3 n = tx.base.normal(theta[0], theta[1]);
            for (int c = 0; c < 3; ++c) {
                fit.normal[t * 3 + size_t(c)] = float(n[c]);
                fit.diffuse[t * 3 + size_t(c)] = float(ev.coef[c][0]);
                fit.ambient[t * 3 + size_t(c)] = float(ev.coef[c][1]);
                for (int j = 0; j < lobes; ++j)
                    fit.lobeAlbedo[(t * size_t(lobes) + size_t(j)) * 3 + size_t(c)] =
                        float(ev.coef[c][2 + j]);
            }
            for (int j = 0; j < lobes; ++j) {
                float* sh = &fit.lobeShape[(t * size_t(lobes) + size_t(j)) * 4];
                sh[0] = float(theta[2 + 3 * j]);
                sh[1] = float(theta[3 + 3 * j]);
                sh[2] = 1.0f;
                sh[3] = float(std::exp(theta[4 + 3 * j]));
            }
        }
    });
    double sum = 0.0;
    for (int v : iterations) sum += v;
    fit.meanIterations = sum / double(texels);
    for (const std::vector<float>* map :
         {&fit.normal, &fit.diffuse, &fit.ambient, &fit.lobeAlbedo, &fit.lobeShape})
        for (float v : *map)
            if (!std::isfinite(v))
                throw InvalidArgument("the Lafortune fit produced non-finite values; are the "
                                      "sample values in a sane range?");
    return fit;
}

std::vector<double> btfLafortuneErrors(const BtfSamples& samples, const BtfLafortuneFit& fit,
                                       std::vector<float>* reconstruction, int threads) {
    const size_t texels = samples.texels();
    if (fit.width != samples.width() || fit.height != samples.height() ||
        fit.normal.size() != texels * 3 || fit.lobes < 1 || fit.lobes > 2 ||
        fit.lobeShape.size() != texels * size_t(fit.lobes) * 4 ||
        fit.lobeAlbedo.size() != texels * size_t(fit.lobes) * 3 ||
        fit.diffuse.size() != texels * 3 || fit.ambient.size() != texels * 3)
        throw InvalidArgument("Lafortune fit and samples differ in size");
    const int count = samples.count();
    if (reconstruction) reconstruction->assign(texels * 3 * size_t(count), 0.0f);
    std::vector<double> errors(static_cast<size_t>(count), 0.0);
    btfParallelFor(count, threads, [&](int s0, int s1) {
        for (int s = s0; s < s1; ++s) {
            double sum = 0.0;
            for (size_t t = 0; t < texels; ++t) {
                float out[3];
                evaluateFit(fit, t, samples.light(s), samples.view(s), out);
                for (int c = 0; c < 3; ++c) {
                    const double r = double(out[c]) - samples.plane(s, c)[t];
                    sum += r * r;
                    if (reconstruction)
                        (*reconstruction)[(size_t(s) * 3 + size_t(c)) * texels + t] = out[c];
                }
            }
            errors[size_t(s)] = sum / double(texels * 3);
        }
    });
    return errors;
}

} // namespace weft
