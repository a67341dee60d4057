#version 450
// Where each texel of a bounce capture (render/BounceProbes.h) lies as seen from each of the
// caster's points (bounce_points.glsl), for bounce_sh.frag: drawn once per probe over its
// BOUNCE_POINTS rows, fragment (j, row) holds texel j = (face S + v) S + u of the capture as
// seen from point row % BOUNCE_POINTS: (direction, solid angle), w = 0 where nothing is.
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

layout(set = 0, binding = 2) uniform sampler2DArray faceDepth; // layer 6 probe + face
layout(push_constant) uniform Push {
    vec4 params; // y: texels per face, z: probe
    vec4 centre; // xyz: where the capture was taken
    vec4 extent; // xyz: the caster's half extents
} push;
layout(location = 0) out vec4 outGeometry;

// probeFaceViewProj's planes (ReflectionProbe.cpp)
const float kNear = 0.02, kFar = 1000.0;

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
    int size = int(push.params.y), probe = int(push.params.z);
    int point = c.y - probe * BOUNCE_POINTS;
    int face = c.x / (size * size), i = c.x % size, j = (c.x / size) % size;
    vec3 ma = kCubeAxes[3 * face], su = kCubeAxes[3 * face + 1], sv = kCubeAxes[3 * face + 2];
    int layer = 6 * probe + face;
    float texel = 2.0 / float(size);
    float u = (float(i) + 0.5) * texel - 1.0, v = (float(j) + 0.5) * texel - 1.0;
    float r2 = 1.0 + u * u + v * v;
    vec3 d = (ma + u * su + v * sv) / sqrt(r2);
    float omega = texel * texel / (r2 * sqrt(r2));
    vec4 x = receiver(i, j, layer, ma, su, sv, texel);
    if (x.w == 0.0) { // no receiver: nothing to see from any point
        outGeometry = vec4(d, 0.0);
        return;
    }
    if (point == 0) {
        outGeometry = vec4(d, omega);
        return;
    }
    // the receiver's normal from its neighbours in the face, towards c
    int i1 = i + 1 < size ? i + 1 : i - 1, j1 = j + 1 < size ? j + 1 : j - 1;
    vec4 xu = receiver(i1, j, layer, ma, su, sv, texel);
    vec4 xv = receiver(i, j1, layer, ma, su, sv, texel);
    vec3 N = -d;
    if (xu.w > 0.0 && xv.w > 0.0) {
        vec3 cr = cross(xu.xyz - x.xyz, xv.xyz - x.xyz);
        if (dot(cr, cr) > 0.0) N = normalize(cr) * -sign(dot(cr, d));
    }
    vec3 e = x.xyz - push.extent.xyz * bouncePointDirection(point); // from q, relative to c
    float dist2 = max(dot(e, e), 1e-12);
    vec3 w = e * inversesqrt(dist2);
    float cosQ = -dot(N, w), cosC = max(-dot(N, d), 0.05);
    // a patch right at q: bounded
    omega = cosQ > 0.0 ? min(omega * dot(x.xyz, x.xyz) / dist2 * cosQ / cosC, 0.5) : 0.0;
    outGeometry = vec4(w, omega);
}
