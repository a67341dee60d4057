#pragma once
// The sun of the analytic sky (see weft/Sky.h): its disc as equal-area points and the radiance of
// each point after the atmosphere.
#include <vector>

#include <glm/glm.hpp>

namespace weft::sky {

/// Solid angle (sr) of the sun's disc, 2 pi (1 - cos kSunAngularRadius).
double sunSolidAngle();

/// `count` unit directions spread evenly by area over the sun's disc around unit `toSun` (a
/// sunflower spiral): each stands for sunSolidAngle() / count steradians.
std::vector<glm::vec3> sunDiscPoints(const glm::vec3& toSun, int count);

/// Transmits the extraterrestrial sun through an atmosphere of turbidity T; see sunIrradiance in
/// weft/Sky.h for the model. Spectral weights are set up once per turbidity.
class SunRadiance {
public:
    explicit SunRadiance(double turbidity);
    /// Linear Rec. 709 RGB radiance (kcd/m^2 luminance) of a point of the disc in unit direction
    /// `dir`; 0 at or below the horizon.
    glm::vec3 operator()(const glm::vec3& dir) const;
    /// Relative optical air mass (Kasten 1966) along a direction of zenith angle cosine
    /// `cosZenith`.
    static double airMass(double cosZenith);

private:
    std::vector<double> mDepth;   // optical depth per unit air mass, per wavelength
    std::vector<glm::dvec3> mXyz; // black body x CIE colour matching functions, per wavelength
};

/// Linear Rec. 709 (sRGB primaries, D65 white) from CIE XYZ (IEC 61966-2-1).
glm::vec3 xyzToRgb(const glm::dvec3& xyz);

} // namespace weft::sky
