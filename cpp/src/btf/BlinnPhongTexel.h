#pragma once
// One texel's Blinn-Phong problem, in the renderer's form (shading.glsl):
//   P_sc = w_s (m_c max(n·l_s, 0) + k_c [n·l_s > 0] max(n_s·h_s, 0)^e) + b_c
// with n = normalise(u, v, 1) (so n_z > 0 whatever u, v), n_s = n or (0, 0, 1) (seed eq. 4.30),
// e = exp(η) in [e_min, e_max] and m, b, k >= 0 (non-negative least squares per channel).
// w_s = 1 for a sample that is used, 0 for one left out (estimated cast shadow, padding).
// Shared by the built-in and Ceres solvers.
#include <vector>

#include <glm/glm.hpp>

namespace weft {

/// The sample directions as structure-of-arrays floats, padded with zeros to a multiple of
/// kBlinnPhongLanes (a padded sample has l = h = 0, so it adds nothing but to the constant
/// basis function, which the solver counts separately). Built once per fit, shared by all texels.
constexpr int kBlinnPhongLanes = 8;
struct BlinnPhongGeometry {
    int count = 0, padded = 0;
    std::vector<float> l[3], h[3]; ///< [axis][sample]
    std::vector<float> ones;       ///< 1 for each real sample, 0 for padding: all samples used
    std::vector<float> logHz;  ///< log h_z (0 where h_z <= 0): n_s = (0,0,1) needs no log per fit
    bool flatSpecular = false; ///< n_s = (0, 0, 1)
    unsigned long long id;     ///< unique per constructed geometry (blinnPhongTerms' memo)
    BlinnPhongGeometry(const std::vector<glm::vec3>& lights, const std::vector<glm::vec3>& halves);
};

struct BlinnPhongTexel {
    const std::vector<glm::vec3>* lights = nullptr;   ///< l_s
    const std::vector<glm::vec3>* halves = nullptr;   ///< h_s
    std::vector<float> values;                        ///< p, [sample][channel]
    double squares[3] = {0, 0, 0};                    ///< Σ_s p_sc² (set with the values)
    glm::dvec3 n0{0, 0, 1}, t1{1, 0, 0}, t2{0, 1, 0}; ///< n = normalise(n0 + u t1 + v t2)
    double start[2] = {0, 0};                         ///< (u, v) of the seed normal
    // For the built-in solver: the values as [channel][padded sample] (zero padding), Σ_s w_s p_sc.
    const BlinnPhongGeometry* geometry = nullptr;
    const float* planes = nullptr;
    const float* weights = nullptr; ///< w_s per padded sample (geometry->ones: all used)
    double used = 0;                ///< Σ_s w_s
    std::vector<float> planeStore;
    double sums[3] = {0, 0, 0};
    /// false: the model without its highlight (k = 0), for a texel whose fitted lobe no sample
    /// sees (k and e then have no support in the data)
    bool specular = true;

    /// The start (u, v) for a seed normal; a normal below the horizon starts at n_z = 0.05.
    void setSeedNormal(glm::vec3 n);
    void updateSquares();
    /// updateSquares() plus `planes` (in planeStore) and `sums` from `values` (needs `geometry`).
    void prepare();
    /// `planes`, `sums`, `squares` and `used` from planes laid out as above and the sample
    /// weights `w` (null: all samples); values left alone.
    void setPlanes(const float* p, const float* w = nullptr);
    glm::dvec3 normal(double u, double v) const;
};

struct BlinnPhongResult {
    double theta[3] = {0, 0, 0}; ///< u, v, η
    double coef[3][3] = {};      ///< [channel] (m, b, k)
    double cost = 0;             ///< Σ residual²
    int iterations = 0;
};

/// For fixed (u, v, η): the optimal (m, b, k) >= 0 per channel and the cost (variable projection).
BlinnPhongResult blinnPhongProject(const BlinnPhongTexel& texel, const double theta[3]);

/// Levenberg-Marquardt over (u, v, η) with Kaufman's variable-projection Jacobian, η kept in
/// [etaMin, etaMax] by projecting each step; starts at (start[0], start[1], eta0).
BlinnPhongResult blinnPhongBuiltin(const BlinnPhongTexel& texel, double eta0, double etaMin,
                                   double etaMax, int maxIterations);

/// Per-sample model terms at θ for the used coefficients: d_s = max(n·l_s, 0) and the gated
/// highlight g_s (both without w_s), for shadow classification; `specular` false: g = 0 (for a
/// fit whose k is 0 in every channel: no log or exp per sample).
void blinnPhongTerms(const BlinnPhongTexel& texel, const double theta[3], std::vector<double>& d,
                     std::vector<double>& g, bool specular = true);

/// The full 12-parameter problem with Ceres (autodiff, m, b, k >= 0 and η bounded), started
/// from `start`, over the samples with w_s > 0. Throws Error when weft was built without Ceres.
BlinnPhongResult blinnPhongCeres(const BlinnPhongTexel& texel, const BlinnPhongResult& start,
                                 double etaMin, double etaMax, int maxIterations);

} // namespace weft
