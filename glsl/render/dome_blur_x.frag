#version 450
// The dome's shadows blurred along the rows (dome_blur.glsl); writes (blurred visibility, view
// depth), or (own visibility, -1) where the pixel holds no surface.
#include "dome_blur.glsl"
layout(location = 0) out vec4 outVisDepth;

void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    vec2 centre = texelFetch(visDepthTex, c, 0).rg;
    outVisDepth = vec4(blurAlong(c, ivec2(1, 0), centre), centre.y, 0.0, 0.0);
}
