// The cast-shadow pass's helpers for the per-texel Blinn-Phong fit (BlinnPhongVisibility.h).
#include "btf/BlinnPhongVisibility.h"

#include <weft/BtfNonlinear.h>

#include <algorithm>
#include <cmath>

#include "btf/BtfParallel.h"
#include "btf/BtfShadowClassify.h"

namespace weft {

double blinnPhongParts(const BlinnPhongTexel& tx, const BlinnPhongResult& r, const float* planes,
                       std::vector<double>& lit, std::vector<double>& diffuse,
                       std::vector<double>& seen) {
    static thread_local std::vector<double> d, g; // no allocation per texel
    const size_t count = size_t(tx.geometry->count), np = size_t(tx.geometry->padded);
    const bool highlight = r.coef[0][2] > 0.0 || r.coef[1][2] > 0.0 || r.coef[2][2] > 0.0;
    blinnPhongTerms(tx, r.theta, d, g, highlight); // k g = 0 in every channel otherwise
    double base = 0.0;
    for (int c = 0; c < 3; ++c) base += r.coef[c][1];
    lit.resize(count);
    diffuse.resize(count);
    seen.resize(count);
    for (size_t s = 0; s < count; ++s) {
        double l = 0.0, p = 0.0, m = 0.0;
        for (int c = 0; c < 3; ++c) {
            l += r.coef[c][0] * d[s] + r.coef[c][2] * g[s];
            m += r.coef[c][0] * d[s];
            p += planes[size_t(c) * np + s];
        }
        lit[s] = l;
        diffuse[s] = m;
        seen[s] = p - base;
    }
    return base;
}

int classifyBlinnPhongShadows(const BlinnPhongTexel& tx, const BlinnPhongResult& r,
                              const float* planes, std::vector<float>& weights, int& misfit,
                              double sigmaCap) {
    static thread_local std::vector<double> lit, diffuse, seen;
    const double base = blinnPhongParts(tx, r, planes, lit, diffuse, seen);
    std::fill(weights.begin(), weights.end(), 0.0f);
    return classifyCastShadows(size_t(tx.geometry->count), lit.data(), diffuse.data(), seen.data(),
                               base, tx.geometry->l[2].data(), tx.weights, 12, weights.data(),
                               misfit, sigmaCap);
}

namespace {

// x = A⁻¹ b for a symmetric positive definite 4x4 A (Cholesky); false when a pivot falls below
// 1e-10 of the largest diagonal entry.
bool solve4(const double a[4][4], const double b[4], double x[4]) {
    double l[4][4] = {};
    const double scale = std::max({a[0][0], a[1][1], a[2][2], a[3][3]});
    if (!(scale > 0.0) || !std::isfinite(scale)) return false;
    for (int j = 0; j < 4; ++j) {
        double d = a[j][j];
        for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
        if (!(d > 1e-10 * scale)) return false;
        l[j][j] = std::sqrt(d);
        for (int i = j + 1; i < 4; ++i) {
            double v = a[i][j];
            for (int k = 0; k < j; ++k) v -= l[i][k] * l[j][k];
            l[i][j] = v / l[j][j];
        }
    }
    double y[4];
    for (int i = 0; i < 4; ++i) {
        double v = b[i];
        for (int k = 0; k < i; ++k) v -= l[i][k] * y[k];
        y[i] = v / l[i][i];
    }
    for (int i = 3; i >= 0; --i) {
        double v = y[i];
        for (int k = i + 1; k < 4; ++k) v -= l[k][i] * x[k];
        x[i] = v / l[i][i];
    }
    return true;
}

} // namespace

BlinnPhongResult lambertFit(BlinnPhongTexel& tx, const double start[2], double eta) {
    // Σ_c p_sc = B + M·l_s with M = (Σ_c m_c) n where n·l_s > 0, B alone elsewhere (the
    // renderer's clamp): linear in (M, B) once the samples facing away are known, so the set
    // facing away from the current normal is re-solved until it settles (photometric stereo
    // with an ambient term; no local minima, a few 4x4 solves instead of an LM search).
    const BlinnPhongGeometry& geo = *tx.geometry;
    const size_t np = size_t(geo.padded);
    glm::dvec3 n = tx.normal(start[0], start[1]);
    bool anyFacing = true;
    struct Scratch {
        std::vector<char> facing;
        std::vector<double> value; // Σ_c p_sc per sample
    };
    static thread_local Scratch scratch; // no allocation per texel
    const int count = geo.count;
    scratch.facing.assign(size_t(count), 1); // the first solve takes every used sample as lit
    scratch.value.resize(size_t(count));
    char* const facing = scratch.facing.data();
    double* const value = scratch.value.data();
    const float *const lx = geo.l[0].data(), *const ly = geo.l[1].data(),
                       *const lz = geo.l[2].data();
    for (int s = 0; s < count; ++s)
        value[s] = double(tx.planes[s]) + tx.planes[np + size_t(s)] + tx.planes[2 * np + size_t(s)];
    for (int round = 0; round < 4 && anyFacing; ++round) {
        // the normal equations of the rows (f l_s, 1), f = 1 facing, else 0, written out (the
        // upper triangle; a row built in an array was re-read across its stores, stalling)
        double a00 = 0, a01 = 0, a02 = 0, a03 = 0, a11 = 0, a12 = 0, a13 = 0, a22 = 0, a23 = 0,
               a33 = 0, b0 = 0, b1 = 0, b2 = 0, b3 = 0;
        for (int s = 0; s < count; ++s) {
            if (!(tx.weights[s] > 0.0f)) continue;
            const double p = value[s];
            const double f = facing[s] ? 1.0 : 0.0;
            const double x = f * lx[s], y = f * ly[s], z = f * lz[s];
            b0 += x * p;
            b1 += y * p;
            b2 += z * p;
            b3 += p;
            a00 += x * x;
            a01 += x * y;
            a02 += x * z;
            a03 += x;
            a11 += y * y;
            a12 += y * z;
            a13 += y;
            a22 += z * z;
            a23 += z;
            a33 += 1.0;
        }
        const double a[4][4] = {
            {a00, a01, a02, a03}, {a01, a11, a12, a13}, {a02, a12, a22, a23}, {a03, a13, a23, a33}};
        const double b[4] = {b0, b1, b2, b3};
        double x[4];
        if (!solve4(a, b, x)) break;
        const glm::dvec3 m(x[0], x[1], x[2]);
        const double len = glm::length(m);
        if (!(len > 0.0) || !std::isfinite(len) || !(m.z > 0.0)) break;
        n = m / len;
        bool changed = false;
        for (int s = 0; s < count; ++s) {
            const char f = glm::dot(n, glm::dvec3(lx[s], ly[s], lz[s])) > 0.0;
            changed |= f != facing[s];
            facing[s] = f;
        }
        anyFacing = changed;
    }
    // n = normalise(u, v, 1) with n_z kept >= 0.05, as a seed normal is
    const double z = std::max(n.z, 0.05);
    const double theta[3] = {n.x / z, n.y / z, eta};
    const bool specular = tx.specular;
    tx.specular = false;
    BlinnPhongResult r = blinnPhongProject(tx, theta);
    tx.specular = specular;
    return r;
}

double seedEta(const BtfMaterialMaps& seed, size_t t, double etaMin, double etaMax) {
    const float e0 = seed.exponentMap.empty() ? seed.exponent : seed.exponentMap[t];
    return std::min(std::max(std::log(std::max(double(e0), 1e-2)), etaMin), etaMax);
}

void texelPlanes(const BtfSamples& samples, size_t t, size_t padded, bool luma, float* out) {
    const int count = samples.count();
    for (int c = 0; c < 3; ++c)
        for (int s = 0; s < count; ++s)
            out[size_t(c) * padded + size_t(s)] = samples.plane(s, c)[t];
    if (luma)
        for (int s = 0; s < count; ++s) {
            const float y = 0.299f * out[size_t(s)] + 0.587f * out[padded + size_t(s)] +
                            0.114f * out[2 * padded + size_t(s)];
            out[size_t(s)] = out[padded + size_t(s)] = out[2 * padded + size_t(s)] = y;
        }
}

double blinnPhongDataNoise(const BtfSamples& samples, const BlinnPhongGeometry& geometry,
                           const std::vector<glm::vec3>& lights,
                           const std::vector<glm::vec3>& halves, const BtfMaterialMaps& seed,
                           const BtfNonlinearOptions& options, double etaMin, double etaMax) {
    // Most texels' first fits follow their steep lights to the noise and the model's error;
    // the texels in deep grooves, or with a lobe the fit missed, whose σ the cap is for, are
    // the few.
    constexpr size_t kTexels = 1024;
    const size_t texels = samples.texels();
    const int n = int(std::min(texels, kTexels));
    std::vector<double> sigma(static_cast<size_t>(n), 0.0);
    btfParallelFor(n, options.threads, [&](int i0, int i1) {
        BlinnPhongTexel tx;
        tx.lights = &lights;
        tx.halves = &halves;
        tx.geometry = &geometry;
        const size_t np = size_t(geometry.padded);
        std::vector<float> planes(3 * np, 0.0f);
        std::vector<double> lit, diffuse, seen;
        for (int i = i0; i < i1; ++i) {
            const size_t t = size_t(i) * texels / size_t(n);
            texelPlanes(samples, t, np, options.luminanceNormals, planes.data());
            tx.setPlanes(planes.data());
            tx.setSeedNormal(
                glm::vec3(seed.normal[t * 3], seed.normal[t * 3 + 1], seed.normal[t * 3 + 2]));
            const BlinnPhongResult r = blinnPhongBuiltin(tx, seedEta(seed, t, etaMin, etaMax),
                                                         etaMin, etaMax, options.maxIterations);
            blinnPhongParts(tx, r, planes.data(), lit, diffuse, seen);
            sigma[size_t(i)] = steepResidualSigma(size_t(geometry.count), lit.data(), seen.data(),
                                                  geometry.l[2].data(), geometry.ones.data());
        }
    });
    std::nth_element(sigma.begin(), sigma.begin() + long(sigma.size() / 2), sigma.end());
    return sigma[sigma.size() / 2];
}

} // namespace weft
