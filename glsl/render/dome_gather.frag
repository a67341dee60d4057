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
// 2 x 2 block: 5 / 4 / 4 / 3; tests/python/render/test_dome_truth.py). Four textureGathers
// read the neighbourhood: 25 ms at 1280 x 720 on lavapipe against 41 ms for 18 texelFetches.
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
vec4 viewDepth4(vec4 d) {
    float n = push.params.y, f = push.params.z;
    return n * f / (f - d * (f - n));
}

void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    float d = texelFetch(depthTex, c, 0).r; // cleared to 1: no surface
    float zc = d < 1.0 ? viewDepth(d) : -1.0;
    float o = texelFetch(domeTex, c, 0).a;
    if (push.flags.x > 0.5 && zc > 0.0) {
        // Four gathers at the corners of c's texel cover the 3 x 3 neighbourhood, the centre
        // four times, its row and column neighbours twice, the diagonals once: the tent. Each
        // gather holds one texel of each place relative to c (own, row, column, diagonal).
        vec2 size = vec2(textureSize(domeTex, 0));
        vec4 sums = vec4(0.0), weights = vec4(0.0);
        for (int g = 0; g < 4; ++g) {
            ivec2 corner = c + ivec2(g & 1, g >> 1);
            vec2 uv = vec2(corner) / size;
            vec4 d4 = textureGather(depthTex, uv, 0); // texels (-1, 0) (0, 0) (0, -1) (-1, -1)
            vec4 o4 = textureGather(domeTex, uv, 3);  // from the corner
            vec4 tx = vec4(corner.x - 1, corner.x, corner.x, corner.x - 1);
            vec4 ty = vec4(corner.y, corner.y, corner.y - 1, corner.y - 1);
            vec4 inside = step(0.0, tx) * step(tx, vec4(size.x - 1.0)) * step(0.0, ty) *
                          step(ty, vec4(size.y - 1.0)) * vec4(lessThan(d4, vec4(1.0)));
            vec4 dz = (viewDepth4(d4) - zc) / (push.params.w * zc);
            vec4 w = exp(-dz * dz) * inside;
            // in place order: own, row neighbour, column neighbour, diagonal
            if (g == 0) {
                w = w.yxzw;
                o4 = o4.yxzw;
            } else if (g == 1) {
                w = w.xywz;
                o4 = o4.xywz;
            } else if (g == 2) {
                w = w.zwyx;
                o4 = o4.zwyx;
            } else {
                w = w.wzxy;
                o4 = o4.wzxy;
            }
            sums += w * o4;
            weights += w;
        }
        // every place with a texel on c's surface counts once (the own place always has c)
        vec4 present = vec4(greaterThan(weights, vec4(0.0)));
        o = dot(present, sums / max(weights, vec4(1e-30))) / dot(present, vec4(1.0));
    }
    vec2 aux = texelFetch(auxTex, c, 0).rg;
    float f = aux.x, v = clamp(1.0 - o, 0.0, f);
    if (push.flags.y > 0.5) {
        v = multiBounceVisibility(v, aux.y);
        f = multiBounceVisibility(f, aux.y);
    }
    outVisDepth = vec4(f > 0.0 ? min(v / f, 1.0) : 0.0, zc, 0.0, 0.0);
}
