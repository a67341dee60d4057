#version 450
// The bounce captures (render/BounceProbes.h) projected onto SH9 irradiance. Fragment (c, p)
// sums coefficient k = c % 9 of set s = c / 9 for probe p over its six faces:
//   s = 0: the receivers' radiance (rgb; the capture is cleared to 0 where no receiver is),
//   s = 1: the environment's radiance where a receiver covers it (coverage = the capture's alpha),
//   s = 2: the coverage itself, as a radiance of 1,
// each weighted by its texel's solid angle (2/S)^2 / (1 + u^2 + v^2)^(3/2) and stored as
// A_l L_lm / pi (Ramamoorthi & Hanrahan 2001; A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4), the
// convention of frame.environmentSh, so sum_k basis_k(n) coeff_k is E(n) / pi.
layout(set = 0, binding = 0) uniform sampler2DArray faces;      // layer 6 probe + face
layout(set = 0, binding = 1) uniform samplerCube environmentMap; // the GGX chain, level 0
layout(push_constant) uniform Push { vec4 params; } push; // environment intensity, face size, probes
layout(location = 0) out vec4 outSh;

#include "cube_faces.glsl"

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

void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    int set = c.x / 9, k = c.x % 9, probe = c.y;
    int size = int(push.params.y);
    float intensity = push.params.x;
    float texel = 2.0 / float(size);
    vec3 sum = vec3(0.0);
    for (int face = 0; face < 6; ++face) {
        vec3 ma = kCubeAxes[3 * face], su = kCubeAxes[3 * face + 1], sv = kCubeAxes[3 * face + 2];
        for (int j = 0; j < size; ++j) {
            float v = (float(j) + 0.5) * texel - 1.0;
            for (int i = 0; i < size; ++i) {
                float u = (float(i) + 0.5) * texel - 1.0;
                float r2 = 1.0 + u * u + v * v;
                vec3 d = (ma + u * su + v * sv) / sqrt(r2);
                float w = texel * texel / (r2 * sqrt(r2)) * basis(k, d);
                vec4 t = texelFetch(faces, ivec3(i, j, 6 * probe + face), 0);
                vec3 radiance = set == 0 ? t.rgb
                              : set == 1 ? (intensity > 0.0 ? t.a * intensity *
                                                textureLod(environmentMap, d, 0.0).rgb : vec3(0.0))
                                         : vec3(t.a);
                sum += w * radiance;
            }
        }
    }
    float band = k == 0 ? 1.0 : k < 4 ? 2.0 / 3.0 : 0.25;
    outSh = vec4(sum * band, 0.0);
}
