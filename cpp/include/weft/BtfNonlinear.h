#pragma once
// Per-texel nonlinear Blinn-Phong fit seeded by the linear fit (SPEC §3.5):
// P_c = m_c max(n·l, 0) + b_c + k_c max(n·h, 0)^e, unknowns n (2 dof), m, b, k (RGB), e.
// Built-in: Levenberg-Marquardt over (n, log e) with m, b, k eliminated by variable projection
// (Kaufman's Jacobian). Ceres (when built with it): the full 12-parameter problem, autodiff.
#include <string>

#include <weft/BtfFit.h>

namespace weft {

enum class BtfSolver { Auto, Builtin, Ceres };

struct BtfNonlinearOptions {
    BtfSolver solver = BtfSolver::Auto; ///< Auto: Ceres when built with it, else built-in
    int maxIterations = 30;
    float minExponent = 1.0f, maxExponent = 4096.0f;
    int threads = 0;
};

struct BtfNonlinearFit {
    BtfMaterialMaps maps; ///< clamped diffuse, n_s = n, per-texel exponent
    double meanIterations = 0;
    std::string solver;   ///< "builtin" or "ceres"
};

/// True when weft was built with Ceres Solver.
bool btfHaveCeres();

/// Seeds from `seed` (normal, ρ, a, k, exponent of the linear + specular pipeline).
BtfNonlinearFit fitBtfBlinnPhong(const BtfSamples& samples, const BtfMaterialMaps& seed,
                                 const BtfNonlinearOptions& options = {});

} // namespace weft
