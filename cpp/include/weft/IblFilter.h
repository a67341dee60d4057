#pragma once
// Irradiance and glossy filtering of cube-map environments (SPEC §4.3).
//
// Irradiance is physical: E(n) = integral of L(w) max(0, n.w) dw, so a constant radiance L gives
// E = pi L (divide by pi for the diffuse colour of a white Lambertian surface). All integrals
// treat the cube as a sphere: each texel counts with its exact solid angle.
#include <array>
#include <vector>

#include <glm/glm.hpp>

#include <weft/CubeMap.h>

namespace weft {

/// Nine real spherical-harmonic radiance coefficients L_lm (RGB) in the order
/// Y00, Y1-1 (y), Y10 (z), Y11 (x), Y2-2 (xy), Y2-1 (yz), Y20 (3z^2 - 1), Y21 (xz), Y22 (x^2 - y^2)
/// over world coordinates (Ramamoorthi & Hanrahan 2001).
struct Sh9 {
    std::array<glm::vec3, 9> coeffs{};
};

/// The nine basis functions at unit direction d.
std::array<float, 9> sh9Basis(const glm::vec3& d);
/// Projects radiance onto SH9 with precomputed per-texel basis x solid-angle tables (cached per
/// size), multithreaded. Level 0 is used.
Sh9 projectSh9(const CubeMap& radiance);
/// Irradiance from SH9: sum of A_l L_lm Y_lm(n), A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4.
glm::vec3 shIrradiance(const Sh9& sh, const glm::vec3& normal);
/// An irradiance cube map of `size` evaluated from SH9.
CubeMap irradianceFromSh(const Sh9& sh, int size);
/// Exact cosine convolution (the reference): every output texel sums all source texels of the
/// first mip level whose size is <= sourceSize. Cost ~ 6 size^2 x 6 sourceSize^2.
CubeMap irradianceExact(const CubeMap& radiance, int size, int sourceSize = 64);
/// The seed's 2D filter: cube -> sphere map (wrap 1, sphereSize^2), `passes` separable box blurs
/// of radius `radius` texels, -> cube of `size`, times pi.
CubeMap irradianceBoxBlur(const CubeMap& radiance, int size, int sphereSize = 64, int radius = 12,
                          int passes = 2);
/// The seed's 3-axis rotational ("cylindrical") blur: the map is averaged over `steps` rotations
/// in [-halfAngle, halfAngle] about X, then Z, then Y, at `size`, times pi.
CubeMap irradianceRotationalBlur(const CubeMap& radiance, int size, float halfAngle = 1.0f,
                                 int steps = 16);

/// Phong lobe, exact: G(R) = sum L dw max(0, R.w)^s / sum dw max(0, R.w)^s over the source
/// level of size <= sourceSize (texels with weight below 1e-6 of the peak are skipped).
CubeMap phongExact(const CubeMap& radiance, float shininess, int size, int sourceSize = 64);
/// Phong lobe by filtered importance sampling: `samples` Hammersley directions from the lobe,
/// each read from the mip level whose texel solid angle matches the sample's (Krivanek &
/// Colbert 2008), so a tiny bright source is spread instead of producing fireflies.
CubeMap phongSampled(const CubeMap& radiance, float shininess, int size, int samples = 64);
/// GGX split-sum prefiltered chain (Karis 2013, N = V = R): mip level m of the result holds
/// perceptual roughness m / (levels - 1) (alpha = roughness^2); level 0 is the source resampled.
/// Converged next to a small bright sun (cpp/src/ibl/GgxPlan.h): rough levels are exact sums over
/// the texel clusters of a source mip; narrow ones sample (as phongSampled) the environment
/// clamped to 8x its mean luminance and sum what the clamp removed exactly. `samples` sets both
/// the samples per texel and the cluster budget (24 per sample, at most 16384).
CubeMap prefilterGgx(const CubeMap& radiance, int size, int levels = 5, int samples = 64);
/// Split-sum DFG table, `size` x `size` x 2 floats (scale, bias to F0): row j has perceptual
/// roughness (j + 0.5) / size, column i has n.v = (i + 0.5) / size; Smith-Schlick G, k = a / 2.
std::vector<float> dfgLut(int size = 32, int samples = 256);
/// The directional albedo of a GGX coat towards a view at cos n.v = `cosView` (clamped to
/// >= 1e-4): the fraction of a uniform sky a dielectric microfacet surface of `alpha` (0: a
/// mirror) and normal-incidence reflectance `f0` reflects, the integral of f(l, v) (n.l) with
/// GGX D, separable Smith G1 and the dielectric's exact Fresnel (eta = (1 + sqrt f0) /
/// (1 - sqrt f0)), by `samples` Hammersley importance samples of D (n.h). What Mitsuba's
/// roughconductor with k = 0 reflects and Material::specularModel's Ggx weights its prefiltered
/// reflection with; unlike dfgLut's Schlick Fresnel (10-25% low at F0 0.02-0.05 against it) it
/// does not split into a scale and a bias to F0. Throws InvalidArgument outside cosView, alpha,
/// f0 in [0, 1], samples in [1, 2^20].
double coatAlbedo(double cosView, double alpha, double f0, int samples = 1024);
/// coatAlbedo on an even grid (the renderer's table, render/CoatAlbedoGpu.h): `f0s` layers of
/// `roughness` rows of `cosines` values, value [(k * roughness + j) * cosines + i] at
/// sqrt(n.v) = i / (cosines - 1), perceptual roughness sqrt(alpha) = j / (roughness - 1) and
/// sqrt(F0) = k / (f0s - 1) (F0 = 1 taken as 0.999: a perfect mirror has no IOR).
std::vector<float> coatAlbedoTable(int cosines, int roughness, int f0s, int samples = 1024);

/// The point of the Hammersley set: (i / n, radical inverse of i).
glm::vec2 hammersley(unsigned i, unsigned n);

} // namespace weft
