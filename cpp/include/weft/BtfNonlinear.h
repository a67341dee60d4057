#pragma once
// Per-texel nonlinear Blinn-Phong fit seeded by the linear fit (SPEC §3.5), in the model the
// renderer draws: P_c = m_c max(n·l, 0) + b_c + k_c [n·l > 0] max(n_s·h, 0)^e, n_s = n or
// (0, 0, 1) (seed eq. 4.30). Unknowns n (2 dof), m, b, k (RGB), e, all inside the physical
// space: n = normalise(u, v, 1) (n_z > 0), m, b, k >= 0 (non-negative least squares), e in
// [minExponent, maxExponent] (projected steps).
// Built-in: Levenberg-Marquardt over (n, log e) with m, b, k eliminated by variable projection
// (Kaufman's Jacobian), the default. Ceres (when built with it and asked for): the full
// 12-parameter problem, autodiff, bounds on m, b, k and log e.
// Cast shadows: with `visibility`, samples much darker than the fitted model (closer to the
// constant term than to the lit prediction, by more than the texel's noise, itself at most twice
// the data's) are taken as shadowed and left out, and the texel is fitted again (a few rounds,
// until the set is stable); a texel whose fit misses its samples finds its shadows first with
// Lambert + ambient, which no highlight can bend to mimic them. A texel left without a highlight
// (k = 0, where the cost does not depend on e) restarts from a grid of exponents.
#include <string>

#include <weft/BtfFit.h>

namespace weft {

enum class BtfSolver { Auto, Builtin, Ceres };

struct BtfNonlinearOptions {
    BtfSolver solver = BtfSolver::Auto; ///< Auto: the built-in LM (fastest, as accurate)
    int maxIterations = 30;
    /// maxExponent 0: btfResolvableExponent(samples), the largest the sampling resolves
    float minExponent = 1.0f, maxExponent = 0.0f;
    bool flatSpecularNormal = false; ///< n_s = (0, 0, 1) (eq. 4.30) instead of n
    /// keep each texel's exponent from the seed (its exponent map, else its exponent; inside
    /// [minExponent, maxExponent]) and fit only n, m, b, k: for exponents pooled over the
    /// material (weft.btf.fit_blinn_phong(exponent="pooled"))
    bool fixedExponent = false;
    bool visibility = true; ///< estimate cast shadows per sample and leave them out
    /// fit n and e to the luma (BT.601) and only the colours to RGB: for JPEG data, whose
    /// chroma is stored at half resolution and coarser precision than the luma
    bool luminanceNormals = false;
    /// The data's noise (standard deviation of a sample's channel sum) that bounds the
    /// cast-shadow classification's σ: 0 estimates it from the samples (btfBlinnPhongNoise). A
    /// dataset fitted in parts (bands of rows) passes the whole dataset's, so that each part
    /// gives exactly its texels of the whole fit.
    double noise = 0.0;
    int threads = 0;
};

struct BtfNonlinearFit {
    BtfMaterialMaps
        maps; ///< clamped diffuse, per-texel exponent; ρ = max(m, 1e-3 b, 1e-6), a = b/ρ
    double meanIterations = 0;
    std::string solver;          ///< "builtin" or "ceres"
    double shadowedFraction = 0; ///< samples left out as cast shadows / all samples
    double noise = 0;            ///< the noise level the visibility pass used (0 without it)
};

/// True when weft was built with Ceres Solver.
bool btfHaveCeres();

/// The largest Blinn-Phong exponent the sample directions resolve: a lobe cos^e around one
/// sample's half vector must keep `fraction` of its peak at the neighbouring half vector, so
/// e_max = ln(1 / fraction) / -ln cos δ with δ the median angle from a half vector to its
/// nearest neighbour. Narrower lobes are seen by one sample at most, where k and e trade off
/// freely (needle lobes). Bonn frontal (81 lights, 15° rings): δ = 7.6°, e_max = 519 at 1%.
float btfResolvableExponent(const BtfSamples& samples, double fraction = 0.01);

/// The noise level fitBtfBlinnPhong estimates with options.noise = 0: the median over up to 1024
/// texels spread evenly over the image of the robust σ of their first fit's residuals under
/// steep light (θ_l <= 31°). Most texels fit there to the noise and the model's error.
double btfBlinnPhongNoise(const BtfSamples& samples, const BtfMaterialMaps& seed,
                          const BtfNonlinearOptions& options = {});

/// Seeds from `seed` (normal, ρ, a, k, exponent of the linear + specular pipeline).
BtfNonlinearFit fitBtfBlinnPhong(const BtfSamples& samples, const BtfMaterialMaps& seed,
                                 const BtfNonlinearOptions& options = {});

} // namespace weft

namespace weft {

/// Per-texel diffuse term plus Lafortune lobes (seed eq. 4.10/4.11):
/// P_c = m_c max(n·l, 0) + b_c + Σ_j ρ_jc max(C_xj l_x v_x + C_yj l_y v_y + C_zj l_z v_z, 0)^e_j
/// with C_zj = 1 (its scale is absorbed by ρ_jc). Built-in LM by variable projection (the
/// linear m, b, ρ eliminated), seeded by the normal and exponent of `seed`. With the frontal
/// view only, C_x and C_y have no effect (v_x = v_y = 0) and keep their start values (-1).
struct BtfLafortuneFit {
    int width = 0, height = 0, lobes = 1;
    std::vector<float> normal;     ///< (H, W, 3) unit
    std::vector<float> diffuse;    ///< m (H, W, 3)
    std::vector<float> ambient;    ///< b (H, W, 3), additive
    std::vector<float> lobeAlbedo; ///< ρ (H, W, lobes, 3)
    std::vector<float> lobeShape;  ///< (C_x, C_y, C_z, e) (H, W, lobes, 4)
    double meanIterations = 0;
};

/// `visibility`: cast shadows estimated per sample and left out, as in fitBtfBlinnPhong (off by
/// default: with a fixed Blinn-Phong normal it only raises the deviation over all samples).
/// `fixedNormal`: the seed's normal is kept. With the frontal view the lobe depends on l_z only
/// and trades off with the diffuse term, so the normal is better taken from a Blinn-Phong fit.
BtfLafortuneFit fitBtfLafortune(const BtfSamples& samples, const BtfMaterialMaps& seed, int lobes,
                                int maxIterations = 30, int threads = 0, bool visibility = false,
                                bool fixedNormal = false);

/// Per-sample mean squared error of a Lafortune fit (and the reconstruction when asked).
std::vector<double> btfLafortuneErrors(const BtfSamples& samples, const BtfLafortuneFit& fit,
                                       std::vector<float>* reconstruction = nullptr,
                                       int threads = 0);

} // namespace weft
