#version 450
// GGX split-sum prefiltering of one output cube level (N = V = R), the GPU twin of
// weft::prefilterGgx (cpp/src/ibl/GlossyFilter.cpp) running the same plan (cpp/src/ibl/GgxPlan.h):
// filtered importance sampling of the clamped source (same samples, same seamless bilinear taps
// and trilinear blend between the source levels) plus an exact sum over the level's points.
//
// The source levels carry a one-texel border holding the taps past each face edge (the
// neighbouring face's texel; past a corner, the mean of three), so a bilinear lookup is four
// plain reads: on lavapipe every lane runs both sides of a divergent branch, and resolving the
// wrap per tap cost three quarters of the time. They are read through a texel buffer: lavapipe
// loads a storage buffer at per-lane addresses one lane at a time, a texel fetch as a gather.
layout(local_size_x = 64) in;

// Level l (size s, p = s + 2) at texel offset o: texel (face, i, j), i, j in [-1, s], is
// texelFetch(src, o + (face p + j + 1) p + i + 1).rgb.
layout(set = 0, binding = 0) uniform samplerBuffer src;
layout(std430, set = 0, binding = 1) writeonly buffer Target { float dst[]; };

// A sample: the half vector in the output texel's frame (z = normal) in dir.xyz, and the
// trilinear lookup: level (offset, size) in level.xy, weight dir.w of the level in level.zw.
struct Sample {
    vec4 dir;
    ivec4 level;
};
layout(std430, set = 0, binding = 2) readonly buffer Samples { Sample smp[]; };

// The points of the exact sums follow the source levels in `src`, two texels each: the unit
// direction (xyz), then radiance x solid angle (rgb) (a texel fetch, not a storage buffer load:
// see above).

layout(push_constant) uniform Params {
    int outSize;    // face size of the level written
    int outOffset;  // float offset of that level in `dst`
    int first;      // this level's samples: smp[first .. first + count)
    int count;
    int pointFirst; // texel of this level's first point in src
    int pointCount;
    float alpha2;   // GGX alpha^2 of the level
    float invNorm;  // 1 / integral of D(h) (n.l) dl
} pc;

vec3 faceDirection(int face, float u, float v) {
    vec3 d;
    if (face == 0) d = vec3(1.0, -v, -u);
    else if (face == 1) d = vec3(-1.0, -v, u);
    else if (face == 2) d = vec3(u, 1.0, v);
    else if (face == 3) d = vec3(u, -1.0, -v);
    else if (face == 4) d = vec3(u, -v, 1.0);
    else d = vec3(-u, -v, -1.0);
    return normalize(d);
}

// Face and (u, v) of a direction: the major axis picks the face.
vec3 cubeCoord(vec3 d) {
    vec3 a = abs(d);
    float face, sc, tc, ma;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x > 0.0 ? 0.0 : 1.0;
        sc = d.x > 0.0 ? -d.z : d.z;
        tc = -d.y;
        ma = a.x;
    } else if (a.y >= a.z) {
        face = d.y > 0.0 ? 2.0 : 3.0;
        sc = d.x;
        tc = d.y > 0.0 ? d.z : -d.z;
        ma = a.y;
    } else {
        face = d.z > 0.0 ? 4.0 : 5.0;
        sc = d.z > 0.0 ? d.x : -d.x;
        tc = -d.y;
        ma = a.z;
    }
    return vec3(face, clamp(sc / ma, -1.0, 1.0), clamp(tc / ma, -1.0, 1.0));
}

vec3 fetch(int texel) { return texelFetch(src, texel).xyz; }

// Seamless bilinear lookup of the level at texel offset `offset`, size s, at cube coordinate c.
vec3 bilinear(vec3 c, int offset, int s) {
    int p = s + 2;
    float x = (c.y + 1.0) * 0.5 * float(s) - 0.5, y = (c.z + 1.0) * 0.5 * float(s) - 0.5;
    int i0 = clamp(int(floor(x)), -1, s - 1), j0 = clamp(int(floor(y)), -1, s - 1);
    float fx = x - float(i0), fy = y - float(j0);
    int t = offset + (int(c.x) * p + j0 + 1) * p + i0 + 1;
    vec3 top = mix(fetch(t), fetch(t + 1), fx);
    vec3 bottom = mix(fetch(t + p), fetch(t + p + 1), fx);
    return mix(top, bottom, fy);
}

vec3 sampleLod(vec3 c, Sample sm) {
    vec3 a = bilinear(c, sm.level.x, sm.level.y);
    if (sm.dir.w <= 0.0) return a;
    return mix(a, bilinear(c, sm.level.z, sm.level.w), sm.dir.w);
}

void main() {
    int index = int(gl_GlobalInvocationID.x);
    int s = pc.outSize;
    if (index >= 6 * s * s) return;
    int face = index / (s * s), j = (index / s) % s, i = index % s;
    vec3 n = faceDirection(face, 2.0 * (float(i) + 0.5) / float(s) - 1.0,
                           2.0 * (float(j) + 0.5) / float(s) - 1.0);
    vec3 up = abs(n.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 t = normalize(cross(up, n));
    vec3 b = cross(n, t);
    vec3 acc = vec3(0.0);
    float wsum = 0.0;
    for (int k = pc.first; k < pc.first + pc.count; ++k) {
        Sample sm = smp[k];
        vec3 hl = sm.dir.xyz;
        vec3 h = hl.x * t + hl.y * b + hl.z * n;
        vec3 l = 2.0 * hl.z * h - n;
        float nl = dot(n, l);
        if (nl <= 0.0) continue;
        acc += nl * sampleLod(cubeCoord(l), sm);
        wsum += nl;
    }
    // weft::ggxPointWeight: D(h) (n.l) with (n.h)^2 = (1 + n.l) / 2
    vec3 exact = vec3(0.0);
    for (int k = 0; k < pc.pointCount; ++k) {
        int texel = pc.pointFirst + 2 * k;
        float nl = dot(n, texelFetch(src, texel).xyz);
        if (nl <= 0.0) continue;
        float d = 0.5 * (1.0 + nl) * (pc.alpha2 - 1.0) + 1.0;
        exact += (pc.alpha2 / (3.14159265358979 * d * d) * nl) * texelFetch(src, texel + 1).rgb;
    }
    vec3 result = (wsum > 0.0 ? acc / wsum : vec3(0.0)) + exact * pc.invNorm;
    int o = pc.outOffset + index * 3;
    dst[o] = result.x;
    dst[o + 1] = result.y;
    dst[o + 2] = result.z;
}
