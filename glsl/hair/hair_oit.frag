#version 450
// Weighted blended OIT accumulation (SPEC §5.4). Both targets blend alike (no independent-blend
// feature needed): colour channels ONE, ONE; alpha ZERO, ONE_MINUS_SRC_ALPHA. Target 0 gets
// rgb += C a w and its alpha (the revealage) *= 1 - a; target 1 (one channel) gets += a w.
// Weights eq. 7-10 as in python/weft/reference/hair_oit.py.
#include "hair_lighting.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inTangent;
layout(location = 2) in vec3 inColor;
layout(location = 3) flat in uint inStrand;
layout(location = 4) in float inAlpha;
layout(location = 5) in float inViewDepth;

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

void main() {
    float vis;
    HairShading s = hairInstances[push.instance].shading;
    vec3 c = hairRadiance(inWorldPos, normalize(inTangent), inColor, s, inStrand, vis);
    float a = inAlpha;
    float w = oitWeight(inViewDepth, a, gl_FragCoord.z);
    outAccum = vec4(c * a * w, a);
    outWeight = vec4(a * w, 0.0, 0.0, a);
}
