#version 450
// Depth-only pass from a light: the shadow map.
layout(location = 0) in vec3 inPosition;
layout(push_constant) uniform Push { mat4 lightMvp; float alphaCutoff; } push;

void main() { gl_Position = push.lightMvp * vec4(inPosition, 1.0); }
