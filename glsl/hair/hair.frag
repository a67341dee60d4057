#version 450
// Opaque hair: depth-tested, shaded per fragment.
#include "hair_lighting.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inTangent;
layout(location = 2) in vec3 inColor;
layout(location = 3) flat in uint inStrand;

layout(location = 0) out vec4 outColor;

void main() {
    float vis;
    HairShading s = hairInstances[push.instance].shading;
    outColor = vec4(hairRadiance(inWorldPos, normalize(inTangent), inColor, s, inStrand, vis), 1.0);
}
