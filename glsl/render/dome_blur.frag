#version 450
// The dome's shadows blurred along the columns of dome_blur_x.frag's result (dome_blur.glsl);
// each pixel adds its dome-darkened diffuse light (over the casters' floor) times the result.
#include "dome_blur.glsl"
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    vec2 centre = texelFetch(visDepthTex, c, 0).rg;
    float v = blurAlong(c, ivec2(0, 1), centre);
    outColor = vec4(texelFetch(domeTex, c, 0).rgb * v, 0.0); // added to the colour
}
