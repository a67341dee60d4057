#version 450
#extension GL_EXT_control_flow_attributes : require
// Exact cosine convolution, the GPU twin of weft::irradianceExact
// (cpp/src/ibl/IrradianceFilter.cpp): output texel with direction N gets the sum of
// max(0, N.w) L(w) dw over every source texel. The source comes as two vec4 per texel, (w, dw)
// and (L dw, 0), built on the CPU from the very table the CPU version sums (exact solid angles),
// in a storage buffer (lavapipe mishandles sampler arrays indexed in loops).
//
// The workgroup walks the source in tiles of TILE texels staged in shared memory, one texel per
// invocation per tile. Each invocation computes OUTPUTS output texels (outputs
// group * TILE * OUTPUTS + q * TILE + local index, q < OUTPUTS), so every texel read from shared
// memory serves OUTPUTS sums: lavapipe (Mesa 22) reads shared and storage memory lane by lane,
// and that amortisation makes it ~5x faster there (a GPU is indifferent at this register cost).
//
// Accumulation is float: a partial sum per tile, added to the running total once per tile, so the
// rounding error grows with TILE plus the number of tiles rather than with the 6 sourceSize^2
// texels (measured: ~3e-7 mean relative to a float64 sum of the same table, the CPU's single
// running sum ~2e-6).
//
// One dispatch sums up to 32768 source texels, a 1 MiB window of the source buffer bound at a
// dynamic offset (no descriptor exceeds maxStorageBufferRange, 128 MiB on lavapipe, while a
// 1024^2 source is 192 MiB); larger sources take several dispatches, each adding to what the
// previous ones wrote. The windows also keep lavapipe (Mesa 22) correct: it silently ends a
// shader's loops after 65535 iterations in all (its "loop limiter", shared by every loop of the
// shader); with the loops over the outputs unrolled a window counts about 65 iterations per
// tile, 33k in all.
#define TILE 64
#define OUTPUTS 8
layout(local_size_x = TILE) in;

layout(std430, set = 0, binding = 0) readonly buffer Source { vec4 src[]; }; // 2 per texel, window
layout(std430, set = 0, binding = 1) buffer Target { float dst[]; }; // read when accumulating

layout(push_constant) uniform Params {
    int outSize;    // face size of the output
    int texelCount; // source texels in this dispatch's window (6 sourceSize^2 in all)
    int accumulate; // 0: write the sums, 1: add them to dst (a later window of the source)
} pc;

shared vec4 tileDir[TILE];
shared vec4 tileRad[TILE];

// Same face convention as weft::cubeDirection (weft/CubeMap.h).
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

void main() {
    int group = int(gl_WorkGroupID.x);
    int lid = int(gl_LocalInvocationIndex);
    int s = pc.outSize;
    int outCount = 6 * s * s;
    int first = group * TILE * OUTPUTS + lid;
    // Invocations past the end still stage tiles (every invocation reaches each barrier); their
    // sums (of the last texel, clamped) are simply not written.
    vec3 n[OUTPUTS];
    vec3 total[OUTPUTS];
    [[unroll]] for (int q = 0; q < OUTPUTS; ++q) {
        int o = min(first + q * TILE, outCount - 1);
        int face = o / (s * s), j = (o / s) % s, i = o % s;
        n[q] = faceDirection(face, 2.0 * (float(i) + 0.5) / float(s) - 1.0,
                             2.0 * (float(j) + 0.5) / float(s) - 1.0);
        total[q] = vec3(0.0);
    }
    for (int base = 0; base < pc.texelCount; base += TILE) {
        int k = base + lid;
        bool inside = k < pc.texelCount;
        tileDir[lid] = inside ? src[2 * k] : vec4(0.0); // zero radiance pads the last tile
        tileRad[lid] = inside ? src[2 * k + 1] : vec4(0.0);
        barrier();
        vec3 partial[OUTPUTS];
        [[unroll]] for (int q = 0; q < OUTPUTS; ++q) partial[q] = vec3(0.0);
        for (int t = 0; t < TILE; ++t) { // not unrolled: ~20 ms more of lavapipe compile per call
            vec3 d = tileDir[t].xyz, r = tileRad[t].xyz;
            [[unroll]] for (int q = 0; q < OUTPUTS; ++q) partial[q] += max(0.0, dot(n[q], d)) * r;
        }
        [[unroll]] for (int q = 0; q < OUTPUTS; ++q) total[q] += partial[q];
        barrier(); // everyone has read the tile before it is overwritten
    }
    [[unroll]] for (int q = 0; q < OUTPUTS; ++q) {
        int index = first + q * TILE;
        if (index < outCount) {
            vec3 e = total[q];
            if (pc.accumulate != 0)
                e += vec3(dst[3 * index], dst[3 * index + 1], dst[3 * index + 2]);
            dst[3 * index] = e.x;
            dst[3 * index + 1] = e.y;
            dst[3 * index + 2] = e.z;
        }
    }
}
