// Hair shading models (SPEC §5.2): Kajiya-Kay, Marschner et al. 2003, Sadeghi et al. 2010.
// Directions t (tangent, root to tip), l (to the light) and v (to the eye) are unit vectors.
// Angles: sin(theta_i) = l.t, sin(theta_o) = v.t, theta_h = (theta_i + theta_o) / 2,
// theta_d = (theta_o - theta_i) / 2, phi in [0, pi] = angle between l and v projected onto the
// plane normal to t (pi/2 when either projection vanishes). hairShade() returns f, the RGB
// radiance per unit light radiance: diffuse * sin(t, l) + the model's specular scattering.
// python/weft/reference/hair.py is the independent NumPy version of this file.
#ifndef WEFT_HAIR_SHADING_GLSL
#define WEFT_HAIR_SHADING_GLSL

#include "hair_gpu_types.h" // HairShading, HAIR_MODEL_*

const float HAIR_PI = 3.14159265358979;
const float HAIR_MIN_COS2 = 1e-3; // floor of cos^2(theta_d) in the 1 / cos^2(theta_d) factor

uint hairHash(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// Sadeghi's per-strand glint half-angle G_angle in [min, max].
float hairGlintAngle(HairShading s, uint strand) {
    float u = float(hairHash(strand) >> 8) * (1.0 / 16777216.0);
    return mix(s.glint.z, s.glint.w, u);
}

struct HairAngles {
    float cosThetaI; // = sin(t, l)
    float thetaI;
    float thetaO;
    float thetaH;
    float thetaD;
    float phi;
};

HairAngles hairAngles(vec3 t, vec3 l, vec3 v) {
    HairAngles a;
    float sinI = clamp(dot(l, t), -1.0, 1.0);
    float sinO = clamp(dot(v, t), -1.0, 1.0);
    vec3 lp = l - sinI * t;
    vec3 vp = v - sinO * t;
    float lpLen = length(lp);
    float vpLen = length(vp);
    a.cosThetaI = lpLen;
    a.thetaI = atan(sinI, lpLen);
    a.thetaO = atan(sinO, vpLen);
    a.thetaH = 0.5 * (a.thetaI + a.thetaO);
    a.thetaD = 0.5 * (a.thetaO - a.thetaI);
    a.phi = (lpLen < 1e-6 || vpLen < 1e-6) ? 0.5 * HAIR_PI
                                           : atan(length(cross(lp, vp)), dot(lp, vp));
    return a;
}

float hairInvCos2(float thetaD) {
    float c = cos(thetaD);
    return 1.0 / max(c * c, HAIR_MIN_COS2);
}

vec3 hairKajiyaKay(HairShading s, HairAngles a) {
    float c = max(cos(a.thetaI + a.thetaO), 0.0);
    return s.specular.rgb * pow(c, s.specular.w);
}

// Unit-height Gaussian g'(width; x) (Sadeghi) and unit-area Gaussian g(width; x) (Marschner).
float hairGaussUnitHeight(float width, float x) { return exp(-x * x / (2.0 * width * width)); }
float hairGaussUnitArea(float width, float x) {
    return hairGaussUnitHeight(width, x) / (width * sqrt(2.0 * HAIR_PI));
}

vec3 hairSadeghi(HairShading s, HairAngles a, uint strand) {
    float mR = hairGaussUnitHeight(s.width.x, a.thetaH - s.shift.x);
    float mTT = hairGaussUnitHeight(s.width.y, a.thetaH - s.shift.y);
    float mTRT = hairGaussUnitHeight(s.width.z, a.thetaH - s.shift.z);
    float nR = cos(0.5 * a.phi);
    float nTT = hairGaussUnitHeight(s.width.w, HAIR_PI - a.phi);
    float nTRT = nR + s.glint.x * hairGaussUnitHeight(s.glint.y, hairGlintAngle(s, strand) - a.phi);
    vec3 f = s.colorR.rgb * s.colorR.w * mR * nR + s.colorTT.rgb * s.colorTT.w * mTT * nTT +
             s.colorTRT.rgb * s.colorTRT.w * mTRT * nTRT;
    return f * hairInvCos2(a.thetaD);
}

// Unpolarised Fresnel reflectance of a dielectric of relative index eta at incidence cosI.
float hairFresnel(float eta, float cosI) {
    float sinT2 = (1.0 - cosI * cosI) / (eta * eta);
    if (sinT2 >= 1.0) return 1.0;
    float cosT = sqrt(1.0 - sinT2);
    float rs = (cosI - eta * cosT) / (cosI + eta * cosT);
    float rp = (eta * cosI - cosT) / (eta * cosI + cosT);
    return 0.5 * (rs * rs + rp * rp);
}

// Inverse trigonometric/hyperbolic functions written with atan/log/sqrt: some drivers (Mesa's
// lavapipe) evaluate asin, acos, asinh and acosh with approximations accurate to only ~1e-3.
float hairAcos(float x) { return atan(sqrt(max(1.0 - x * x, 0.0)), x); }
float hairAsinh(float x) { return sign(x) * log(abs(x) + sqrt(x * x + 1.0)); }
float hairAcosh(float x) { return log(x + sqrt(max(x * x - 1.0, 0.0))); }

// Real roots of x^3 + p x + q = 0 (trigonometric / hyperbolic forms); returns their count.
int hairCubicRoots(float p, float q, out float roots[3]) {
    if (abs(p) < 1e-6) {
        roots[0] = -sign(q) * pow(abs(q), 1.0 / 3.0);
        return 1;
    }
    if (p > 0.0) {
        float m = sqrt(p / 3.0);
        roots[0] = -2.0 * m * sinh(hairAsinh(1.5 * q / (p * m)) / 3.0);
        return 1;
    }
    float m = sqrt(-p / 3.0);
    if (4.0 * p * p * p + 27.0 * q * q < 0.0) {
        float base = hairAcos(clamp(1.5 * q / (p * m), -1.0, 1.0)) / 3.0;
        for (int k = 0; k < 3; ++k) roots[k] = 2.0 * m * cos(base - 2.0 * HAIR_PI * float(k) / 3.0);
        return 3;
    }
    roots[0] = -2.0 * sign(q) * m * cosh(hairAcosh(max(-1.5 * abs(q) / (p * m), 1.0)) / 3.0);
    return 1;
}

// Marschner's azimuthal N_p for p = 1 (TT) or 2 (TRT): the sum over the offsets h whose path
// leaves at phi of A(p, h) x / (x^2 + eps^2), x = |2 dphi/dh| (1 / x away from caustics; zero
// instead of infinite where two paths merge, so N stays continuous in phi), with
// phi(p, gamma) = (6pc/pi - 2) gamma - 8pc/pi^3 gamma^3 + p pi, c = asin(1 / eta').
vec3 hairMarschnerN(HairShading s, int p, float phi, float etaP, float sigmaScale) {
    float c = atan(1.0, sqrt(etaP * etaP - 1.0)); // asin(1 / eta')
    float pc = float(p) * c;
    float a = -8.0 * pc / (HAIR_PI * HAIR_PI * HAIR_PI);
    float b = 6.0 * pc / HAIR_PI - 2.0;
    float d = (p == 1) ? HAIR_PI - phi : -phi;
    float roots[3];
    int count = hairCubicRoots(b / a, d / a, roots);
    vec3 n = vec3(0.0);
    for (int i = 0; i < count; ++i) {
        float gamma = roots[i];
        if (abs(gamma) > 0.5 * HAIR_PI) continue;
        float h = sin(gamma);
        float fresnel = hairFresnel(etaP, cos(gamma));
        vec3 transmit = exp(-2.0 * sigmaScale * s.absorption.rgb * (2.0 - 2.0 * h * h / (etaP * etaP)));
        vec3 att = (1.0 - fresnel) * (1.0 - fresnel) * transmit;
        if (p == 2) att *= fresnel * transmit;
        float dphidh = (3.0 * a * gamma * gamma + b) / max(cos(gamma), 1e-6);
        float x = abs(2.0 * dphidh);
        n += att * (x / (x * x + s.absorption.w * s.absorption.w));
    }
    return n;
}

vec3 hairMarschner(HairShading s, HairAngles a) {
    float eta = s.shift.w;
    float sinD = sin(a.thetaD);
    float cosD = sqrt(max(1.0 - sinD * sinD, HAIR_MIN_COS2));
    float etaP = sqrt(eta * eta - sinD * sinD) / cosD; // Bravais index in the normal plane
    float sinT = sinD / eta;                            // longitudinal refraction
    float sigmaScale = 1.0 / sqrt(1.0 - sinT * sinT);
    float mR = hairGaussUnitArea(s.width.x, a.thetaH - s.shift.x);
    float mTT = hairGaussUnitArea(s.width.y, a.thetaH - s.shift.y);
    float mTRT = hairGaussUnitArea(s.width.z, a.thetaH - s.shift.z);
    float cosHalfPhi = cos(0.5 * a.phi);
    float nR = hairFresnel(etaP, cosHalfPhi) * cosHalfPhi * 0.25;
    vec3 f = vec3(mR * nR) + mTT * hairMarschnerN(s, 1, a.phi, etaP, sigmaScale) +
             mTRT * hairMarschnerN(s, 2, a.phi, etaP, sigmaScale);
    return f * hairInvCos2(a.thetaD);
}

// The model a pipeline is specialized to (HairPipelines: the strands' own), or -1: the
// model of `s`, chosen at run time. lavapipe evaluates every side of a branch under a mask, so
// the generic pipeline pays for all three models: the demo's Kajiya-Kay fur took twice as long.
layout(constant_id = 2) const int kHairModel = -1;

vec3 hairShade(HairShading s, vec3 t, vec3 l, vec3 v, uint strand) {
    HairAngles a = hairAngles(t, l, v);
    vec3 f = s.diffuse.rgb * a.cosThetaI;
    int model = kHairModel >= 0 ? kHairModel : s.model.x;
    if (model == HAIR_MODEL_KAJIYA_KAY) f += hairKajiyaKay(s, a);
    else if (model == HAIR_MODEL_MARSCHNER) f += hairMarschner(s, a);
    else f += hairSadeghi(s, a, strand);
    return f;
}

#endif
