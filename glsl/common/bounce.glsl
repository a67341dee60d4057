// One bounce of diffuse light (render/BounceProbes.h, bounce_sh.frag): SH9 sets per caster of
// the receivers' radiance (0), the environment they hide (1) and the solid angle they cover
// (2), each evaluated as E(n) / pi. Included by shading.glsl after frame.glsl.
layout(set = 0, binding = 14) uniform sampler2D bounceSh; // row: probe, column: 9 set + k

// The instance's bounce capture, or -1 (none, or a frame without bounce light).
int bounceProbe(Instance ins) { return frame.sky.z > 0.5 ? int(ins.flags.y) - 1 : -1; }

vec3 bounceIrradiance(int probe, int set, vec3 n) {
    float b[9] = float[9](0.282095, 0.488603 * n.y, 0.488603 * n.z, 0.488603 * n.x,
                          1.092548 * n.x * n.y, 1.092548 * n.y * n.z,
                          0.315392 * (3.0 * n.z * n.z - 1.0), 1.092548 * n.x * n.z,
                          0.546274 * (n.x * n.x - n.y * n.y));
    vec3 e = vec3(0.0);
    for (int k = 0; k < 9; ++k) e += b[k] * texelFetch(bounceSh, ivec2(9 * set + k, probe), 0).rgb;
    return max(e, vec3(0.0));
}
