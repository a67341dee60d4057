#version 450
// Opaque hair in anti-aliased frames: the pixels a strand covers entirely (hair_aa_core.vert
// draws a strip narrowed to them; the exact test here keeps the partly covered ones, up to
// rounding, for the fringe passes of hair_oit_main.glsl).
#include "hair_lighting.glsl"
#include "hair_coverage.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inTangent;
layout(location = 2) in vec3 inColor;
layout(location = 3) flat in uint inStrand;
layout(location = 6) noperspective in vec2 inStrip;
layout(location = 7) noperspective in vec2 inAcross;
layout(location = 8) noperspective in vec2 inEnds;

layout(location = 0) out vec4 outColor;

void main() {
    if (hairCoverage(inStrip, inEnds, normalize(inAcross)) < 0.999) discard;
    float vis;
    HairShading s = hairInstances[push.instance].shading;
    outColor = vec4(hairRadiance(inWorldPos, normalize(inTangent), inColor, s, inStrand, vis), 1.0);
}
