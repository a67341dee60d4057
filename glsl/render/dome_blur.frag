#version 450
// The dome's shadows blurred (SPEC §4.5: "the accumulated shadow image is blurred and multiplies
// the diffuse term only"), second of two separable passes: the row-blurred visibility of
// dome_blur_x.frag averaged along the column with the same weights; each pixel adds its
// environment diffuse light (before the dome's shadows) times the result.
layout(set = 0, binding = 0) uniform sampler2D domeTex;     // rgb: diffuse light, a: visibility
layout(set = 0, binding = 1) uniform sampler2D visDepthTex; // dome_blur_x.frag's output
layout(push_constant) uniform Push { vec4 params; } push;   // radius, near, far, tolerance
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    vec2 centre = texelFetch(visDepthTex, c, 0).rg;
    if (centre.y < 0.0) { // no depth here (background or MSAA sample 0 uncovered): unblurred
        outColor = vec4(texelFetch(domeTex, c, 0).rgb * centre.x, 0.0);
        return;
    }
    int last = textureSize(visDepthTex, 0).y - 1;
    float step = push.params.x / 3.0;
    float sigma = max(push.params.x * 0.5, 1e-6);
    float sum = 0.0, weights = 0.0;
    for (int k = -3; k <= 3; ++k) {
        float o = float(k) * step;
        vec2 s = texelFetch(visDepthTex, ivec2(c.x, clamp(c.y + int(floor(o + 0.5)), 0, last)), 0).rg;
        if (s.y < 0.0) continue;
        float dz = (s.y - centre.y) / (push.params.w * centre.y);
        float w = exp(-o * o / (2.0 * sigma * sigma) - dz * dz);
        sum += w * s.x;
        weights += w;
    }
    outColor = vec4(texelFetch(domeTex, c, 0).rgb * (sum / weights), 0.0); // added to the colour
}
