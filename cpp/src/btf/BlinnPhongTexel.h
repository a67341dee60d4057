#pragma once
// One texel's Blinn-Phong problem: P_sc = m_c max(n·l_s, 0) + b_c + k_c max(n·h_s, 0)^e with
// n = normalise(n0 + u t1 + v t2) and e = exp(η). Shared by the built-in and Ceres solvers.
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
    BlinnPhongGeometry(const std::vector<glm::vec3>& lights, const std::vector<glm::vec3>& halves);
};

struct BlinnPhongTexel {
    const std::vector<glm::vec3>* lights = nullptr; ///< l_s
    const std::vector<glm::vec3>* halves = nullptr; ///< h_s
    std::vector<float> values;                      ///< p, [sample][channel]
    double squares[3] = {0, 0, 0};                  ///< Σ_s p_sc² (set with the values)
    glm::dvec3 n0{0, 0, 1}, t1{1, 0, 0}, t2{0, 1, 0};
    // For the built-in solver: the values as [channel][padded sample] (zero padding), Σ_s p_sc.
    const BlinnPhongGeometry* geometry = nullptr;
    const float* planes = nullptr;
    std::vector<float> planeStore;
    double sums[3] = {0, 0, 0};

    void setSeedNormal(glm::vec3 n);
    void updateSquares();
    /// updateSquares() plus `planes` (in planeStore) and `sums` from `values` (needs `geometry`).
    void prepare();
    /// `planes`, `sums` and `squares` from planes laid out as above (values left alone).
    void setPlanes(const float* p);
    glm::dvec3 normal(double u, double v) const;
};

struct BlinnPhongResult {
    double theta[3] = {0, 0, 0}; ///< u, v, η
    double coef[3][3] = {};      ///< [channel] (m, b, k)
    double cost = 0;             ///< Σ residual²
    int iterations = 0;
};

/// For fixed (u, v, η): the optimal (m, b, k) per channel and the cost (variable projection).
BlinnPhongResult blinnPhongProject(const BlinnPhongTexel& texel, const double theta[3]);

/// Levenberg-Marquardt over (u, v, η) with Kaufman's variable-projection Jacobian.
BlinnPhongResult blinnPhongBuiltin(const BlinnPhongTexel& texel, double eta0, double etaMin,
                                   double etaMax, int maxIterations);

/// The full 12-parameter problem with Ceres (autodiff), started from `start`. Throws Error when
/// weft was built without Ceres.
BlinnPhongResult blinnPhongCeres(const BlinnPhongTexel& texel, const BlinnPhongResult& start,
                                 double etaMin, double etaMax, int maxIterations);

} // namespace weft
