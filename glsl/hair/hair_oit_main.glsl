// Weighted blended OIT accumulation (SPEC §5.4). Both targets blend alike (no independent-blend
// feature needed): colour channels ONE, ONE; alpha ZERO, ONE_MINUS_SRC_ALPHA. Target 0 gets
// rgb += C a w and its alpha (the revealage) *= 1 - a; target 1 (one channel) gets += a w.
// Weights eq. 7-10 as in python/weft/reference/hair_oit.py. With HAIR_AA the opacity is
// multiplied by the pixel's coverage (hair_coverage.glsl).
//
// With HAIR_AA_MASK it accumulates the partly covered pixels of opaque strands (anti-aliased
// frames; the entirely covered ones were drawn opaque, with depth, before), so that a pixel's
// coverage approaches the union of its strands' footprints rather than independent alphas (the
// product of 1 - coverage), which leave a dense head of hair see-through where strands lie side
// by side. hairMask, per pixel: layer 0 the nearest depth, layer 1 the sum of the shares taken
// (fixed point), layers 2-5 the samples of a 128-point pattern taken so far. A fragment's share is
// its exact coverage times the fraction of its own samples still free (all of them for the first
// strand, or a strand beside the others); it adds C w share and multiplies the revealage by
// 1 - share / (1 - shares before it), which telescopes to 1 - (sum of shares) in any order. The
// composite thus gives sum C_i share_i + background (1 - sum share_i) for equal weights. The
// fragment that takes the last free samples takes the rest of the pixel (shares that fill the
// pattern but fall short of 1 in their sum would leave a dense head of hair see-through). Which
// strand takes a sample shared by several depends on the order, so the nearest strand of each
// pixel goes first: HAIR_AA_PASS 0 keeps the nearest depth (atomic min), pass 1 lets the
// fragments at that depth take their samples and shares (neither pass shades or draws), pass 2
// shades every fragment once and lets the others take what is left. Depth tests run early, so
// fragments hidden by meshes or opaque hair leave no trace.
#include "hair_lighting.glsl"
#include "hair_coverage.glsl"

#ifdef HAIR_AA_MASK
layout(early_fragment_tests) in;
layout(set = 3, binding = 2, r32ui) uniform coherent uimage2DArray hairMask;
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
#endif

layout(location = 0) out vec4 outAccum;
layout(location = 1) out vec4 outWeight;

float oitWeight(float z, float a, float zNdc) {
    z = abs(z);
    int eq = hairFrame.params.y;
    float far6 = pow(z / 200.0, 6.0);
    if (eq == 7) return a * clamp(10.0 / (1e-5 + pow(z / 5.0, 2.0) + far6), 1e-2, 3e3);
    if (eq == 8) return a * clamp(10.0 / (1e-5 + pow(z / 10.0, 3.0) + far6), 1e-2, 3e3);
    if (eq == 9) return a * clamp(0.03 / (1e-5 + pow(z / 200.0, 4.0)), 1e-2, 3e3);
    return a * max(1e-2, 3e3 * pow(1.0 - zNdc, 3.0));
}

#ifdef HAIR_AA_MASK
const float HAIR_SHARE_ONE = 65536.0; // fixed-point unit of the shares' sum

// Samples of the pixel (offsets from its centre) inside the strip, HAIR_SAMPLE_WORDS x 32 of
// them: a Hammersley set, x stratified by their count and y by the bit-reversed index, so that
// its projection across a strand of any direction is spread evenly.
const uint HAIR_SAMPLE_WORDS = 4u;
const uint HAIR_SAMPLE_BITS = 7u; // log2(32 HAIR_SAMPLE_WORDS)
const float HAIR_SAMPLES = float(32u * HAIR_SAMPLE_WORDS);
const uvec4 HAIR_ALL_SAMPLES = uvec4(~0u, HAIR_SAMPLE_WORDS > 1u ? ~0u : 0u,
                                     HAIR_SAMPLE_WORDS > 2u ? ~0u : 0u,
                                     HAIR_SAMPLE_WORDS > 3u ? ~0u : 0u);
uvec4 hairSampleMask(vec2 strip, vec2 across) {
    float h = 0.5 * strip.y;
    uvec4 mask = uvec4(0u);
    for (uint i = 0u; i < 32u * HAIR_SAMPLE_WORDS; ++i) {
        vec2 o = (vec2(i, bitfieldReverse(i) >> (32u - HAIR_SAMPLE_BITS)) + 0.5) / HAIR_SAMPLES;
        if (abs(strip.x + dot(o - 0.5, across)) <= h) mask[i >> 5] |= 1u << (i & 31u);
    }
    return mask;
}

// ORs the samples into the pixel's (layers 2...), returning those taken before.
uvec4 hairTakeSamples(ivec2 pixel, uvec4 mask) {
    uvec4 before = uvec4(0u);
    for (uint k = 0u; k < HAIR_SAMPLE_WORDS; ++k)
        before[k] = imageAtomicOr(hairMask, ivec3(pixel, 2 + int(k)), mask[k]);
    return before;
}

float hairSampleCount(uvec4 mask) {
    uvec4 n = uvec4(bitCount(mask));
    return float(n.x + n.y + n.z + n.w);
}
#endif

void main() {
#ifdef HAIR_AA
    vec2 across = normalize(inAcross);
    float coverage = inAlpha * hairCoverage(inStrip, across); // opaque strands: alpha 1
    if (coverage <= 0.0) discard; // the strip's outer corners
#endif
#if defined(HAIR_AA_MASK) && HAIR_AA_PASS < 2
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint depth = floatBitsToUint(gl_FragCoord.z);
#if HAIR_AA_PASS == 0
    imageAtomicMin(hairMask, ivec3(pixel, 0), depth);
#else
    if (depth == imageLoad(hairMask, ivec3(pixel, 0)).r) { // the nearest takes its samples
        hairTakeSamples(pixel, hairSampleMask(inStrip, across));
        imageAtomicAdd(hairMask, ivec3(pixel, 1), uint(coverage * HAIR_SHARE_ONE + 0.5));
    }
#endif
    // nothing drawn (colour write mask 0): the inputs are read so that these passes use the
    // same vertex shader as the last, hence the same depths
    outAccum = vec4(inWorldPos + inTangent + inColor, inViewDepth + float(inStrand));
    outWeight = vec4(0.0);
#else
#if defined(HAIR_AA_MASK)
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float a, reveal;
    if (floatBitsToUint(gl_FragCoord.z) == imageLoad(hairMask, ivec3(pixel, 0)).r) {
        a = coverage; // taken in pass 1, first
        reveal = coverage >= 0.999 ? 1.0 : coverage;
    } else {
        uvec4 mask = hairSampleMask(inStrip, across);
        uvec4 before = hairTakeSamples(pixel, mask);
        float own = hairSampleCount(mask);
        float share = coverage * (own > 0.0 ? hairSampleCount(mask & ~before) / own : 1.0);
        uint fixedShare = uint(share * HAIR_SHARE_ONE + 0.5);
        if (fixedShare == 0u) discard;
        float free = 1.0 - float(imageAtomicAdd(hairMask, ivec3(pixel, 1), fixedShare)) /
                               HAIR_SHARE_ONE;
        a = clamp(min(float(fixedShare) / HAIR_SHARE_ONE, free), 0.0, 1.0);
        reveal = free > 0.0 ? a / free : 1.0;
        // the last free samples: the rest of the pixel is hair
        if (all(equal(before | mask, HAIR_ALL_SAMPLES))) {
            a = max(a, free);
            reveal = 1.0;
        }
    }
    float w = oitWeight(inViewDepth, 1.0, gl_FragCoord.z); // colours averaged by their shares
#else
#ifdef HAIR_AA
    float a = coverage;
#else
    float a = inAlpha;
#endif
    float reveal = a;
    float w = oitWeight(inViewDepth, a, gl_FragCoord.z);
#endif
    float vis;
    HairShading s = hairInstances[push.instance].shading;
    vec3 c = hairRadiance(inWorldPos, normalize(inTangent), inColor, s, inStrand, vis);
    outAccum = vec4(c * a * w, reveal);
    outWeight = vec4(a * w, 0.0, 0.0, reveal);
#endif
}
