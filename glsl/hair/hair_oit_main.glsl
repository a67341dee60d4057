// Weighted blended OIT accumulation (SPEC §5.4). Both targets blend alike (no independent-blend
// feature needed): colour channels ONE, ONE; alpha ZERO, ONE_MINUS_SRC_ALPHA. Target 0 gets
// rgb += C a w and its alpha (the revealage) *= 1 - a; target 1 gets r += a w (and, with
// HAIR_AA_MASK, g += the pixel's coverage by opaque strands, b += 1, averaged by the composite).
// Weights eq. 7-10 as in python/weft/reference/hair_oit.py. With HAIR_AA the opacity is
// multiplied by the pixel's coverage (hair_coverage.glsl).
//
// With HAIR_AA_MASK it accumulates the partly covered pixels of opaque strands (anti-aliased
// frames; the entirely covered ones were drawn opaque, with depth, before), each strand with
// the share of the pixel it shows: a point-sampled frame shows, at each point, the nearest
// strand there, and in dense hair a pixel shows 2.7 strands on average (weft.reference.picture's
// hair_scene, 16 x 16 points per pixel), 42% of its hair area behind the nearest one.
// hairSamples, per pixel: layers 0-31 the nearest depth at each of the first 32 of 128 sample
// points, 32-35 which of the 128 points some strand covers, 36-38 sums for the coverage (below).
// HAIR_AA_PASS 0 writes every fragment's depth into the depth samples inside its strip (atomic
// min; a fragment's depth is its strip's at the pixel's centre) and ORs in the points it covers.
// Pass 1 (after a barrier) shades every fragment once with the share
// a = coverage * (depth samples it won) / (depth samples it covers): its exact coverage where
// nothing nearer overlaps it, and order-independent. Colours are averaged by a (times the OIT
// weight, as for transparent strands). Depth tests run early, so fragments hidden by meshes or
// opaque hair leave no trace. (Before, the nearest strand went first and the others took the
// points still free in drawing order, hidden strands included: hair_scene's AA error was
// 9.97/255 at 128 x 96, 6.08 with the depths; BENCHMARKS.md, picture.)
#include "hair_lighting.glsl"
#include "hair_coverage.glsl"

#ifdef HAIR_AA_MASK
layout(early_fragment_tests) in;
layout(set = 3, binding = 2, r32ui) uniform coherent uimage2DArray hairSamples;
#endif

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inTangent;
layout(location = 2) in vec3 inColor;
layout(location = 3) flat in uint inStrand;
layout(location = 4) in float inAlpha;
layout(location = 5) in float inViewDepth;
#ifdef HAIR_AA
layout(location = 6) noperspective in vec2 inStrip;
layout(location = 7) noperspective in vec2 inAcross;
layout(location = 8) noperspective in vec2 inEnds;
#endif

layout(location = 0) out vec4 outAccum;
layout(location = 1) out vec4 outWeight;

// The weight the pipeline is made for (HairPipelines::shaded; weft::OitWeight, eq. 7-10), or
// -1: the frame's (hairFrame.params.y). lavapipe would evaluate all four under a mask.
layout(constant_id = 3) const int kOitWeight = -1;

float oitWeight(float z, float a, float zNdc) {
    z = abs(z);
    int eq = kOitWeight >= 0 ? kOitWeight : hairFrame.params.y;
    float far6 = pow(z / 200.0, 6.0);
    if (eq == 7) return a * clamp(10.0 / (1e-5 + pow(z / 5.0, 2.0) + far6), 1e-2, 3e3);
    if (eq == 8) return a * clamp(10.0 / (1e-5 + pow(z / 10.0, 3.0) + far6), 1e-2, 3e3);
    if (eq == 9) return a * clamp(0.03 / (1e-5 + pow(z / 200.0, 4.0)), 1e-2, 3e3);
    return a * max(1e-2, 3e3 * pow(1.0 - zNdc, 3.0));
}

#ifdef HAIR_AA_MASK
// the first layer after the depths: one per bit of a mask word (kHairAaDepthSamples,
// HairPipelines.h)
const int HAIR_COVERED = 32;
const float HAIR_FIXED_ONE = 65536.0; // fixed-point unit of the coverage sums

// The sample points of the pixel inside the strip, between its ends (bit j of word k: point
// 32 k + j): the first 128 points of the 2D Sobol sequence in Gray code order, which visits the
// first 32 points first. Point (X, Y) (integers < 128) lies at ((X, Y) + 0.5) / 128 - 0.5 from
// the pixel's centre; X is the van der Corput radical inverse of the index, Y Sobol's second
// dimension, whose direction numbers (64, 96, 80, 120, 68, 102, 85) are the rows of Pascal's
// triangle mod 2. Points 0-31 and 0-127 are (0, m, 2)-nets: every 2^-a x 2^-b box of the pixel
// with a + b = 5 (or 7) holds one point. The points are written out, one HAIR_POINT each
// (tests/python/hair/test_hair_sample_points.py checks them against the sequence): lavapipe
// ran the loop that walked the sequence, or read a constant table, 28% slower in the opaque
// strands' fringe passes (BENCHMARKS.md, hair).
#define HAIR_POINT(k, j, X, Y)                                                         \
    d = x0 + dot(vec2(X, Y), stepAcross);                                             \
    l = dot(vec2(X, Y), stepAlong);                                                   \
    if (abs(d) <= h && l >= yLo && l <= yHi) mask[k] |= 1u << j;
uvec4 hairSampleMask(vec2 strip, vec2 ends, vec2 across, uint words) {
    vec2 along = vec2(across.y, -across.x); // root to tip
    vec2 stepAcross = across / 128.0, stepAlong = along / 128.0;
    const float first = 0.5 / 128.0 - 0.5;
    float x0 = strip.x + first * (across.x + across.y), h = 0.5 * strip.y;
    float y0 = first * (along.x + along.y), yLo = -ends.x - y0, yHi = ends.y - y0;
    uvec4 mask = uvec4(0u);
    float d, l;
    HAIR_POINT(0, 0, 0, 0) HAIR_POINT(0, 1, 64, 64) HAIR_POINT(0, 2, 96, 32)
    HAIR_POINT(0, 3, 32, 96) HAIR_POINT(0, 4, 48, 48) HAIR_POINT(0, 5, 112, 112)
    HAIR_POINT(0, 6, 80, 16) HAIR_POINT(0, 7, 16, 80) HAIR_POINT(0, 8, 24, 40)
    HAIR_POINT(0, 9, 88, 104) HAIR_POINT(0, 10, 120, 8) HAIR_POINT(0, 11, 56, 72)
    HAIR_POINT(0, 12, 40, 24) HAIR_POINT(0, 13, 104, 88) HAIR_POINT(0, 14, 72, 56)
    HAIR_POINT(0, 15, 8, 120) HAIR_POINT(0, 16, 12, 60) HAIR_POINT(0, 17, 76, 124)
    HAIR_POINT(0, 18, 108, 28) HAIR_POINT(0, 19, 44, 92) HAIR_POINT(0, 20, 60, 12)
    HAIR_POINT(0, 21, 124, 76) HAIR_POINT(0, 22, 92, 44) HAIR_POINT(0, 23, 28, 108)
    HAIR_POINT(0, 24, 20, 20) HAIR_POINT(0, 25, 84, 84) HAIR_POINT(0, 26, 116, 52)
    HAIR_POINT(0, 27, 52, 116) HAIR_POINT(0, 28, 36, 36) HAIR_POINT(0, 29, 100, 100)
    HAIR_POINT(0, 30, 68, 4) HAIR_POINT(0, 31, 4, 68)
    if (words > 1u) {
        HAIR_POINT(1, 0, 6, 34) HAIR_POINT(1, 1, 70, 98) HAIR_POINT(1, 2, 102, 2)
        HAIR_POINT(1, 3, 38, 66) HAIR_POINT(1, 4, 54, 18) HAIR_POINT(1, 5, 118, 82)
        HAIR_POINT(1, 6, 86, 50) HAIR_POINT(1, 7, 22, 114) HAIR_POINT(1, 8, 30, 10)
        HAIR_POINT(1, 9, 94, 74) HAIR_POINT(1, 10, 126, 42) HAIR_POINT(1, 11, 62, 106)
        HAIR_POINT(1, 12, 46, 58) HAIR_POINT(1, 13, 110, 122) HAIR_POINT(1, 14, 78, 26)
        HAIR_POINT(1, 15, 14, 90) HAIR_POINT(1, 16, 10, 30) HAIR_POINT(1, 17, 74, 94)
        HAIR_POINT(1, 18, 106, 62) HAIR_POINT(1, 19, 42, 126) HAIR_POINT(1, 20, 58, 46)
        HAIR_POINT(1, 21, 122, 110) HAIR_POINT(1, 22, 90, 14) HAIR_POINT(1, 23, 26, 78)
        HAIR_POINT(1, 24, 18, 54) HAIR_POINT(1, 25, 82, 118) HAIR_POINT(1, 26, 114, 22)
        HAIR_POINT(1, 27, 50, 86) HAIR_POINT(1, 28, 34, 6) HAIR_POINT(1, 29, 98, 70)
        HAIR_POINT(1, 30, 66, 38) HAIR_POINT(1, 31, 2, 102)
    }
    if (words > 2u) {
        HAIR_POINT(2, 0, 3, 51) HAIR_POINT(2, 1, 67, 115) HAIR_POINT(2, 2, 99, 19)
        HAIR_POINT(2, 3, 35, 83) HAIR_POINT(2, 4, 51, 3) HAIR_POINT(2, 5, 115, 67)
        HAIR_POINT(2, 6, 83, 35) HAIR_POINT(2, 7, 19, 99) HAIR_POINT(2, 8, 27, 27)
        HAIR_POINT(2, 9, 91, 91) HAIR_POINT(2, 10, 123, 59) HAIR_POINT(2, 11, 59, 123)
        HAIR_POINT(2, 12, 43, 43) HAIR_POINT(2, 13, 107, 107) HAIR_POINT(2, 14, 75, 11)
        HAIR_POINT(2, 15, 11, 75) HAIR_POINT(2, 16, 15, 15) HAIR_POINT(2, 17, 79, 79)
        HAIR_POINT(2, 18, 111, 47) HAIR_POINT(2, 19, 47, 111) HAIR_POINT(2, 20, 63, 63)
        HAIR_POINT(2, 21, 127, 127) HAIR_POINT(2, 22, 95, 31) HAIR_POINT(2, 23, 31, 95)
        HAIR_POINT(2, 24, 23, 39) HAIR_POINT(2, 25, 87, 103) HAIR_POINT(2, 26, 119, 7)
        HAIR_POINT(2, 27, 55, 71) HAIR_POINT(2, 28, 39, 23) HAIR_POINT(2, 29, 103, 87)
        HAIR_POINT(2, 30, 71, 55) HAIR_POINT(2, 31, 7, 119)
    }
    if (words > 3u) {
        HAIR_POINT(3, 0, 5, 17) HAIR_POINT(3, 1, 69, 81) HAIR_POINT(3, 2, 101, 49)
        HAIR_POINT(3, 3, 37, 113) HAIR_POINT(3, 4, 53, 33) HAIR_POINT(3, 5, 117, 97)
        HAIR_POINT(3, 6, 85, 1) HAIR_POINT(3, 7, 21, 65) HAIR_POINT(3, 8, 29, 57)
        HAIR_POINT(3, 9, 93, 121) HAIR_POINT(3, 10, 125, 25) HAIR_POINT(3, 11, 61, 89)
        HAIR_POINT(3, 12, 45, 9) HAIR_POINT(3, 13, 109, 73) HAIR_POINT(3, 14, 77, 41)
        HAIR_POINT(3, 15, 13, 105) HAIR_POINT(3, 16, 9, 45) HAIR_POINT(3, 17, 73, 109)
        HAIR_POINT(3, 18, 105, 13) HAIR_POINT(3, 19, 41, 77) HAIR_POINT(3, 20, 57, 29)
        HAIR_POINT(3, 21, 121, 93) HAIR_POINT(3, 22, 89, 61) HAIR_POINT(3, 23, 25, 125)
        HAIR_POINT(3, 24, 17, 5) HAIR_POINT(3, 25, 81, 69) HAIR_POINT(3, 26, 113, 37)
        HAIR_POINT(3, 27, 49, 101) HAIR_POINT(3, 28, 33, 53) HAIR_POINT(3, 29, 97, 117)
        HAIR_POINT(3, 30, 65, 21) HAIR_POINT(3, 31, 1, 85)
    }
    return mask;
}
#undef HAIR_POINT

float hairSampleCount(uvec4 mask) {
    uvec4 n = uvec4(bitCount(mask));
    return float(n.x + n.y + n.z + n.w);
}
#endif

void main() {
#ifdef HAIR_AA
    vec2 across = normalize(inAcross);
    float coverage = inAlpha * hairCoverage(inStrip, inEnds, across); // opaque: alpha 1
    if (coverage <= 0.0) discard; // the strip's outer corners
#endif
#if defined(HAIR_AA_MASK) && HAIR_AA_PASS == 0
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint depth = floatBitsToUint(gl_FragCoord.z); // ordered as the depths are (all >= 0)
    uvec4 mask = hairSampleMask(inStrip, inEnds, across, 4u);
    // only the depth samples the fragment covers, one set bit after another (its loop runs as
    // long as the most covering fragment of the SIMD group needs: fringe passes 6-9% faster on
    // lavapipe than all 32 with the min's identity, which was a few percent faster than a branch
    // per sample; BENCHMARKS.md, hair)
    for (uint m = mask.x; m != 0u; m &= m - 1u)
        imageAtomicMin(hairSamples, ivec3(pixel, findLSB(m)), depth);
    for (uint k = 0u; k < 4u; ++k)
        imageAtomicOr(hairSamples, ivec3(pixel, HAIR_COVERED + int(k)), mask[k]);
    float own = hairSampleCount(mask);
    uint c = uint(coverage * HAIR_FIXED_ONE + 0.5);
    if (own > 0.0) { // sum c, sum own
        imageAtomicAdd(hairSamples, ivec3(pixel, HAIR_COVERED + 4), c);
        imageAtomicAdd(hairSamples, ivec3(pixel, HAIR_COVERED + 5), uint(own));
    } else { // a sliver between the points: sum c
        imageAtomicAdd(hairSamples, ivec3(pixel, HAIR_COVERED + 6), c);
    }
    // nothing drawn (colour write mask 0): the inputs are read so that both passes use the
    // same vertex shader, hence the same depths
    outAccum = vec4(inWorldPos + inTangent + inColor, inViewDepth + float(inStrand));
    outWeight = vec4(0.0);
#else
#ifdef HAIR_AA_MASK
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint depth = floatBitsToUint(gl_FragCoord.z);
    uint mask = hairSampleMask(inStrip, inEnds, across, 1u).x;
    uint won = 0u;
    for (uint m = mask; m != 0u; m &= m - 1u) // the covered depth samples (as pass 0)
        won += imageLoad(hairSamples, ivec3(pixel, findLSB(m))).r == depth ? 1u : 0u;
    // a sliver between the depth samples counts as seen
    uint own = bitCount(mask);
    float a = own > 0u ? coverage * float(won) / float(own) : coverage;
    if (a <= 0.0) discard;
    // The pixel's hair coverage: the fraction of the 128 sample points its strands cover, |U| / N,
    // times the exact coverage of its strands over their sampled one, sum c / sum (own / N)
    // (exact for one strand or strands side by side), plus the slivers between the points; or 1
    // once all points are covered (a dense head of hair must not show the backdrop through it).
    // Every fragment of the pixel adds (coverage, 1) and the composite takes the mean.
    uvec4 all;
    for (uint k = 0u; k < 4u; ++k)
        all[k] = imageLoad(hairSamples, ivec3(pixel, HAIR_COVERED + int(k))).r;
    float u = hairSampleCount(all) / 128.0;
    uvec3 sums = uvec3(imageLoad(hairSamples, ivec3(pixel, HAIR_COVERED + 4)).r,
                       imageLoad(hairSamples, ivec3(pixel, HAIR_COVERED + 5)).r,
                       imageLoad(hairSamples, ivec3(pixel, HAIR_COVERED + 6)).r);
    float sumC = float(sums.x) / HAIR_FIXED_ONE, sumOwn = float(sums.y) / 128.0;
    float slivers = float(sums.z) / HAIR_FIXED_ONE;
    float pixelCoverage = u >= 1.0 ? 1.0 : (sumOwn > 0.0 ? sumC / sumOwn * u : 0.0) + slivers;
    vec2 covered = vec2(min(pixelCoverage, 1.0), 1.0);
    float reveal = 0.0; // transparent strands' revealage untouched
    float w = oitWeight(inViewDepth, 1.0, gl_FragCoord.z);
#else
#ifdef HAIR_AA
    float a = coverage;
#else
    float a = inAlpha;
#endif
    vec2 covered = vec2(0.0);
    float reveal = a;
    float w = oitWeight(inViewDepth, a, gl_FragCoord.z);
#endif
    float vis;
    HairShading s = hairInstances[push.instance].shading;
    vec3 c = hairRadiance(inWorldPos, normalize(inTangent), inColor, s, inStrand, vis);
    outAccum = vec4(c * a * w, reveal);
    outWeight = vec4(a * w, covered, reveal);
#endif
}
