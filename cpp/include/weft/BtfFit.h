#pragma once
// The seed's BTF fit (SPEC §3.2-3.3): diffuse texture T = per-texel mean, normal n and ambient
// I_A by linear least squares (eq. 4.22), specular map from the residual of the θ_l = 0 sample
// and a Blinn-Phong exponent search; plus an outlier-robust variant (IRLS) of the linear fit.
// Maps are interleaved per texel: (height, width, 3) floats, rows top to bottom.
#include <cstdint>
#include <vector>

#include <weft/BtfSamples.h>

namespace weft {

struct BtfLinearOptions {
    bool robust = false; ///< IRLS (Tukey biweight) and samples with n·l <= 0 dropped
    int robustIterations = 4;
    float darkThreshold = 1e-4f; ///< channels with T below this are "dark" (no equations)
    int threads = 0;
};

struct BtfLinearFit {
    int width = 0, height = 0;
    std::vector<float> texture; ///< T, per-texel mean of all samples
    std::vector<float> normal;  ///< n as solved (not normalised; |n| carries the fit's scale)
    std::vector<float> ambient; ///< I_A per channel
    std::vector<uint8_t> dark;  ///< 1 where every channel of T is below darkThreshold
    int darkTexels = 0;         ///< texels with all channels dark (n set to (0, 0, 1))
    int darkChannels = 0;       ///< texel channels without equations (I_A set from the others)
};

/// Fits all samples (any views). Throws InvalidArgument when the light directions do not span
/// 3D with a constant term (fewer than 4 samples, coplanar lights).
BtfLinearFit fitBtfLinear(const BtfSamples& samples, const BtfLinearOptions& options = {});

/// The same least squares for a texture t that is not the sample mean (tests, other models):
/// unknowns (n, a_r, a_g, a_b) per texel minimise Σ_s,c (t_c (l_s·n) + t_c a_c - p_sc)^2.
BtfLinearFit solveBtfLinear(const BtfSamples& samples, const std::vector<float>& texture,
                            const BtfLinearOptions& options = {});

/// A per-texel reflectance model the renderer can consume: P = ρ ⊙ (a + d(n·l)) +
/// k (max(n_s·h, 0))^e, d(x) = x (linear, the seed) or, with clampDiffuse, the renderer's model:
/// d(x) = max(x, 0) and no highlight where n·l <= 0. h = normalise(l + v), n_s = n (eq. 4.29)
/// or (0, 0, 1) (eq. 4.30). A linear fit maps to ρ = T|n|, a = I_A/|n|, n/|n|.
struct BtfMaterialMaps {
    int width = 0, height = 0;
    std::vector<float> normal;   ///< unit normals (H, W, 3)
    std::vector<float> albedo;   ///< ρ (H, W, 3)
    std::vector<float> ambient;  ///< a (H, W, 3)
    std::vector<float> specular; ///< k (H, W, 3); empty = no specular term
    float exponent = 1.0f;
    std::vector<float> exponentMap;  ///< per-texel exponent (H, W); empty = `exponent` everywhere
    bool flatSpecularNormal = false; ///< n_s = (0, 0, 1)
    bool clampDiffuse = false;
    void validate() const;
};

/// The seed's maps from a linear fit (no specular).
BtfMaterialMaps btfMaterialFromLinear(const BtfLinearFit& fit);

/// Per-sample mean squared error over texels and channels (values as given, [0, 1] scale).
/// When `reconstruction` is not null it receives the model's samples (same layout as samples).
std::vector<double> btfSampleErrors(const BtfSamples& samples, const BtfMaterialMaps& maps,
                                    std::vector<float>* reconstruction = nullptr, int threads = 0);

struct BtfSpecularOptions {
    bool flatSpecularNormal = true; ///< eq. 4.30 (n_s = (0,0,1)); false: eq. 4.29
    int maxExponent = 4096;
    bool perTexel = false; ///< also a per-texel exponent (log-spaced candidates)
    int threads = 0;
};

struct BtfSpecularFit {
    BtfMaterialMaps maps;      ///< linear maps + specular map + best exponent
    std::vector<double> curve; ///< total squared error for exponents 1..maxExponent
                               ///< (eq. 4.30: every integer; eq. 4.29: NaN where skipped)
    int specularSample = 0;    ///< the θ_l = 0 sample whose residual is the specular map
};

/// Specular map from the residual of the θ_l = 0 sample (frontal view when present) and the
/// exponent minimising the total squared error. Eq. 4.30 costs O(samples) per candidate after
/// one pass; eq. 4.29 evaluates a log-spaced grid and refines it (O(texels·samples) each).
BtfSpecularFit fitBtfSpecular(const BtfSamples& samples, const BtfLinearFit& fit,
                              const BtfSpecularOptions& options = {});

} // namespace weft
