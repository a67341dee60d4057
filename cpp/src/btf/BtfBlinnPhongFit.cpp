// Per-texel nonlinear Blinn-Phong fit over all texels (SPEC §3.5), seeded by the linear +
// specular pipeline: the seed's normal and exponent start the search.
#include <weft/BtfNonlinear.h>
#include <weft/Error.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "btf/BlinnPhongTexel.h"
#include "btf/BlinnPhongVisibility.h"
#include "btf/BtfModel.h"
#include "btf/BtfParallel.h"

namespace weft {

namespace {

// The share of its peak a fitted lobe must show at some used sample to count as observed, and
// the same share at the neighbouring half vector bounds the exponent (btfResolvableExponent).
constexpr double kSeenFraction = 0.01;
// The shadow classification's σ is at most this many times the data's noise
// (blinnPhongDataNoise): a fit pulled far from the data, by shadowed samples it still uses or by
// a highlight a model without one cannot follow, misses every sample by more than the noise,
// and a σ measured on it hides the shadows that pulled it (grooves whose steep lights are
// shadowed too; random seeds 40, 41 at 32²: 7.0° / 6.2° p95 with the Lambert start alone,
// 1.3° / 0.3° with the cap).
constexpr double kNoiseSigmas = 2.0;
// A lobe restart (below) needs a start that lowers the cost by this share: adding the lobe's
// column lowers it by about 1/count per channel from noise alone.
constexpr double kLobeGain = 0.05;
constexpr double kLobeStarts[] = {4.0, 16.0, 64.0, 256.0};
// ... at the normal's tilt (tan θ_n) times these: a diffuse term that absorbed a lobe around n
// tilted the normal further, towards the lobe's reflection direction
constexpr double kLobeTilts[] = {1.0, 0.75, 0.5, 0.25};

} // namespace

bool btfHaveCeres() {
#ifdef WEFT_HAVE_CERES
    return true;
#else
    return false;
#endif
}

float btfResolvableExponent(const BtfSamples& samples, double fraction) {
    if (!(fraction > 0.0 && fraction < 1.0)) throw InvalidArgument("fraction must lie in (0, 1)");
    const int count = samples.count();
    std::vector<glm::dvec3> h(static_cast<size_t>(count));
    for (int s = 0; s < count; ++s)
        h[size_t(s)] = glm::dvec3(btfHalfVector(samples.light(s), samples.view(s)));
    std::vector<double> nearest; // cos of the angle to the nearest other half vector
    for (int s = 0; s < count; ++s) {
        double best = -1.0;
        for (int q = 0; q < count; ++q)
            // repeated directions (several views with one half vector) are one sample
            if (q != s && glm::dot(h[size_t(s)], h[size_t(q)]) < 1.0 - 1e-9)
                best = std::max(best, glm::dot(h[size_t(s)], h[size_t(q)]));
        if (best > -1.0) nearest.push_back(best);
    }
    if (nearest.empty()) return 4096.0f; // one direction: nothing to resolve a lobe with
    std::nth_element(nearest.begin(), nearest.begin() + long(nearest.size() / 2), nearest.end());
    const double c = std::min(nearest[nearest.size() / 2], 1.0 - 1e-9);
    return float(std::min(std::log(1.0 / fraction) / -std::log(c), 1e6));
}

namespace {

// What the fit and the noise estimate share: the checked inputs, the exponent range as η and
// the sample directions.
struct FitSetup {
    double etaMin = 0, etaMax = 0;
    std::vector<glm::vec3> lights, halves;
    BlinnPhongGeometry geometry;
    FitSetup(const BtfSamples& samples, const BtfMaterialMaps& seed,
             const BtfNonlinearOptions& options)
        : geometry(check(samples, seed, options, lights, halves, etaMin, etaMax), halves) {
        geometry.flatSpecular = options.flatSpecularNormal;
    }
    static const std::vector<glm::vec3>&
    check(const BtfSamples& samples, const BtfMaterialMaps& seed,
          const BtfNonlinearOptions& options, std::vector<glm::vec3>& lights,
          std::vector<glm::vec3>& halves, double& etaMin, double& etaMax) {
        seed.validate();
        samples.requireFinite();
        if (seed.width != samples.width() || seed.height != samples.height())
            throw InvalidArgument("seed material and samples differ in size");
        const float maxExponent = options.maxExponent == 0.0f
                                      ? btfResolvableExponent(samples, kSeenFraction)
                                      : options.maxExponent;
        if (!(options.minExponent >= 0.01f) || !(maxExponent > options.minExponent) ||
            !std::isfinite(maxExponent) || maxExponent > 1e6f)
            throw InvalidArgument("exponent bounds must satisfy 0.01 <= min < max <= 1e6 (max "
                                  "0: the resolvable exponent, here " +
                                  std::to_string(maxExponent) + ")");
        if (options.maxIterations < 1 || options.maxIterations > 1000)
            throw InvalidArgument("maxIterations must be 1..1000");
        if (!(options.noise >= 0.0) || !std::isfinite(options.noise))
            throw InvalidArgument("noise must be finite and >= 0 (0: estimated)");
        checkThreads(options.threads);
        etaMin = std::log(double(options.minExponent));
        etaMax = std::log(double(maxExponent));
        const int count = samples.count();
        lights.resize(static_cast<size_t>(count));
        halves.resize(lights.size());
        for (int s = 0; s < count; ++s) {
            lights[size_t(s)] = samples.light(s);
            halves[size_t(s)] = btfHalfVector(samples.light(s), samples.view(s));
        }
        return lights;
    }
};

} // namespace

double btfBlinnPhongNoise(const BtfSamples& samples, const BtfMaterialMaps& seed,
                          const BtfNonlinearOptions& options) {
    const FitSetup f(samples, seed, options);
    return blinnPhongDataNoise(samples, f.geometry, f.lights, f.halves, seed, options, f.etaMin,
                               f.etaMax);
}

BtfNonlinearFit fitBtfBlinnPhong(const BtfSamples& samples, const BtfMaterialMaps& seed,
                                 const BtfNonlinearOptions& options) {
    const FitSetup setup(samples, seed, options);
    // Auto is the built-in solver: ~100x faster than Ceres per texel at equal or lower
    // deviation (BENCHMARKS.md, btf); Ceres only when asked for.
    const bool ceres = options.solver == BtfSolver::Ceres;
    if (ceres && !btfHaveCeres())
        throw InvalidArgument("solver 'ceres' asked for, but weft was built without Ceres Solver");

    const int count = samples.count();
    const size_t texels = samples.texels();
    const std::vector<glm::vec3>& lights = setup.lights;
    const std::vector<glm::vec3>& halves = setup.halves;
    const BlinnPhongGeometry& geometry = setup.geometry;
    const double etaMin = setup.etaMin, etaMax = setup.etaMax;

    BtfNonlinearFit out;
    out.solver = ceres ? "ceres" : "builtin";
    BtfMaterialMaps& maps = out.maps;
    maps.width = seed.width;
    maps.height = seed.height;
    maps.normal.resize(texels * 3);
    maps.albedo.resize(texels * 3);
    maps.ambient.resize(texels * 3);
    maps.specular.resize(texels * 3);
    maps.exponentMap.resize(texels);
    maps.clampDiffuse = true;
    maps.flatSpecularNormal = options.flatSpecularNormal;
    std::vector<double> iterations(texels, 0.0), shadowed(texels, 0.0);

    out.noise = !options.visibility   ? 0.0
                : options.noise > 0.0 ? options.noise
                                      : blinnPhongDataNoise(samples, geometry, lights, halves, seed,
                                                            options, etaMin, etaMax);
    const double sigmaCap = options.visibility ? kNoiseSigmas * out.noise : HUGE_VAL;
    const int blocks = int((texels + 63) / 64);
    btfParallelForDynamic(blocks, options.threads, 1, [&](int b0, int b1) {
        BlinnPhongTexel tx;
        tx.lights = &lights;
        tx.halves = &halves;
        tx.geometry = &geometry;
        if (ceres) tx.values.resize(size_t(count) * 3);
        // A block's samples transposed to [texel][channel][padded sample]: reading each plane
        // contiguously for 64 texels instead of 243 strided loads per texel.
        const size_t np = size_t(geometry.padded);
        std::vector<float> block(64 * 3 * np, 0.0f), weights(np, 0.0f), next(np, 0.0f);
        std::vector<float> luma(options.luminanceNormals ? 3 * np : 0);
        std::vector<double> d, g; // the lobe check's model terms
        for (int b = b0; b < b1; ++b) {
            const size_t first = size_t(b) * 64, last = std::min(texels, first + 64);
            for (int s = 0; s < count; ++s)
                for (int c = 0; c < 3; ++c) {
                    // 243 short runs: too many streams for the hardware prefetcher, so each
                    // run asks for the one four samples on (its 64 floats, 4 cache lines)
                    if (s + 4 < count) {
                        const char* ahead =
                            reinterpret_cast<const char*>(samples.plane(s + 4, c) + first);
                        for (size_t at = 0; at < (last - first) * sizeof(float); at += 64)
                            __builtin_prefetch(ahead + at);
                    }
                    const float* src = samples.plane(s, c) + first;
                    float* dst = block.data() + size_t(c) * np + size_t(s);
                    for (size_t i = 0; i < last - first; ++i) dst[i * 3 * np] = src[i];
                }
            for (size_t t = first; t < last; ++t) {
                const float* rgb = block.data() + (t - first) * 3 * np;
                const float* planes = rgb;
                if (options.luminanceNormals) {
                    // JPEG's luma (BT.601) in all three channels: the normal and exponent are
                    // fitted to it, the colours projected from the RGB values at the end
                    for (size_t s = 0; s < np; ++s) {
                        const float y =
                            0.299f * rgb[s] + 0.587f * rgb[np + s] + 0.114f * rgb[2 * np + s];
                        luma[s] = luma[np + s] = luma[2 * np + s] = y;
                    }
                    planes = luma.data();
                }
                tx.setPlanes(planes);
                if (ceres)
                    for (int s = 0; s < count; ++s)
                        for (int c = 0; c < 3; ++c)
                            tx.values[size_t(s) * 3 + size_t(c)] =
                                planes[size_t(c) * np + size_t(s)];
                tx.setSeedNormal(
                    glm::vec3(seed.normal[t * 3], seed.normal[t * 3 + 1], seed.normal[t * 3 + 2]));
                const double eta0 = seedEta(seed, t, etaMin, etaMax);
                // the exponent's range for this texel: one point when it is held
                const double lo = options.fixedExponent ? eta0 : etaMin;
                const double hi = options.fixedExponent ? eta0 : etaMax;
                auto solve = [&](const double start[3]) {
                    if (!ceres)
                        return blinnPhongBuiltin(tx, start[2], lo, hi, options.maxIterations);
                    return blinnPhongCeres(tx, blinnPhongProject(tx, start), lo, hi,
                                           options.maxIterations);
                };
                const double start[3] = {tx.start[0], tx.start[1], eta0};
                const double seedStart[2] = {tx.start[0], tx.start[1]};
                BlinnPhongResult r = solve(start);
                int iters = r.iterations, left = 0;
                if (options.visibility) {
                    // A texel with samples off its fit by more than the noise gets its cast
                    // shadows from a Lambert fit to its steep lights (θ_l <= 46°), then is fitted
                    // again from every sample not classified as shadowed, until the
                    // classification is stable.
                    std::copy(geometry.ones.begin(), geometry.ones.end(), weights.begin());
                    const BlinnPhongResult first = r;
                    int misfit = 0;
                    left = classifyBlinnPhongShadows(tx, r, planes, next, misfit, sigmaCap);
                    // a fit with no diffuse term in some channel may be a highlight posing as
                    // the diffuse lobe of a texel shadowed from every grazing light
                    const bool noDiffuse =
                        r.coef[0][0] <= 0.0 || r.coef[1][0] <= 0.0 || r.coef[2][0] <= 0.0;
                    // One or two misfits: noise (3σ is passed by 0.27% of Gaussian samples,
                    // so by one sample in ~5 texels of 81) or a lone shadowed sample that cannot
                    // have pulled the fit far. Nothing dark: keep the fit. Else one warm refit
                    // without the dark samples; the full procedure only if that is not stable.
                    bool settled = !noDiffuse && misfit <= 2 && left == 0;
                    if (!settled && !noDiffuse && misfit <= 2) {
                        weights.swap(next);
                        tx.setPlanes(planes, weights.data());
                        tx.start[0] = r.theta[0];
                        tx.start[1] = r.theta[1];
                        r = solve(r.theta);
                        iters += r.iterations;
                        left = classifyBlinnPhongShadows(tx, r, planes, next, misfit, sigmaCap);
                        settled =
                            misfit <= 2 && std::equal(next.begin(), next.end(), weights.begin());
                    }
                    if (!settled) {
                        // Visibility first from Lambert + ambient, from the steep lights: a
                        // broad lobe can absorb the falloff that cast shadows give grazing
                        // light, or stand in for the diffuse term (m = 0) so that no sample
                        // lies below half the diffuse light; a model without a highlight can
                        // do neither (random seeds 106, 114 at 32²: 18.9° / 18.3° p95 -> 0.8° /
                        // 1.9°, 0.9° with the σ cap). Its fit is linear: the rounds cost little.
                        for (int s = 0; s < count; ++s)
                            next[size_t(s)] = geometry.l[2][size_t(s)] >= 0.69f ? 1.0f : 0.0f;
                        double at[2] = {seedStart[0], seedStart[1]};
                        for (int round = 0; round < 5; ++round) {
                            weights.swap(next);
                            tx.setPlanes(planes, weights.data());
                            r = lambertFit(tx, at, eta0);
                            at[0] = r.theta[0];
                            at[1] = r.theta[1];
                            classifyBlinnPhongShadows(tx, r, planes, next, misfit, sigmaCap);
                            if (std::equal(next.begin(), next.end(), weights.begin())) break;
                        }
                        // then the whole model from there, until its classification is stable
                        for (int round = 0; round < 5; ++round) {
                            weights.swap(next);
                            tx.setPlanes(planes, weights.data());
                            tx.start[0] = r.theta[0];
                            tx.start[1] = r.theta[1];
                            r = solve(r.theta);
                            iters += r.iterations;
                            left = classifyBlinnPhongShadows(tx, r, planes, next, misfit, sigmaCap);
                            if (std::equal(next.begin(), next.end(), weights.begin())) break;
                        }
                        // The rounds restart from the steep lights and may settle in a worse
                        // minimum than the first fit: keep the first one (re-projected) where it
                        // is cheaper on the final set of samples.
                        BlinnPhongResult again = blinnPhongProject(tx, first.theta);
                        if (again.cost < r.cost) {
                            again.iterations = r.iterations;
                            r = again;
                        }
                        left = 0;
                        for (int s = 0; s < count; ++s) left += weights[size_t(s)] > 0.0f ? 0 : 1;
                    }
                }
                // A lobe that no used sample sees at >= kSeenFraction of its peak has no
                // support in the data: k and e trade off freely (a needle lobe, k up to 10^3,
                // that would sparkle from unsampled directions). Such a texel gets no highlight.
                auto lobeSeen = [&](const BlinnPhongResult& x) {
                    if (x.coef[0][2] <= 0.0 && x.coef[1][2] <= 0.0 && x.coef[2][2] <= 0.0)
                        return false;
                    blinnPhongTerms(tx, x.theta, d, g);
                    double seen = 0.0;
                    for (int s = 0; s < count; ++s)
                        if (tx.weights[s] > 0.0f) seen = std::max(seen, g[size_t(s)]);
                    return seen >= kSeenFraction;
                };
                if ((r.coef[0][2] > 0.0 || r.coef[1][2] > 0.0 || r.coef[2][2] > 0.0) &&
                    !lobeSeen(r)) {
                    tx.specular = false;
                    tx.start[0] = r.theta[0];
                    tx.start[1] = r.theta[1];
                    r = solve(r.theta);
                    iters += r.iterations;
                }
                // No highlight in any channel (the NNLS dropped the lobe, k = 0, or it was a
                // needle no sample sees): where k = 0 the cost no longer depends on η, so the
                // search cannot bring a lobe back, and a broad lobe that the diffuse term
                // absorbed by tilting the normal (from a start at a needle exponent, or the
                // highlight-free normal of the visibility pass) stays absorbed (random seed 103
                // at 32²: 9.8° p95 -> 0.9°). Restart from the start on a coarse grid (exponent x
                // the normal's tilt) whose lobe explains most, and keep that fit where it is
                // cheaper on the same samples and its lobe is seen; only where the lobe
                // explains clearly more than noise (kLobeGain): on a material without a
                // highlight every texel ends here.
                if (r.coef[0][2] <= 0.0 && r.coef[1][2] <= 0.0 && r.coef[2][2] <= 0.0) {
                    const bool specular = tx.specular;
                    tx.specular = true;
                    BlinnPhongResult from;
                    from.cost = r.cost * (1.0 - kLobeGain);
                    bool found = false;
                    for (double f : kLobeTilts)
                        for (double e : kLobeStarts) {
                            const double at[3] = {f * r.theta[0], f * r.theta[1],
                                                  std::min(std::max(std::log(e), lo), hi)};
                            const BlinnPhongResult p = blinnPhongProject(tx, at);
                            if (p.cost < from.cost) {
                                from = p;
                                found = true;
                            }
                        }
                    bool kept = false;
                    if (found) {
                        tx.start[0] = from.theta[0];
                        tx.start[1] = from.theta[1];
                        const BlinnPhongResult lobe = solve(from.theta);
                        iters += lobe.iterations;
                        if (lobe.cost < r.cost && lobeSeen(lobe)) {
                            r = lobe;
                            kept = true;
                        }
                    }
                    if (!kept) tx.specular = specular;
                }
                if (options.luminanceNormals) { // the colours at the luma fit's (n, e)
                    tx.setPlanes(rgb, tx.weights);
                    const int it = r.iterations;
                    r = blinnPhongProject(tx, r.theta);
                    r.iterations = it;
                }
                tx.specular = true;
                const glm::dvec3 n = tx.normal(r.theta[0], r.theta[1]);
                maps.exponentMap[t] = float(std::exp(r.theta[2]));
                for (int c = 0; c < 3; ++c) {
                    maps.normal[t * 3 + size_t(c)] = float(n[c]);
                    // ρ (a + d) + k g with ρ = m, ρ a = b (m, b >= 0). A texel without diffuse
                    // reflection (m = 0) keeps ρ = max(1e-3 b, 1e-6), so a = b / ρ stays finite
                    // and ρ d adds at most 1e-3 b.
                    const double m = r.coef[c][0], bc = r.coef[c][1];
                    const double rho = std::max({m, 1e-3 * bc, 1e-6});
                    maps.albedo[t * 3 + size_t(c)] = float(rho);
                    maps.ambient[t * 3 + size_t(c)] = float(bc / rho);
                    maps.specular[t * 3 + size_t(c)] = float(r.coef[c][2]);
                }
                iterations[t] = iters;
                shadowed[t] = left;
            }
        }
    });
    double sum = 0.0;
    for (double v : iterations) sum += v;
    out.meanIterations = sum / double(texels);
    double left = 0.0;
    for (double v : shadowed) left += v;
    out.shadowedFraction = left / (double(texels) * double(count));
    try {
        maps.validate();
    } catch (const InvalidArgument& e) {
        throw InvalidArgument(std::string("the Blinn-Phong fit produced invalid maps (") +
                              e.what() + "); are the sample values in a sane range?");
    }
    return out;
}

} // namespace weft
