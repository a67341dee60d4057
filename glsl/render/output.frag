#version 450
// The output pass: linear radiance times the exposure, tone mapped to [0, 1] and written to an
// sRGB target (the hardware encodes). Operators (weft::ToneMap):
//   0 clamp   - the seed's look, values above 1 clip;
//   1 ACES    - K. Narkowicz, "ACES Filmic Tone Mapping Curve" (2015), a rational fit of the
//               ACES RRT + ODT with its suggested 0.6 pre-scale;
//   2 AgX     - T. Sobotka's AgX base look as shipped in Blender 4: inset matrix, log2 encoding
//               over [-12.47, 4.03] EV, a 6th-order polynomial fit of the contrast sigmoid,
//               outset matrix; the curve's output is display-encoded (gamma 2.2), so it is
//               decoded before the hardware's sRGB encoding;
//   3 neutral - Khronos PBR Neutral (2024): hue and values below ~0.76 kept, highlights
//               compressed towards white.
layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(push_constant) uniform OutputPush { vec4 params; } push; // x: 2^EV, y: operator
// The operator the pipeline is made for (ScenePipelines::outputPipeline), or -1: push.params.y.
// lavapipe would run every operator's code under a mask (3 of the pass's 6.6 ms at 1280 x 720).
layout(constant_id = 0) const int kToneMap = -1;
layout(location = 0) out vec4 outColor;

vec3 aces(vec3 x) {
    x *= 0.6;
    return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 agx(vec3 c) {
    const mat3 inset = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
                            0.0784335999999992, 0.878468636469772, 0.0784336,
                            0.0792237451477643, 0.0791661274605434, 0.879142973793104);
    const mat3 outset = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438,
                             -0.0980208811401368, 1.15190312990417, -0.0980434501171241,
                             -0.0990297440797205, -0.0989611768448433, 1.15107367264116);
    const float minEv = -12.47393, maxEv = 4.026069;
    vec3 x = inset * max(c, vec3(0.0));
    x = clamp((log2(max(x, vec3(1e-10))) - minEv) / (maxEv - minEv), 0.0, 1.0);
    const vec3 x2 = x * x, x4 = x2 * x2;
    x = 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x -
        0.00232;
    x = outset * x;
    return pow(clamp(x, 0.0, 1.0), vec3(2.2));
}

vec3 neutral(vec3 c) {
    const float start = 0.8 - 0.04, desaturation = 0.15;
    const float low = min(c.r, min(c.g, c.b));
    const float offset = low < 0.08 ? low - 6.25 * low * low : 0.04;
    c -= offset;
    const float peak = max(c.r, max(c.g, c.b));
    if (peak < start) return c;
    const float d = 1.0 - start;
    const float newPeak = 1.0 - d * d / (peak + d - start);
    c *= newPeak / peak;
    const float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
    return mix(c, vec3(newPeak), g);
}

void main() {
    vec3 c = max(texelFetch(hdr, ivec2(gl_FragCoord.xy), 0).rgb * push.params.x, vec3(0.0));
    const int op = kToneMap >= 0 ? kToneMap : int(push.params.y + 0.5);
    if (op == 1) c = aces(c);
    else if (op == 2) c = agx(c);
    else if (op == 3) c = neutral(c);
    outColor = vec4(clamp(c, 0.0, 1.0), 1.0);
}
