#version 450
// GGX split-sum prefiltering of one output cube level (N = V = R) by filtered importance sampling,
// the GPU twin of weft::prefilterGgx (cpp/src/ibl/GlossyFilter.cpp): same face convention,
// seamless taps (edge neighbours at the same position along the edge, corners averaged over the
// three faces), Hammersley points, GGX half vectors and mip level from each sample's solid angle.
// samples == 0 writes the mirror level: the source read at lod `lod0`.
layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Source { float src[]; }; // all mip levels
layout(std430, set = 0, binding = 1) writeonly buffer Target { float dst[]; };

layout(push_constant) uniform Params {
    int srcSize;      // level-0 face size of the source
    int srcLevels;    // levels in `src`
    int outSize;      // face size of the level written
    int outOffset;    // float offset of that level in `dst`
    int samples;      // 0: mirror level
    float alpha;      // GGX alpha = roughness^2
    float lod0;       // source lod for the mirror level
    float texelOmega; // solid angle of a level-0 source texel, 4 pi / (6 srcSize^2)
} pc;

const float PI = 3.14159265358979;

int levelSize(int l) { return max(1, pc.srcSize >> l); }

int levelOffset(int l) {
    int o = 0;
    for (int k = 0; k < l; ++k) o += 6 * levelSize(k) * levelSize(k) * 3;
    return o;
}

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

int faceIndex(float c, int s) { return clamp(int(floor((c + 1.0) * 0.5 * float(s))), 0, s - 1); }

float across(int k, int s) {
    float eps = 1e-3 / float(s);
    return k < 0 ? -1.0 - eps : (k >= s ? 1.0 + eps : 2.0 * (float(k) + 0.5) / float(s) - 1.0);
}

int indexWrapped(int face, int i, int j, int s) {
    if (i < 0 || i >= s || j < 0 || j >= s) {
        vec3 c = cubeCoord(faceDirection(face, across(i, s), across(j, s)));
        face = int(c.x);
        i = faceIndex(c.y, s);
        j = faceIndex(c.z, s);
    }
    return (face * s + j) * s + i;
}

vec3 fetch(int offset, int index) {
    int o = offset + index * 3;
    return vec3(src[o], src[o + 1], src[o + 2]);
}

vec3 tap(int offset, int s, int face, int i, int j) {
    int ci = clamp(i, 0, s - 1), cj = clamp(j, 0, s - 1);
    if (ci != i && cj != j)
        return (fetch(offset, (face * s + cj) * s + ci) +
                fetch(offset, indexWrapped(face, i, cj, s)) +
                fetch(offset, indexWrapped(face, ci, j, s))) / 3.0;
    return fetch(offset, indexWrapped(face, i, j, s));
}

vec3 sampleLevel(vec3 d, int l) {
    int s = levelSize(l), offset = levelOffset(l);
    vec3 c = cubeCoord(d);
    int face = int(c.x);
    float x = (c.y + 1.0) * 0.5 * float(s) - 0.5, y = (c.z + 1.0) * 0.5 * float(s) - 0.5;
    int i0 = int(floor(x)), j0 = int(floor(y));
    float fx = x - float(i0), fy = y - float(j0);
    vec3 top = mix(tap(offset, s, face, i0, j0), tap(offset, s, face, i0 + 1, j0), fx);
    vec3 bottom = mix(tap(offset, s, face, i0, j0 + 1), tap(offset, s, face, i0 + 1, j0 + 1), fx);
    return mix(top, bottom, fy);
}

vec3 sampleLod(vec3 d, float lod) {
    lod = clamp(lod, 0.0, float(pc.srcLevels - 1));
    int l0 = int(floor(lod));
    float f = lod - float(l0);
    vec3 a = sampleLevel(d, l0);
    if (f <= 0.0 || l0 + 1 >= pc.srcLevels) return a;
    return mix(a, sampleLevel(d, l0 + 1), f);
}

vec2 hammersley(uint i, uint n) {
    return vec2(float(i) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10);
}

void main() {
    int index = int(gl_GlobalInvocationID.x);
    int s = pc.outSize;
    if (index >= 6 * s * s) return;
    int face = index / (s * s), j = (index / s) % s, i = index % s;
    vec3 n = faceDirection(face, 2.0 * (float(i) + 0.5) / float(s) - 1.0,
                           2.0 * (float(j) + 0.5) / float(s) - 1.0);
    vec3 result;
    if (pc.samples == 0) {
        result = sampleLod(n, pc.lod0);
    } else {
        vec3 up = abs(n.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
        vec3 t = normalize(cross(up, n));
        vec3 b = cross(n, t);
        float a2 = pc.alpha * pc.alpha;
        vec3 acc = vec3(0.0);
        float wsum = 0.0;
        for (int k = 0; k < pc.samples; ++k) {
            vec2 u = hammersley(uint(k), uint(pc.samples));
            float cosT = sqrt((1.0 - u.y) / (1.0 + (a2 - 1.0) * u.y));
            float sinT = sqrt(max(0.0, 1.0 - cosT * cosT));
            float phi = 2.0 * PI * u.x;
            vec3 hl = vec3(sinT * cos(phi), sinT * sin(phi), cosT);
            vec3 h = hl.x * t + hl.y * b + hl.z * n;
            vec3 l = 2.0 * hl.z * h - n;
            float nl = dot(n, l);
            if (nl <= 0.0) continue;
            float dd = cosT * cosT * (a2 - 1.0) + 1.0;
            float pdf = a2 / (PI * dd * dd) * 0.25;
            float omegaS = 1.0 / (float(pc.samples) * max(pdf, 1e-12));
            float lod = max(0.0, 0.5 * log2(omegaS / pc.texelOmega));
            acc += nl * sampleLod(l, lod);
            wsum += nl;
        }
        result = wsum > 0.0 ? acc / wsum : vec3(0.0);
    }
    int o = pc.outOffset + index * 3;
    dst[o] = result.x;
    dst[o + 1] = result.y;
    dst[o + 2] = result.z;
}
