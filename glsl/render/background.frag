#version 450
// The scene's background image (a camera frame for AR, SPEC §4.5) stretched over the target;
// sRGB textures decode to linear on sampling.
#include "frame.glsl"

layout(location = 0) out vec4 outColor;

void main() {
    outColor = vec4(textureLod(backgroundImage, gl_FragCoord.xy * frame.viewport.xy, 0.0).rgb, 1.0);
}
