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
// by side. hairMask, per pixel: layer 0 the samples of a 32-point pattern taken so far, layer 1
// the nearest depth, layer 2 the sum of the shares taken (fixed point). A fragment's share is
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

// Samples of the pixel (offsets from its centre) inside the strip: a Hammersley set, x stratified
// by 32 and y by the bit-reversed index, so that its projection across a strand of any direction
// is spread evenly.
uint hairSampleMask(vec2 strip, vec2 across) {
    float h = 0.5 * strip.y;
    uint mask = 0u;
    for (uint i = 0u; i < 32u; ++i) {
        vec2 o = vec2((float(i) + 0.5) / 32.0, (float(bitfieldReverse(i) >> 27) + 0.5) / 32.0);
        if (abs(strip.x + dot(o - 0.5, across)) <= h) mask |= 1u << i;
    }
    return mask;
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
    imageAtomicMin(hairMask, ivec3(pixel, 1), depth);
#else
    if (depth == imageLoad(hairMask, ivec3(pixel, 1)).r) { // the nearest takes its samples
        imageAtomicOr(hairMask, ivec3(pixel, 0), hairSampleMask(inStrip, across));
        imageAtomicAdd(hairMask, ivec3(pixel, 2), uint(coverage * HAIR_SHARE_ONE + 0.5));
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
    if (floatBitsToUint(gl_FragCoord.z) == imageLoad(hairMask, ivec3(pixel, 1)).r) {
        a = coverage; // taken in pass 1, first
        reveal = coverage >= 0.999 ? 1.0 : coverage;
    } else {
        uint mask = hairSampleMask(inStrip, across);
        uint before = imageAtomicOr(hairMask, ivec3(pixel, 0), mask);
        float own = float(bitCount(mask));
        float share = coverage * (own > 0.0 ? float(bitCount(mask & ~before)) / own : 1.0);
        uint fixedShare = uint(share * HAIR_SHARE_ONE + 0.5);
        if (fixedShare == 0u) discard;
        float free = 1.0 - float(imageAtomicAdd(hairMask, ivec3(pixel, 2), fixedShare)) /
                               HAIR_SHARE_ONE;
        a = clamp(min(float(fixedShare) / HAIR_SHARE_ONE, free), 0.0, 1.0);
        reveal = free > 0.0 ? a / free : 1.0;
        if ((before | mask) == ~0u) { // the last free samples: the rest of the pixel is hair
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
