// The analytic daylight sky of Preetham, Shirley & Smits 1999 (see weft/Sky.h for the model,
// its units and what happens below the horizon and at night).
#include <weft/Sky.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <weft/Error.h>

#include "IblParallel.h"
#include "SkySun.h"

namespace weft {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The paper's appendix A.2: the Perez coefficients A..E of Y, x and y as (slope, offset) in T.
constexpr double kPerez[3][5][2] = {
    {{0.1787, -1.4630}, {-0.3554, 0.4275}, {-0.0227, 5.3251}, {0.1206, -2.5771}, {-0.0670, 0.3703}},
    {{-0.0193, -0.2592},
     {-0.0665, 0.0008},
     {-0.0004, 0.2125},
     {-0.0641, -0.8989},
     {-0.0033, 0.0452}},
    {{-0.0167, -0.2608},
     {-0.0950, 0.0092},
     {-0.0079, 0.2102},
     {-0.0441, -1.6537},
     {-0.0109, 0.0529}},
};
// Zenith chromaticity, appendix A.2: x_z = [T^2 T 1] M [theta_s^3 theta_s^2 theta_s 1]^T.
constexpr double kZenithX[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                                   {-0.02903, 0.06377, -0.03202, 0.00394},
                                   {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                                   {-0.04214, 0.08970, -0.04153, 0.00516},
                                   {0.15346, -0.26756, 0.06670, 0.26688}};

// Sun points for the light and the ground: enough that the lower limb sets smoothly.
constexpr int kSunPoints = 256;

double zenithChromaticity(const double m[3][4], double t, double thetaS) {
    const double tv[3] = {t * t, t, 1.0};
    const double sv[4] = {thetaS * thetaS * thetaS, thetaS * thetaS, thetaS, 1.0};
    double sum = 0.0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) sum += tv[r] * m[r][c] * sv[c];
    return sum;
}

// F(theta, gamma); cos theta is kept off 0 so that e^(B / cos theta) -> 0 at the horizon (B < 0
// over the whole turbidity range).
double perez(const float c[5], double cosTheta, double gamma) {
    const double cosGamma = std::cos(gamma);
    return (1.0 + c[0] * std::exp(c[1] / std::max(cosTheta, 1e-4))) *
           (1.0 + c[2] * std::exp(c[3] * gamma) + c[4] * cosGamma * cosGamma);
}

glm::vec3 unitOrThrow(const glm::vec3& v, const char* what) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw InvalidArgument(std::string(what) + " must be finite");
    const float len = glm::length(v);
    if (!(len > 0.0f) || !std::isfinite(len))
        throw InvalidArgument(std::string(what) + " must be a non-zero vector");
    return v / len;
}

// Irradiance of the sun's disc at normal incidence and on a horizontal surface (before scale):
// its points after the atmosphere, each sunSolidAngle() / N of the disc.
void sunDisc(const glm::vec3& toSun, double turbidity, glm::vec3& normal, glm::vec3& horizontal) {
    const sky::SunRadiance sun(turbidity);
    const double dw = sky::sunSolidAngle() / kSunPoints;
    glm::dvec3 n(0.0), h(0.0);
    for (const glm::vec3& d : sky::sunDiscPoints(toSun, kSunPoints)) {
        const glm::dvec3 e = glm::dvec3(sun(d)) * dw;
        n += e;
        h += e * double(std::max(d.y, 0.0f));
    }
    normal = glm::vec3(n);
    horizontal = glm::vec3(h);
}

} // namespace

void SkyParams::validate() const {
    unitOrThrow(sunDirection, "sky sun direction");
    if (!(turbidity >= kSkyTurbidityMin && turbidity <= kSkyTurbidityMax))
        throw InvalidArgument("sky turbidity must be in [1.7, 10] (the model's range), got " +
                              std::to_string(turbidity));
    for (int c = 0; c < 3; ++c)
        if (!(groundAlbedo[c] >= 0.0f && groundAlbedo[c] <= 1.0f))
            throw InvalidArgument("sky ground albedo must be in [0, 1] per channel, got " +
                                  std::to_string(groundAlbedo[c]));
    if (!(scale >= 0.0f) || !std::isfinite(scale))
        throw InvalidArgument("sky scale must be finite and >= 0, got " + std::to_string(scale));
    for (int c = 0; c < 3; ++c)
        if (!(nightRadiance[c] >= 0.0f) || !std::isfinite(nightRadiance[c]))
            throw InvalidArgument("sky night radiance must be finite and >= 0");
}

SkyModel::SkyModel(const SkyParams& params) : mParams(params) {
    params.validate();
    mToSun = unitOrThrow(params.sunDirection, "sky sun direction");
    const double t = params.turbidity;
    // Below the horizon the model sees the sun on the horizon at the same azimuth (straight
    // down: any azimuth) and the result is dimmed (twilight).
    mModelSun = mToSun;
    if (mToSun.y < 0.0f) {
        const glm::vec2 h(mToSun.x, mToSun.z);
        const float len = glm::length(h);
        mModelSun = len > 1e-6f ? glm::vec3(h.x / len, 0.0f, h.y / len) : glm::vec3(1, 0, 0);
        const double elevationDeg = std::asin(double(mToSun.y)) * 180.0 / kPi;
        mTwilight = float(std::pow(10.0, 0.4 * elevationDeg));
    }
    mThetaS = std::acos(std::clamp(mModelSun.y, 0.0f, 1.0f));
    for (int q = 0; q < 3; ++q)
        for (int k = 0; k < 5; ++k) mCoeffs[q][k] = float(kPerez[q][k][0] * t + kPerez[q][k][1]);

    // Zenith values (appendix A.2); chi is the paper's angle, Y_z in kcd/m^2.
    const double chi = (4.0 / 9.0 - t / 120.0) * (kPi - 2.0 * mThetaS);
    const double yz = (4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192;
    mZenith = glm::vec3(float(zenithChromaticity(kZenithX, t, mThetaS)),
                        float(zenithChromaticity(kZenithY, t, mThetaS)), float(yz));
    // Y = Y_z F(theta, gamma) / F(0, theta_s), the same for x and y.
    const float zenith[3] = {mZenith.z, mZenith.x, mZenith.y};
    for (int q = 0; q < 3; ++q) mNorm[q] = float(zenith[q] / perez(mCoeffs[q], 1.0, mThetaS));

    glm::vec3 sunHorizontal(0.0f);
    sunDisc(mToSun, t, mSunIrradiance, sunHorizontal);
    mSunIrradiance *= params.scale;

    // Horizontal irradiance of the sky: E = int L cos theta dw = 1/2 int_0^1 int_0^2pi L du dphi
    // with u = cos^2 theta; a midpoint rule in (u, phi).
    constexpr int nu = 32, nphi = 64;
    glm::dvec3 sky(0.0);
    for (int i = 0; i < nu; ++i) {
        const double cosTheta = std::sqrt((i + 0.5) / nu);
        const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
        for (int j = 0; j < nphi; ++j) {
            const double phi = 2.0 * kPi * (j + 0.5) / nphi;
            sky += glm::dvec3(skyAbove(glm::vec3(float(sinTheta * std::cos(phi)), float(cosTheta),
                                                 float(sinTheta * std::sin(phi)))));
        }
    }
    sky *= 0.5 * (2.0 * kPi) / (double(nu) * nphi);
    mSkyHorizontal = glm::vec3(sky) * params.scale;
    // The ground is Lambertian under the sky and the sun.
    mGround = params.groundAlbedo * float(1.0 / kPi) * (glm::vec3(sky) + glm::vec3(sunHorizontal));
}

glm::vec3 SkyModel::xyY(const glm::vec3& dir) const {
    const glm::vec3 d = unitOrThrow(dir, "sky direction");
    const double cosTheta = std::max(d.y, 0.0f);
    const double gamma = std::acos(std::clamp(double(glm::dot(d, mModelSun)), -1.0, 1.0));
    return glm::vec3(float(mNorm[1] * perez(mCoeffs[1], cosTheta, gamma)),
                     float(mNorm[2] * perez(mCoeffs[2], cosTheta, gamma)),
                     float(mNorm[0] * perez(mCoeffs[0], cosTheta, gamma)));
}

// The sky (twilight and night included) above the horizon, before `scale`; `dir` is unit.
glm::vec3 SkyModel::skyAbove(const glm::vec3& dir) const {
    const double cosTheta = std::max(dir.y, 0.0f);
    const double gamma = std::acos(std::clamp(double(glm::dot(dir, mModelSun)), -1.0, 1.0));
    const double yy = mNorm[0] * perez(mCoeffs[0], cosTheta, gamma);
    const double x = mNorm[1] * perez(mCoeffs[1], cosTheta, gamma);
    const double y = mNorm[2] * perez(mCoeffs[2], cosTheta, gamma);
    const glm::dvec3 xyz(x / y * yy, yy, (1.0 - x - y) / y * yy);
    return glm::max(sky::xyzToRgb(xyz), glm::vec3(0.0f)) * mTwilight + mParams.nightRadiance;
}

glm::vec3 SkyModel::radiance(const glm::vec3& dir) const {
    const glm::vec3 d = unitOrThrow(dir, "sky direction");
    return (d.y >= 0.0f ? skyAbove(d) : mGround) * mParams.scale;
}

CubeMap skyCube(const SkyParams& params, int size) {
    if (size < 1 || size > 2048)
        throw InvalidArgument("sky cube size must be in [1, 2048], got " + std::to_string(size));
    const SkyModel model(params);
    CubeMap cube(size);
    iblParallelFor(6 * size, [&](int begin, int end) {
        for (int row = begin; row < end; ++row) {
            const int face = row / size, j = row % size;
            for (int i = 0; i < size; ++i) {
                const glm::vec3 c = model.radiance(cubeTexelDirection(face, i, j, size));
                float* t = cube.texel(face, i, j);
                t[0] = c.x;
                t[1] = c.y;
                t[2] = c.z;
            }
        }
    });
    if (!params.sun || params.scale == 0.0f) return cube;
    // The disc splatted as points, each adding its share of the irradiance over the solid
    // angle of the texel it falls in: the cube integrates to the sun's irradiance at any size,
    // and shows a disc of the right size once texels are smaller than it (~16 points a texel).
    const double texelsInDisc = sky::sunSolidAngle() * double(size) * size / 4.0 * 5.2;
    const int count = int(std::clamp(16.0 * texelsInDisc, 64.0, 65536.0));
    const sky::SunRadiance sun(params.turbidity);
    const double dw = sky::sunSolidAngle() / count;
    for (const glm::vec3& d : sky::sunDiscPoints(model.toSun(), count)) {
        if (!(d.y > 0.0f)) continue;
        const CubeCoord cc = cubeCoord(d);
        const int i = std::clamp(int((cc.u + 1.0f) * 0.5f * float(size)), 0, size - 1);
        const int j = std::clamp(int((cc.v + 1.0f) * 0.5f * float(size)), 0, size - 1);
        const glm::vec3 add =
            sun(d) * float(dw / cubeTexelSolidAngle(i, j, size) * double(params.scale));
        float* t = cube.texel(cc.face, i, j);
        for (int c = 0; c < 3; ++c) t[c] += add[c];
    }
    return cube;
}

glm::vec3 sunIrradiance(const SkyParams& params) {
    params.validate();
    glm::vec3 normal, horizontal;
    sunDisc(glm::normalize(params.sunDirection), params.turbidity, normal, horizontal);
    return normal * params.scale;
}

} // namespace weft
