#version 450
// Deep opacity map pass 2 (SPEC §5.3): a fragment adds its alpha to its layer and every layer
// behind it (R, G, B, blend ONE, ONE); A keeps the smallest depth, z0 (blend MIN).
#include "hair_frame.glsl"

layout(push_constant) uniform LightPush {
    mat4 mvp;
    vec4 params; // x: DOM slot, y: layer size d (stored-depth units)
} lightPush;

layout(location = 0) in float inAlpha;
layout(location = 0) out vec4 outOpacity;

void main() {
    int slot = int(lightPush.params.x);
    float z0 = texelFetch(hairDom, ivec3(ivec2(gl_FragCoord.xy), slot), 0).r;
    int k = hairDomLayer(gl_FragCoord.z - z0, hairDomBounds(lightPush.params.y));
    outOpacity = vec4(k == 0 ? inAlpha : 0.0, k <= 1 ? inAlpha : 0.0, inAlpha, gl_FragCoord.z);
}
