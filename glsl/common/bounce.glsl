// One bounce of diffuse light (render/BounceProbes.h, bounce_sh.frag): SH9 sets per caster of
// the receivers' radiance (0), the environment they hide (1) and the solid angle they cover
// (2), each evaluated as E(n) / pi. Included by shading.glsl after frame.glsl.
layout(set = 0, binding = 14) uniform sampler2D bounceSh; // row: probe * BOUNCE_POINTS + point,
                                                          // column: 9 set + k
layout(set = 0, binding = 15) uniform sampler2DArray bounceFaces; // layer 6 probe + face
// the casters' radiance as proxy spheres (bounce_radiance.frag): row probe, column k
layout(set = 0, binding = 16) uniform sampler2D bounceRadiance;
// the captures' depths (layer 6 probe + face), where their receivers are
layout(set = 0, binding = 17) uniform sampler2DArray bounceDepth;

#include "cube_faces.glsl"
#include "bounce_points.glsl"

// The instance's bounce capture, or -1 (none, or a frame without bounce light).
int bounceProbe(Instance ins) {
    return (kMaterialFlags & BOUNCE_CAPTURE) != 0u && featureOn(FEATURE_BOUNCE) &&
                   frame.sky.z > 0.5
               ? int(ins.flags.y) - 1
               : -1;
}

// SH9 basis at unit n, each band scaled by w (x: l = 0, y: l = 1, z: l = 2).
void shBasis9(vec3 n, vec3 w, out float b[9]) {
    b = float[9](w.x * 0.282095, w.y * 0.488603 * n.y, w.y * 0.488603 * n.z,
                 w.y * 0.488603 * n.x, w.z * 1.092548 * n.x * n.y, w.z * 1.092548 * n.y * n.z,
                 w.z * 0.315392 * (3.0 * n.z * n.z - 1.0), w.z * 1.092548 * n.x * n.z,
                 w.z * 0.546274 * (n.x * n.x - n.y * n.y));
}

// The rows of capture `probe`'s points (bounce_points.glsl) that light p, and their weights:
// the points around p's direction from the caster's centre, on the ellipsoid its bounds hold,
// blended towards the centre's own row for p inside it.
struct BounceRows {
    ivec4 rows;
    vec4 weights;
};

BounceRows bounceRowsAt(int probe, vec3 p) {
    vec3 extent = max(frame.bounceHalves[probe].xyz, vec3(1e-6));
    vec3 a = (p - frame.bounceSpheres[probe].xyz) / extent;
    float len = length(a);
    BounceRows r;
    r.rows = ivec4(probe * BOUNCE_POINTS);
    r.weights = vec4(1.0, 0.0, 0.0, 0.0);
    if (len < 1e-6) return r;
    ivec3 points;
    vec3 weights;
    bouncePointsAround(a / len, points, weights);
    float t = min(len, 1.0);
    r.rows.yzw += points;
    r.weights = vec4(1.0 - t, t * weights);
    return r;
}

// Set `set` at rows r with its bands scaled by w (1: the set's own E(n) / pi).
vec3 bounceSet(BounceRows r, int set, vec3 n, vec3 w) {
    float b[9];
    shBasis9(n, w, b);
    vec3 e = vec3(0.0);
    for (int j = 0; j < 4; ++j) {
        vec3 ej = vec3(0.0);
        for (int k = 0; k < 9; ++k)
            ej += b[k] * texelFetch(bounceSh, ivec2(9 * set + k, r.rows[j]), 0).rgb;
        e += r.weights[j] * ej;
    }
    return e;
}

vec3 bounceIrradiance(BounceRows r, int set, vec3 n) {
    return max(bounceSet(r, set, n, vec3(1.0)), vec3(0.0));
}

// Capture `probe`'s texel in direction d: rgb the receivers' radiance, a their coverage.
vec4 bounceFace(int probe, vec3 d) {
    vec2 uv;
    int face = cubeFace(d, uv);
    return textureLod(bounceFaces, vec3(uv, float(6 * probe + face)), 0.0);
}

// Where the ray from p along unit r meets capture `probe`'s receivers, as a direction from the
// caster's centre (r itself where the ray meets none): the capture's depth gives the receivers'
// distance from the centre along a direction, and three steps of p + t r at that distance
// converge on the hit (Szirmay-Kalos et al. 2005, "Approximate ray-tracing on the GPU with
// distance impostors"). Without it a glossy caster reflected, near its contact with the ground,
// the sunlit ground beyond its shadow that the centre sees along r.
vec3 bounceHitDirection(int probe, vec3 p, vec3 r) {
    const float near = 0.02, far = 1000.0; // probeFaceViewProj's planes (ReflectionProbe.cpp)
    vec3 o = p - frame.bounceSpheres[probe].xyz;
    vec3 d = r;
    ivec3 size = textureSize(bounceDepth, 0);
    for (int i = 0; i < 3; ++i) {
        vec2 uv;
        int face = cubeFace(d, uv);
        ivec2 t = clamp(ivec2(uv * vec2(size.xy)), ivec2(0), size.xy - 1);
        float z = texelFetch(bounceDepth, ivec3(t, 6 * probe + face), 0).r;
        if (z >= 1.0) return d;
        float along = near * far / (far - z * (far - near)); // along the face's axis
        float dist = along / max(dot(d, kCubeAxes[3 * face]), 1e-6);
        float b = dot(o, r), c = dot(o, o) - dist * dist;
        float disc = b * b - c;
        if (disc < 0.0) return d;
        d = normalize(o + (-b + sqrt(disc)) * r);
    }
    return d;
}
