// The per-texel Blinn-Phong problem with Ceres Solver (full 12 parameters, automatic
// derivatives, m, b, k >= 0 and η in [η_min, η_max] as parameter bounds); compiled to a stub
// that throws when weft is built without Ceres.
#include <weft/Error.h>

#include "btf/BlinnPhongTexel.h"

#ifdef WEFT_HAVE_CERES
#include <ceres/ceres.h>
#endif

#include <algorithm>

namespace weft {

#ifdef WEFT_HAVE_CERES

namespace {

struct SampleResidual {
    glm::dvec3 l, h, n0, t1, t2;
    double p[3];
    bool flat;

    template <typename T>
    bool operator()(const T* uv, const T* m, const T* b, const T* k, const T* eta, T* r) const {
        T w[3], len2 = T(0);
        for (int i = 0; i < 3; ++i) {
            w[i] = T(n0[i]) + uv[0] * T(t1[i]) + uv[1] * T(t2[i]);
            len2 += w[i] * w[i];
        }
        const T len = ceres::sqrt(len2);
        T nl = T(0), nh = T(0);
        for (int i = 0; i < 3; ++i) {
            nl += w[i] * T(l[i]);
            nh += w[i] * T(h[i]);
        }
        nl /= len;
        nh = flat ? T(h[2]) : nh / len;
        // the renderer's model: no highlight where n·l <= 0
        const T d = nl > T(0) ? nl : T(0);
        const T g = nl > T(0) && nh > T(0) ? ceres::exp(ceres::exp(eta[0]) * ceres::log(nh)) : T(0);
        for (int c = 0; c < 3; ++c) r[c] = m[c] * d + b[c] + k[c] * g - T(p[c]);
        return true;
    }
};

} // namespace

BlinnPhongResult blinnPhongCeres(const BlinnPhongTexel& tx, const BlinnPhongResult& start,
                                 double etaMin, double etaMax, int maxIterations) {
    double uv[2] = {start.theta[0], start.theta[1]}, eta = start.theta[2];
    double m[3], b[3], k[3];
    for (int c = 0; c < 3; ++c) {
        m[c] = start.coef[c][0];
        b[c] = start.coef[c][1];
        k[c] = start.coef[c][2];
    }
    ceres::Problem problem;
    for (size_t s = 0; s < tx.lights->size(); ++s) {
        if (tx.weights && !(tx.weights[s] > 0.0f)) continue; // left out (cast shadow)
        auto* cost =
            new SampleResidual{glm::dvec3((*tx.lights)[s]),
                               glm::dvec3((*tx.halves)[s]),
                               tx.n0,
                               tx.t1,
                               tx.t2,
                               {tx.values[s * 3], tx.values[s * 3 + 1], tx.values[s * 3 + 2]},
                               tx.geometry && tx.geometry->flatSpecular};
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<SampleResidual, 3, 2, 3, 3, 3, 1>(cost), nullptr, uv, m,
            b, k, &eta);
    }
    for (double* coef : {m, b, k})
        for (int c = 0; c < 3; ++c) {
            coef[c] = std::max(coef[c], 0.0);
            problem.SetParameterLowerBound(coef, c, 0.0);
        }
    if (!tx.specular) {
        for (int c = 0; c < 3; ++c) k[c] = 0.0;
        problem.SetParameterBlockConstant(k);
    }
    if (etaMin < etaMax) {
        problem.SetParameterLowerBound(&eta, 0, etaMin);
        problem.SetParameterUpperBound(&eta, 0, etaMax);
    } else { // the exponent is held
        eta = etaMin;
        problem.SetParameterBlockConstant(&eta);
    }
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.max_num_iterations = maxIterations;
    options.logging_type = ceres::SILENT;
    options.minimizer_progress_to_stdout = false;
    options.num_threads = 1;
    options.function_tolerance = 1e-10;
    options.parameter_tolerance = 1e-10;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    BlinnPhongResult out;
    out.theta[0] = uv[0];
    out.theta[1] = uv[1];
    out.theta[2] = eta;
    for (int c = 0; c < 3; ++c) {
        out.coef[c][0] = m[c];
        out.coef[c][1] = b[c];
        out.coef[c][2] = k[c];
    }
    out.cost = 2.0 * summary.final_cost;
    out.iterations = int(summary.iterations.size());
    return out;
}

#else

BlinnPhongResult blinnPhongCeres(const BlinnPhongTexel&, const BlinnPhongResult&, double, double,
                                 int) {
    throw Error("weft was built without Ceres Solver; use the built-in solver");
}

#endif

} // namespace weft
