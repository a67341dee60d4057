// The sun of the analytic sky: an extraterrestrial black-body sun scaled to the luminous solar
// constant, attenuated per wavelength by Rayleigh scattering and aerosols along the air mass.
#include "SkySun.h"

#include <cmath>

#include <weft/Sky.h>

namespace weft::sky {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Luminous solar constant (klx): Darula, Kittler & Gueymard 2005, "Reference luminous solar
// constant and solar luminance for illuminance calculations", Solar Energy 79(5).
constexpr double kLuminousSolarConstant = 133.8;
constexpr double kSunTemperature = 5778.0; // K, the sun's effective temperature
constexpr double kLambdaMin = 380.0, kLambdaMax = 780.0, kLambdaStep = 5.0; // nm

// Piecewise Gaussian of Wyman, Sloan & Shirley 2013, "Simple Analytic Approximations to the CIE
// XYZ Color Matching Functions" (JCGT 2(2)): the multi-lobe fit of the CIE 1931 2-degree
// observer, accurate to well under 1% of the peak -- enough for the sun's colour.
double lobe(double x, double mu, double below, double above) {
    const double t = (x - mu) / (x < mu ? below : above);
    return std::exp(-0.5 * t * t);
}

glm::dvec3 cie1931(double nm) {
    return {1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) -
                0.065 * lobe(nm, 501.1, 20.4, 26.2),
            0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1),
            1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8)};
}

// Planck's law up to a constant factor (only the spectrum's shape is used).
double blackBody(double nm, double kelvin) {
    const double c2 = 1.4387769e7; // second radiation constant, nm K
    return std::pow(nm, -5.0) / std::expm1(c2 / (nm * kelvin));
}

} // namespace

double sunSolidAngle() { return 2.0 * kPi * (1.0 - std::cos(kSunAngularRadius)); }

std::vector<glm::vec3> sunDiscPoints(const glm::vec3& toSun, int count) {
    glm::vec3 t = std::abs(toSun.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    t = glm::normalize(glm::cross(t, toSun));
    const glm::vec3 b = glm::cross(toSun, t);
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    std::vector<glm::vec3> points(static_cast<size_t>(count));
    for (int k = 0; k < count; ++k) {
        // Equal areas on the (tiny, flat) disc: radius ~ sqrt of the enclosed fraction.
        const double r = kSunAngularRadius * std::sqrt((k + 0.5) / count);
        const double phi = golden * k;
        const glm::dvec3 d = glm::dvec3(toSun) + std::tan(r) * (std::cos(phi) * glm::dvec3(t) +
                                                                std::sin(phi) * glm::dvec3(b));
        points[size_t(k)] = glm::vec3(glm::normalize(d));
    }
    return points;
}

double SunRadiance::airMass(double cosZenith) {
    const double zenithDeg = std::acos(std::min(1.0, std::max(0.0, cosZenith))) * 180.0 / kPi;
    return 1.0 / (std::max(0.0, cosZenith) + 0.15 * std::pow(93.885 - zenithDeg, -1.253));
}

SunRadiance::SunRadiance(double turbidity) {
    // Preetham et al. 1999, appendix A.1: Angstrom's turbidity coefficient from T, alpha = 1.3.
    const double beta = 0.04608365822050 * turbidity - 0.04586025928522;
    glm::dvec3 sum(0.0);
    for (double nm = kLambdaMin; nm <= kLambdaMax + 1e-9; nm += kLambdaStep) {
        const double um = nm * 1e-3;
        mDepth.push_back(0.008735 * std::pow(um, -4.08) + beta * std::pow(um, -1.3));
        mXyz.push_back(blackBody(nm, kSunTemperature) * cie1931(nm));
        sum += mXyz.back();
    }
    // Outside the atmosphere the disc's luminance is the luminous solar constant over its solid
    // angle; the spectrum sets the colour.
    const double luminance = kLuminousSolarConstant / sunSolidAngle();
    for (glm::dvec3& w : mXyz) w *= luminance / sum.y;
}

glm::vec3 SunRadiance::operator()(const glm::vec3& dir) const {
    if (!(dir.y > 0.0f)) return glm::vec3(0.0f);
    const double m = airMass(dir.y);
    glm::dvec3 xyz(0.0);
    for (size_t k = 0; k < mDepth.size(); ++k) xyz += mXyz[k] * std::exp(-mDepth[k] * m);
    // A sun deep in the air mass is nearly spectral red, just outside the Rec. 709 gamut.
    return glm::max(xyzToRgb(xyz), glm::vec3(0.0f));
}

glm::vec3 xyzToRgb(const glm::dvec3& c) {
    return glm::vec3(float(3.2406 * c.x - 1.5372 * c.y - 0.4986 * c.z),
                     float(-0.9689 * c.x + 1.8758 * c.y + 0.0415 * c.z),
                     float(0.0557 * c.x - 0.2040 * c.y + 1.0570 * c.z));
}

} // namespace weft::sky
