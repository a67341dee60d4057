#version 450
#include "frame.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inTangent;

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUv;
layout(location = 3) out vec4 outTangent; // world xyz, handedness w

void main() {
    Instance ins = instances[push.instance];
    vec4 world = ins.model * vec4(inPosition, 1.0);
    outWorldPos = world.xyz;
    outNormal = mat3(ins.normalMatrix) * inNormal;
    // A mirroring transform flips the bitangent's side.
    float mirror = determinant(mat3(ins.model)) < 0.0 ? -1.0 : 1.0;
    outTangent = vec4(mat3(ins.model) * inTangent.xyz, inTangent.w * mirror);
    outUv = inUv;
    gl_Position = frame.viewProj * world;
}
