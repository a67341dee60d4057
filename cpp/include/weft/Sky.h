#pragma once
// An analytic daylight sky for the day-night cycle: Preetham, Shirley & Smits 1999, "A Practical
// Analytic Model for Daylight" (SIGGRAPH 99). The sky's luminance Y and chromaticity x, y each
// follow the Perez et al. distribution F(theta, gamma) = (1 + A e^(B / cos theta))
// (1 + C e^(D gamma) + E cos^2 gamma), normalised so that the zenith takes the paper's zenith
// values: Y = Y_z F(theta, gamma) / F(0, theta_s) (theta: view zenith angle, gamma: angle to the
// sun, theta_s: the sun's zenith angle). A..E are linear in the turbidity T (paper, appendix
// A.2); Y_z (kcd/m^2) and x_z, y_z are the paper's fits in T and theta_s. xyY -> XYZ -> linear
// Rec. 709 (sRGB primaries, D65), negative channels (out of gamut) clamped to 0.
//
// Units: radiance is luminance-calibrated, Rec. 709 luminance of the RGB = Y in kcd/m^2, times
// `scale`; irradiance (the sun's) is then in klx. The sun: see sunIrradiance() (as a scene
// light: sunLight in weft/SunLight.h).
// Below the horizon: a Lambertian ground of RGB `groundAlbedo` lit by the sky and the sun,
// L = albedo E_horizontal / pi. Night: the model holds for the sun above the horizon only; below
// it the sky is the model's sky for the sun on the horizon (same azimuth) dimmed by
// 10^(0.4 h) (h: solar elevation in degrees, < 0), about the measured fall of twilight
// illuminance (~400 lx at sunset, ~3 lx at h = -6 deg, civil twilight's end), plus a constant
// night sky `nightRadiance` that it fades into.
#include <glm/glm.hpp>

#include <weft/CubeMap.h>

namespace weft {

/// Mean angular radius of the sun seen from the earth (0.2666 deg; diameter 0.533 deg).
constexpr double kSunAngularRadius = 0.0046531;
/// Turbidity range of the model (below 1.7 the zenith factor 1 + A e^B of Y nears 0).
constexpr float kSkyTurbidityMin = 1.7f;
constexpr float kSkyTurbidityMax = 10.0f;

struct SkyParams {
    /// Towards the sun (world, +Y up); any length > 0.
    glm::vec3 sunDirection{0.0f, 1.0f, 0.0f};
    /// Atmospheric turbidity T in [1.7, 10]: 2 very clear, 3 clear, 6 light haze, 10 haze.
    float turbidity = 3.0f;
    /// RGB albedo of the Lambertian ground below the horizon, each in [0, 1] (grey 0.2 by
    /// default; a scene's own ground colour makes the ground beyond it a continuation of it).
    glm::vec3 groundAlbedo{0.2f};
    /// Include the sun's disc in sky cube maps (skyCube); leave it out when the sun is a light.
    bool sun = true;
    /// Multiplies every radiance and irradiance (1: luminance in kcd/m^2), >= 0.
    float scale = 1.0f;
    /// Night sky radiance (before `scale`) that the twilight fades into, >= 0. The default is
    /// the natural (moonless, unpolluted) night sky's luminance, 174 ucd/m^2 (Falchi et al.
    /// 2016, the world atlas of artificial night sky brightness), slightly blue.
    glm::vec3 nightRadiance{1.5e-7f, 1.7e-7f, 2.4e-7f};

    /// Throws InvalidArgument for a zero or non-finite sun direction, a turbidity outside
    /// [1.7, 10], an albedo outside [0, 1], a negative or non-finite scale or night radiance.
    void validate() const;
};

/// The sky model for one set of parameters (validated): coefficients, zenith values and the
/// ground's radiance evaluated once, radiance() per direction.
class SkyModel {
public:
    explicit SkyModel(const SkyParams& params);

    const SkyParams& params() const { return mParams; }
    /// Unit direction towards the sun.
    const glm::vec3& toSun() const { return mToSun; }
    /// Radiance (RGB, see units above) of the sky or ground in `dir` (any length > 0), without
    /// the sun's disc; throws InvalidArgument for a zero or non-finite direction.
    glm::vec3 radiance(const glm::vec3& dir) const;
    /// CIE xyY of the sky in `dir` (upper hemisphere, before twilight dimming and scale): the
    /// paper's quantities, for tests. Y in kcd/m^2.
    glm::vec3 xyY(const glm::vec3& dir) const;
    /// The paper's zenith chromaticity and luminance (x_z, y_z, Y_z in kcd/m^2) for this sun
    /// (the sun's zenith angle clamped to 90 deg).
    glm::vec3 zenithxyY() const { return mZenith; }
    /// Irradiance (RGB) of the sun's disc at normal incidence: the integral of its radiance over
    /// the part of the disc above the horizon (see sunIrradiance).
    const glm::vec3& sunIrradiance() const { return mSunIrradiance; }
    /// Irradiance (RGB) of the sky alone (without the sun) on a horizontal surface facing up.
    const glm::vec3& skyHorizontalIrradiance() const { return mSkyHorizontal; }

private:
    glm::vec3 skyAbove(const glm::vec3& dir) const;

    SkyParams mParams;
    glm::vec3 mToSun{0.0f, 1.0f, 0.0f};
    glm::vec3 mModelSun{0.0f, 1.0f, 0.0f}; // the sun the Perez model sees (clamped to the horizon)
    float mThetaS = 0.0f;
    float mTwilight = 1.0f;   // dimming below the horizon
    float mCoeffs[3][5] = {}; // A..E of Y, x, y
    float mNorm[3] = {};      // value / F(0, theta_s) at the zenith: Y_z, x_z, y_z over F
    glm::vec3 mZenith{0.0f};
    glm::vec3 mSunIrradiance{0.0f};
    glm::vec3 mSkyHorizontal{0.0f};
    glm::vec3 mGround{0.0f};
};

/// A cube map of `size` (1..2048) texels per face of the sky's radiance (linear RGB, +Y up, the
/// face convention of CubeMap.h); with params.sun the sun's disc (0.533 deg) is added so that
/// the cube's radiance integrated over the disc is the sun's irradiance exactly, whatever the
/// texel size (a disc smaller than a texel brightens that texel). Throws InvalidArgument for bad
/// parameters or size.
CubeMap skyCube(const SkyParams& params, int size);

/// The sun's irradiance at normal incidence (RGB, klx times scale): the extraterrestrial sun
/// (luminous solar constant 133.8 klx, Darula, Kittler & Gueymard 2005, with the spectrum of a
/// 5778 K black body) through the atmosphere along the relative optical air mass of Kasten 1966,
/// m = 1 / (cos theta + 0.15 (93.885 - theta_deg)^-1.253), with the paper's spectral
/// transmittances (appendix A.1): Rayleigh exp(-0.008735 lambda^-4.08 m) and aerosols (Angstrom)
/// exp(-beta lambda^-1.3 m), beta = 0.04608 T - 0.04586 (lambda in um); ozone, water vapour and
/// mixed gases are left out (small in the visible). Evaluated per point of the disc, so a sun
/// setting loses its lower limb first; 0 once the disc is below the horizon.
glm::vec3 sunIrradiance(const SkyParams& params);

} // namespace weft
