#version 450
// The dome's visibility over the casters' floor, per pixel, for the blur (dome_blur*.frag).
// The forward pass leaves the dome's linear occlusion o (dome.a), the floor f the casters'
// proxies leave and the albedo rho of the multi-bounce fit (aux); here the visibility becomes
// clamp(1 - o, 0, f), through the fit where the dome stands for the ambient's sky
// (multi_bounce.glsl), over the floor's own: min(V(v) / V(f), 1).
// With interleaved dome lights each pixel's o covers a quarter of the lights (by its place in
// its 2 x 2 block, times 4), so o is first averaged over the 3 x 3 neighbourhood, tent-weighted
// and with the blur's depth similarity, per place, and the four places' means averaged: every
// quarter of the lights counts equally, and the clamps and the fit see the whole dome's
// estimate, not a quarter's (which would bias them and leave the block's pattern). Against one
// pixel of each place (the 2 x 2 block), the tent halves the variance: 16 dome lights at 96^2
// showed 3 / 2 / 2 / 3 shadow minima on circles (every light per pixel: 2 / 2 / 2 / 3, the
// 2 x 2 block: 5 / 4 / 4 / 3; tests/python/render/test_dome_truth.py).
#include "multi_bounce.glsl"
layout(set = 0, binding = 0) uniform sampler2D domeTex;  // a: the dome's linear occlusion
layout(set = 0, binding = 1) uniform sampler2D depthTex; // the forward pass's depth (perspective)
layout(set = 0, binding = 2) uniform sampler2D auxTex;   // floor before the fit, fit albedo
layout(push_constant) uniform Push {
    vec4 params; // radius, near, far, tolerance
    vec4 flags;  // x: interleaved dome lights, y: the multi-bounce fit
} push;
layout(location = 0) out vec4 outVisDepth; // (visibility over the floor, view depth or -1)

float viewDepth(float d) {
    float n = push.params.y, f = push.params.z;
    return n * f / (f - d * (f - n));
}

void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    float d = texelFetch(depthTex, c, 0).r; // cleared to 1: no surface
    float zc = d < 1.0 ? viewDepth(d) : -1.0;
    float o = texelFetch(domeTex, c, 0).a;
    if (push.flags.x > 0.5 && zc > 0.0) {
        // the centre's place is always there: only its own pixel has it
        ivec2 last = textureSize(domeTex, 0) - 1;
        vec4 sum = vec4(0.0), weights = vec4(0.0); // per place in the 2 x 2 block
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                ivec2 q = c + ivec2(x, y);
                if (any(lessThan(q, ivec2(0))) || any(greaterThan(q, last))) continue;
                float dq = texelFetch(depthTex, q, 0).r;
                if (dq >= 1.0) continue;
                float dz = (viewDepth(dq) - zc) / (push.params.w * zc);
                float w = exp(-dz * dz) * (x == 0 ? 2.0 : 1.0) * (y == 0 ? 2.0 : 1.0);
                int k = (q.x & 1) + 2 * (q.y & 1);
                sum[k] += w * texelFetch(domeTex, q, 0).a;
                weights[k] += w;
            }
        float places = 0.0;
        o = 0.0;
        for (int k = 0; k < 4; ++k)
            if (weights[k] > 0.0) {
                o += sum[k] / weights[k];
                places += 1.0;
            }
        o /= places;
    }
    vec2 aux = texelFetch(auxTex, c, 0).rg;
    float f = aux.x, v = clamp(1.0 - o, 0.0, f);
    if (push.flags.y > 0.5) {
        v = multiBounceVisibility(v, aux.y);
        f = multiBounceVisibility(f, aux.y);
    }
    outVisDepth = vec4(f > 0.0 ? min(v / f, 1.0) : 0.0, zc, 0.0, 0.0);
}
