#version 450
// WBOIT composite over the opaque image: (sum C w / sum a w, 1 - prod(1 - a)) blended with
// SRC_ALPHA, ONE_MINUS_SRC_ALPHA gives avg (1 - prod) + C_0 prod (SPEC §5.4). In anti-aliased
// frames the partly covered pixels of opaque strands hide that much more of what lies behind:
// prod (1 - their coverage), the mean of what their fragments wrote (hair_oit_main.glsl,
// HAIR_AA_MASK).
layout(set = 0, binding = 0) uniform sampler2D accumTex;  // rgb: sum C a w; a: prod(1 - a)
layout(set = 0, binding = 1) uniform sampler2D weightTex; // r: sum a w; g / b: opaque coverage
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 accum = texelFetch(accumTex, p, 0);
    vec3 weight = texelFetch(weightTex, p, 0).rgb;
    float covered = weight.b > 0.0 ? min(weight.g / weight.b, 1.0) : 0.0;
    float reveal = accum.a * (1.0 - covered);
    if (reveal >= 1.0) discard; // no hair here
    outColor = vec4(accum.rgb / max(weight.r, 1e-30), 1.0 - reveal);
}
