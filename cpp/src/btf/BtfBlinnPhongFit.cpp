// Per-texel nonlinear Blinn-Phong fit over all texels (SPEC §3.5), seeded by the linear +
// specular pipeline: the seed's normal and exponent start the search.
#include <weft/BtfNonlinear.h>
#include <weft/Error.h>

#include <cmath>

#include "btf/BlinnPhongTexel.h"
#include "btf/BtfModel.h"
#include "btf/BtfParallel.h"

namespace weft {

bool btfHaveCeres() {
#ifdef WEFT_HAVE_CERES
    return true;
#else
    return false;
#endif
}

BtfNonlinearFit fitBtfBlinnPhong(const BtfSamples& samples, const BtfMaterialMaps& seed,
                                 const BtfNonlinearOptions& options) {
    seed.validate();
    samples.requireFinite();
    if (seed.width != samples.width() || seed.height != samples.height())
        throw InvalidArgument("seed material and samples differ in size");
    if (!(options.minExponent >= 0.01f) || !(options.maxExponent > options.minExponent) ||
        !std::isfinite(options.maxExponent) || options.maxExponent > 1e6f)
        throw InvalidArgument("exponent bounds must satisfy 0.01 <= min < max <= 1e6");
    if (options.maxIterations < 1 || options.maxIterations > 1000)
        throw InvalidArgument("maxIterations must be 1..1000");
    // Auto is the built-in solver: ~100x faster than Ceres per texel at equal or lower
    // deviation (BENCHMARKS.md, btf); Ceres only when asked for.
    const bool ceres = options.solver == BtfSolver::Ceres;
    if (ceres && !btfHaveCeres())
        throw InvalidArgument("solver 'ceres' asked for, but weft was built without Ceres Solver");

    const int count = samples.count();
    const size_t texels = samples.texels();
    std::vector<glm::vec3> lights(static_cast<size_t>(count)), halves(lights.size());
    for (int s = 0; s < count; ++s) {
        lights[size_t(s)] = samples.light(s);
        halves[size_t(s)] = btfHalfVector(samples.light(s), samples.view(s));
    }
    const BlinnPhongGeometry geometry(lights, halves);
    const double etaMin = std::log(double(options.minExponent));
    const double etaMax = std::log(double(options.maxExponent));

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
    maps.flatSpecularNormal = false;
    std::vector<double> iterations(texels, 0.0);

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
        std::vector<float> block(64 * 3 * np, 0.0f);
        for (int b = b0; b < b1; ++b) {
            const size_t first = size_t(b) * 64, last = std::min(texels, first + 64);
            for (int s = 0; s < count; ++s)
                for (int c = 0; c < 3; ++c) {
                    const float* src = samples.plane(s, c) + first;
                    float* dst = block.data() + size_t(c) * np + size_t(s);
                    for (size_t i = 0; i < last - first; ++i) dst[i * 3 * np] = src[i];
                }
            for (size_t t = first; t < last; ++t) {
                const float* planes = block.data() + (t - first) * 3 * np;
                tx.setPlanes(planes);
                if (ceres)
                    for (int s = 0; s < count; ++s)
                        for (int c = 0; c < 3; ++c)
                            tx.values[size_t(s) * 3 + size_t(c)] =
                                planes[size_t(c) * np + size_t(s)];
                tx.setSeedNormal(glm::vec3(seed.normal[t * 3], seed.normal[t * 3 + 1],
                                           seed.normal[t * 3 + 2]));
                const float e0 = seed.exponentMap.empty() ? seed.exponent : seed.exponentMap[t];
                const double eta0 = std::log(std::max(double(e0), 1e-2));
                BlinnPhongResult r;
                if (ceres) {
                    const double theta0[3] = {0.0, 0.0, std::min(std::max(eta0, etaMin), etaMax)};
                    r = blinnPhongCeres(tx, blinnPhongProject(tx, theta0), etaMin, etaMax,
                                        options.maxIterations);
                } else {
                    r = blinnPhongBuiltin(tx, eta0, etaMin, etaMax, options.maxIterations);
                }
                const glm::dvec3 n = tx.normal(r.theta[0], r.theta[1]);
                maps.exponentMap[t] = float(std::exp(r.theta[2]));
                for (int c = 0; c < 3; ++c) {
                    maps.normal[t * 3 + size_t(c)] = float(n[c]);
                    // ρ (a + d) + k g with ρ = m, ρ a = b; keep ρ away from 0 so a stays finite.
                    double m = r.coef[c][0];
                    if (std::fabs(m) < 1e-6) m = m < 0 ? -1e-6 : 1e-6;
                    maps.albedo[t * 3 + size_t(c)] = float(m);
                    maps.ambient[t * 3 + size_t(c)] = float(r.coef[c][1] / m);
                    maps.specular[t * 3 + size_t(c)] = float(r.coef[c][2]);
                }
                iterations[t] = r.iterations;
            }
        }
    });
    double sum = 0.0;
    for (double v : iterations) sum += v;
    out.meanIterations = sum / double(texels);
    maps.validate();
    return out;
}

} // namespace weft
