#version 450
// Hair lines seen from a light: shadow maps and the deep opacity map passes 1 and 2.
#include "hair_frame.glsl"

layout(push_constant) uniform LightPush {
    mat4 mvp;    // light view-projection * model
    vec4 params; // x: DOM slot, y: layer size d (stored-depth units)
} lightPush;

layout(location = 0) out float outAlpha;

void main() {
    HairVertex hv = hairVertices[uint(gl_VertexIndex) >> 1];
    outAlpha = hv.tangent.w;
    gl_Position = lightPush.mvp * vec4(hv.position.xyz, 1.0);
}
