#version 450
// The bounce captures (render/BounceProbes.h) projected onto SH9 irradiance at the caster's
// points (bounce_points.glsl). Drawn once per probe over its BOUNCE_POINTS rows; fragment
// (c, row) sums coefficient k = c % 9 of set s = c / 9 at point row % BOUNCE_POINTS:
//   s = 0: the receivers' radiance (rgb; the capture is cleared to 0 where no receiver is),
//   s = 1: the environment's radiance where a receiver covers it (coverage = the capture's alpha),
//   s = 2: the coverage itself, as a radiance of 1,
// over the capture's texels as the point sees them (direction, solid angle: bounce_geometry.frag,
// the same row), stored as A_l L_lm / pi (Ramamoorthi & Hanrahan 2001; A_0 = pi,
// A_1 = 2 pi / 3, A_2 = pi / 4), the convention of frame.environmentSh, so
// sum_k basis_k(n) coeff_k is E(n) / pi.
layout(set = 0, binding = 0) uniform sampler2DArray faces;      // layer 6 probe + face
layout(set = 0, binding = 1) uniform samplerCube environmentMap; // the GGX chain, level 0
layout(set = 0, binding = 3) uniform sampler2D geometry;        // bounce_geometry.frag's
layout(push_constant) uniform Push {
    vec4 params; // x: environment intensity (0: none), y: texels per face, z: probe
    vec4 centre;
    vec4 extent;
} push;
layout(location = 0) out vec4 outSh;

// The nine SH9 basis functions at n, without their constants (see main's `scale`).
void monomials(vec3 n, out vec4 a, out vec4 b, out float c) {
    a = vec4(1.0, n.y, n.z, n.x);
    b = vec4(n.x * n.y, n.y * n.z, 3.0 * n.z * n.z - 1.0, n.x * n.z);
    c = n.x * n.x - n.y * n.y;
}

void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    int set = c.x / 9, k = c.x % 9, probe = int(push.params.z);
    int size = int(push.params.y);
    float intensity = push.params.x;
    // basis k as a dot product with constant weights: the columns of a SIMD group hold
    // different k, and a switch on k ran every case under a mask
    const float kBasis[9] = float[9](0.282095, 0.488603, 0.488603, 0.488603, 1.092548,
                                     1.092548, 0.315392, 1.092548, 0.546274);
    vec4 wa = vec4(0.0), wb = vec4(0.0);
    float wc = 0.0;
    if (k < 4) wa[k] = kBasis[k];
    else if (k < 8) wb[k - 4] = kBasis[k];
    else wc = kBasis[8];
    vec3 sum = vec3(0.0);
    for (int t = 0; t < 6 * size * size; ++t) {
        vec4 g = texelFetch(geometry, ivec2(t, c.y), 0); // direction, solid angle
        if (g.w == 0.0) continue;
        int face = t / (size * size);
        vec4 texel = texelFetch(faces, ivec3(t % size, (t / size) % size, 6 * probe + face), 0);
        vec3 radiance = set == 0 ? texel.rgb
                      : set == 1 ? (intensity > 0.0 ? texel.a * intensity *
                                        textureLod(environmentMap, g.xyz, 0.0).rgb : vec3(0.0))
                                 : vec3(texel.a);
        vec4 ma, mb;
        float mc;
        monomials(g.xyz, ma, mb, mc);
        sum += g.w * (dot(wa, ma) + dot(wb, mb) + wc * mc) * radiance;
    }
    float band = k == 0 ? 1.0 : k < 4 ? 2.0 / 3.0 : 0.25;
    outSh = vec4(sum * band, 0.0);
}
