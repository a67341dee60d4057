// One bounce of diffuse light (render/BounceProbes.h, bounce_sh.frag): SH9 sets per caster of
// the receivers' radiance (0), the environment they hide (1) and the solid angle they cover
// (2), each evaluated as E(n) / pi. Included by shading.glsl after frame.glsl.
layout(set = 0, binding = 14) uniform sampler2D bounceSh; // row: probe, column: 9 set + k
layout(set = 0, binding = 15) uniform sampler2DArray bounceFaces; // layer 6 probe + face
// the casters' radiance as proxy spheres (bounce_radiance.frag): row probe, column k
layout(set = 0, binding = 16) uniform sampler2D bounceRadiance;

#include "cube_faces.glsl"

// The instance's bounce capture, or -1 (none, or a frame without bounce light).
int bounceProbe(Instance ins) {
    return featureOn(FEATURE_BOUNCE) && frame.sky.z > 0.5 ? int(ins.flags.y) - 1 : -1;
}

// SH9 basis at unit n, each band scaled by w (x: l = 0, y: l = 1, z: l = 2).
void shBasis9(vec3 n, vec3 w, out float b[9]) {
    b = float[9](w.x * 0.282095, w.y * 0.488603 * n.y, w.y * 0.488603 * n.z,
                 w.y * 0.488603 * n.x, w.z * 1.092548 * n.x * n.y, w.z * 1.092548 * n.y * n.z,
                 w.z * 0.315392 * (3.0 * n.z * n.z - 1.0), w.z * 1.092548 * n.x * n.z,
                 w.z * 0.546274 * (n.x * n.x - n.y * n.y));
}

// Set `set` of capture `probe` at n with its bands scaled by w (1: the set's own E(n) / pi).
vec3 bounceSet(int probe, int set, vec3 n, vec3 w) {
    float b[9];
    shBasis9(n, w, b);
    vec3 e = vec3(0.0);
    for (int k = 0; k < 9; ++k) e += b[k] * texelFetch(bounceSh, ivec2(9 * set + k, probe), 0).rgb;
    return e;
}

vec3 bounceIrradiance(int probe, int set, vec3 n) {
    return max(bounceSet(probe, set, n, vec3(1.0)), vec3(0.0));
}

// Capture `probe`'s texel in direction d: rgb the receivers' radiance, a their coverage.
vec4 bounceFace(int probe, vec3 d) {
    vec2 uv;
    int face = cubeFace(d, uv);
    return textureLod(bounceFaces, vec3(uv, float(6 * probe + face)), 0.0);
}
