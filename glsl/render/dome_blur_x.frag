#version 450
// The dome's shadows blurred (SPEC §4.5), first of two separable passes: the dome visibility
// averaged along the row over 7 taps spread over `radius` pixels, weighted by a Gaussian
// (sigma = radius / 2) and by depth similarity exp(-(dz / (tolerance z))^2) in linear view depth,
// so shadows do not bleed across silhouettes. Writes (blurred visibility, view depth), or
// (own visibility, -1) where the depth holds no surface. dome_blur.frag does the columns.
// Under MSAA the dome image is the average of its samples: samples without a surface hold
// rgb 0 and visibility 1, so rgb stays weighted by coverage; the depth is sample 0's.
// python/weft/reference/ibl_shading.py: dome_blur implements both passes in NumPy.
layout(set = 0, binding = 0) uniform sampler2D domeTex;  // rgb: diffuse light, a: visibility
layout(set = 0, binding = 1) uniform sampler2D depthTex; // the forward pass's depth (perspective)
layout(push_constant) uniform Push { vec4 params; } push; // radius, near, far, tolerance
layout(location = 0) out vec4 outVisDepth;

float viewDepth(ivec2 p) {
    float d = texelFetch(depthTex, p, 0).r;
    float n = push.params.y, f = push.params.z;
    return n * f / (f - d * (f - n));
}

bool surface(ivec2 p) { return texelFetch(depthTex, p, 0).r < 1.0; } // cleared to 1: none

void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    int last = textureSize(domeTex, 0).x - 1;
    if (!surface(c)) {
        outVisDepth = vec4(texelFetch(domeTex, c, 0).a, -1.0, 0.0, 0.0);
        return;
    }
    float zc = viewDepth(c);
    float step = push.params.x / 3.0;
    float sigma = max(push.params.x * 0.5, 1e-6);
    float sum = 0.0, weights = 0.0;
    for (int k = -3; k <= 3; ++k) {
        float o = float(k) * step;
        ivec2 q = ivec2(clamp(c.x + int(floor(o + 0.5)), 0, last), c.y);
        if (!surface(q)) continue;
        float v = texelFetch(domeTex, q, 0).a;
        float dz = (viewDepth(q) - zc) / (push.params.w * zc);
        float w = exp(-o * o / (2.0 * sigma * sigma) - dz * dz);
        sum += w * v;
        weights += w;
    }
    outVisDepth = vec4(sum / weights, zc, 0.0, 0.0);
}
