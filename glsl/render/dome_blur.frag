#version 450
// The dome's shadows blurred (SPEC §4.5: "the accumulated shadow image is blurred and multiplies
// the diffuse term only"). Each pixel adds its environment diffuse light (before the dome's
// shadows) times the bilateral average of the dome visibility around it: 7 x 7 taps spread over
// `radius` pixels, weighted by a Gaussian (sigma = radius / 2) and by depth similarity
// exp(-(dz / (tolerance z))^2) in linear view depth, so shadows do not bleed across silhouettes.
// python/weft/reference/ibl_shading.py: dome_blur implements the same kernel in NumPy.
layout(set = 0, binding = 0) uniform sampler2D domeTex;  // rgb: diffuse light, a: visibility; a < 0: no surface
layout(set = 0, binding = 1) uniform sampler2D depthTex; // the forward pass's depth (perspective)
layout(push_constant) uniform Push { vec4 params; } push; // radius, near, far, tolerance
layout(location = 0) out vec4 outColor;

float viewDepth(float d) {
    float n = push.params.y, f = push.params.z;
    return n * f / (f - d * (f - n));
}

void main() {
    ivec2 size = textureSize(domeTex, 0);
    ivec2 c = ivec2(gl_FragCoord.xy);
    vec4 centre = texelFetch(domeTex, c, 0);
    if (centre.a < 0.0) discard;
    float zc = viewDepth(texelFetch(depthTex, c, 0).r);
    float radius = push.params.x;
    float step = radius / 3.0;
    float sigma = max(radius * 0.5, 1e-6);
    float sum = 0.0, weights = 0.0;
    for (int dy = -3; dy <= 3; ++dy) {
        for (int dx = -3; dx <= 3; ++dx) {
            vec2 o = vec2(dx, dy) * step;
            ivec2 q = clamp(c + ivec2(floor(o + 0.5)), ivec2(0), size - 1);
            vec4 s = texelFetch(domeTex, q, 0);
            if (s.a < 0.0) continue;
            float dz = (viewDepth(texelFetch(depthTex, q, 0).r) - zc) / (push.params.w * zc);
            float w = exp(-dot(o, o) / (2.0 * sigma * sigma) - dz * dz);
            sum += w * s.a;
            weights += w;
        }
    }
    outColor = vec4(centre.rgb * (sum / weights), 0.0); // blended: added to the colour
}
