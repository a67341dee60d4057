#version 450
#include "shading.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec4 outColor;

void main() {
    float vis, depth;
    vec3 n = normalize(inNormal);
    outColor = vec4(shade(inWorldPos, n, inUv, instances[push.instance], vis, depth), 1.0);
}
