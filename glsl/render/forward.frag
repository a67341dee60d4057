#version 450
#include "shading.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inTangent;

layout(location = 0) out vec4 outColor;

void main() {
    Instance ins = instances[push.instance];
    if (alphaDiscarded(inUv, ins)) discard;
    float vis, depth;
    Surface sf = surfaceAt(inWorldPos, inNormal, inTangent, inUv, ins, gl_FrontFacing);
    outColor = vec4(shade(sf, ins, vis, depth), 1.0);
}
