#version 450
// The bounce captures (render/BounceProbes.h) projected onto SH9 irradiance at the caster's
// points (bouncePoint, bounce_points.glsl). Drawn once per probe over its BOUNCE_POINTS rows;
// fragment (c, row) sums coefficient k = c % 9 of set s = c / 9 at point row % BOUNCE_POINTS:
//   s = 0: the receivers' radiance (rgb; the capture is cleared to 0 where no receiver is),
//   s = 1: the environment's radiance where a receiver covers it (coverage = the capture's alpha),
//   s = 2: the coverage itself, as a radiance of 1,
// stored as A_l L_lm / pi (Ramamoorthi & Hanrahan 2001; A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4),
// the convention of frame.environmentSh, so sum_k basis_k(n) coeff_k is E(n) / pi.
// The capture was taken from the centre c. Its depth places texel j's receiver at x_j, and
// neighbouring texels give the receiver's normal N_j; seen from a point q instead of c the
// texel's patch (area A_j = Omega_j |x_j - c|^2 / cos_c) covers the solid angle
// A_j cos_q / |x_j - q|^2 in direction (x_j - q) / |x_j - q|, and nothing where it faces away
// from q. At the centre this is the capture's own texel solid angle
// (2/S)^2 / (1 + u^2 + v^2)^(3/2). What the caster itself hides from q is left to the clamped
// cosine of the fragment's normal: cutting the sets off at q's tangent plane made SH9 ring
// (the floating sphere 2% too dark and bluish against Mitsuba, objects FLIP 0.040 -> 0.064).
#include "gpu_types.h"
#include "cube_faces.glsl"
#include "bounce_points.glsl"

layout(set = 0, binding = 0) uniform sampler2DArray faces;      // layer 6 probe + face
layout(set = 0, binding = 1) uniform samplerCube environmentMap; // the GGX chain, level 0
layout(set = 0, binding = 2) uniform sampler2DArray faceDepth;  // the captures' depths
layout(push_constant) uniform Push {
    vec4 params; // x: environment intensity (0: none), y: texels per face, z: probe
    vec4 centre; // xyz: where the capture was taken
    vec4 extent; // xyz: the caster's half extents
} push;
layout(location = 0) out vec4 outSh;

// probeFaceViewProj's planes (ReflectionProbe.cpp)
const float kNear = 0.02, kFar = 1000.0;

float basis(int k, vec3 n) {
    switch (k) {
    case 0: return 0.282095;
    case 1: return 0.488603 * n.y;
    case 2: return 0.488603 * n.z;
    case 3: return 0.488603 * n.x;
    case 4: return 1.092548 * n.x * n.y;
    case 5: return 1.092548 * n.y * n.z;
    case 6: return 0.315392 * (3.0 * n.z * n.z - 1.0);
    case 7: return 1.092548 * n.x * n.z;
    default: return 0.546274 * (n.x * n.x - n.y * n.y);
    }
}

// The receiver at texel (i, j) of layer `layer`, relative to the centre; w = 0: none there.
vec4 receiver(int i, int j, int layer, vec3 ma, vec3 su, vec3 sv, float texel) {
    float z = texelFetch(faceDepth, ivec3(i, j, layer), 0).r;
    if (z >= 1.0) return vec4(0.0);
    float along = kNear * kFar / (kFar - z * (kFar - kNear)); // depth along ma
    float u = (float(i) + 0.5) * texel - 1.0, v = (float(j) + 0.5) * texel - 1.0;
    return vec4((ma + u * su + v * sv) * along, 1.0);
}

void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    int set = c.x / 9, k = c.x % 9, probe = int(push.params.z);
    int point = c.y - probe * BOUNCE_POINTS;
    int size = int(push.params.y);
    float intensity = push.params.x;
    float texel = 2.0 / float(size);
    vec3 dir = bouncePointDirection(point);
    vec3 q = push.extent.xyz * dir; // relative to the centre
    vec3 sum = vec3(0.0);
    for (int face = 0; face < 6; ++face) {
        vec3 ma = kCubeAxes[3 * face], su = kCubeAxes[3 * face + 1], sv = kCubeAxes[3 * face + 2];
        int layer = 6 * probe + face;
        for (int j = 0; j < size; ++j) {
            float v = (float(j) + 0.5) * texel - 1.0;
            for (int i = 0; i < size; ++i) {
                float u = (float(i) + 0.5) * texel - 1.0;
                float r2 = 1.0 + u * u + v * v;
                vec3 d = (ma + u * su + v * sv) / sqrt(r2);
                float omega = texel * texel / (r2 * sqrt(r2));
                vec4 t = texelFetch(faces, ivec3(i, j, layer), 0);
                if (point != 0) {
                    vec4 x = receiver(i, j, layer, ma, su, sv, texel);
                    if (x.w == 0.0) continue; // no receiver: nothing to see from q either
                    // the receiver's normal from its neighbours in the face, towards c
                    int i1 = i + 1 < size ? i + 1 : i - 1, j1 = j + 1 < size ? j + 1 : j - 1;
                    vec4 xu = receiver(i1, j, layer, ma, su, sv, texel);
                    vec4 xv = receiver(i, j1, layer, ma, su, sv, texel);
                    vec3 N = -d;
                    if (xu.w > 0.0 && xv.w > 0.0) {
                        vec3 cr = cross(xu.xyz - x.xyz, xv.xyz - x.xyz);
                        if (dot(cr, cr) > 0.0) N = normalize(cr) * -sign(dot(cr, d));
                    }
                    vec3 e = x.xyz - q;
                    float dist2 = dot(e, e);
                    vec3 w = e * inversesqrt(max(dist2, 1e-12));
                    float cosQ = -dot(N, w), cosC = max(-dot(N, d), 0.05);
                    if (cosQ <= 0.0) continue;
                    omega *= dot(x.xyz, x.xyz) / max(dist2, 1e-12) * cosQ / cosC;
                    omega = min(omega, 0.5); // a patch right at q: bounded
                    d = w;
                }
                float wgt = omega * basis(k, d);
                vec3 radiance = set == 0 ? t.rgb
                              : set == 1 ? (intensity > 0.0 ? t.a * intensity *
                                                textureLod(environmentMap, d, 0.0).rgb : vec3(0.0))
                                         : vec3(t.a);
                sum += wgt * radiance;
            }
        }
    }
    float band = k == 0 ? 1.0 : k < 4 ? 2.0 / 3.0 : 0.25;
    outSh = vec4(sum * band, 0.0);
}
