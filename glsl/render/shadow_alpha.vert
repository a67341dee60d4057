#version 450
// Shadow map of alpha-tested geometry: passes the UV on to the alpha test.
layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv;
layout(push_constant) uniform Push { mat4 lightMvp; float alphaCutoff; } push;

layout(location = 0) out vec2 outUv;

void main() {
    outUv = inUv;
    gl_Position = push.lightMvp * vec4(inPosition, 1.0);
}
