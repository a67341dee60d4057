#version 450
// WBOIT composite over the opaque image: (sum C w / sum a w, 1 - prod(1 - a)) blended with
// SRC_ALPHA, ONE_MINUS_SRC_ALPHA gives avg (1 - prod) + C_0 prod (SPEC §5.4).
layout(set = 0, binding = 0) uniform sampler2D accumTex;
layout(set = 0, binding = 1) uniform sampler2D revealTex;
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float reveal = texelFetch(revealTex, p, 0).r;
    if (reveal >= 1.0) discard; // no hair here
    vec4 accum = texelFetch(accumTex, p, 0);
    outColor = vec4(accum.rgb / max(accum.a, 1e-30), 1.0 - reveal);
}
