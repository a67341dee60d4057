#version 450
// WBOIT composite over the opaque image: (sum C w / sum a w, 1 - prod(1 - a)) blended with
// SRC_ALPHA, ONE_MINUS_SRC_ALPHA gives avg (1 - prod) + C_0 prod (SPEC §5.4).
layout(set = 0, binding = 0) uniform sampler2D accumTex;  // rgb: sum C a w; a: prod(1 - a)
layout(set = 0, binding = 1) uniform sampler2D weightTex; // r: sum a w
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 accum = texelFetch(accumTex, p, 0);
    if (accum.a >= 1.0) discard; // no hair here
    float weight = texelFetch(weightTex, p, 0).r;
    outColor = vec4(accum.rgb / max(weight, 1e-30), 1.0 - accum.a);
}
