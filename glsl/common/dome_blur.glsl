// The dome's shadows blurred (SPEC §4.5: "the accumulated shadow image is blurred and multiplies
// the diffuse term only"): the visibility over the casters' floor from dome_gather.frag,
// averaged along one axis over 7 taps spread over `radius` pixels, weighted by a Gaussian
// (sigma = radius / 2) and by depth similarity exp(-(dz / (tolerance z))^2) in linear view depth,
// so shadows do not bleed across silhouettes. dome_blur_x.frag does the rows, dome_blur.frag the
// columns of the rows' result. python/weft/reference/ibl_shading.py: dome_blur implements both
// passes in NumPy.
layout(set = 0, binding = 0) uniform sampler2D domeTex;     // rgb: diffuse light over the floor
layout(set = 0, binding = 1) uniform sampler2D visDepthTex; // (visibility, view depth or -1)
layout(push_constant) uniform Push {
    vec4 params; // radius, near, far, tolerance
    vec4 flags;  // x: interleaved dome lights, y: the multi-bounce fit (dome_gather.frag)
} push;

// The visibility at pixel c averaged along `axis`; `centre` is c's (visibility, depth), depth
// < 0 where c holds no surface (then its own visibility, unblurred).
float blurAlong(ivec2 c, ivec2 axis, vec2 centre) {
    if (centre.y < 0.0) return centre.x;
    ivec2 last = textureSize(visDepthTex, 0) - 1;
    float step = push.params.x / 3.0;
    float sigma = max(push.params.x * 0.5, 1e-6);
    float sum = 0.0, weights = 0.0;
    for (int k = -3; k <= 3; ++k) {
        float o = float(k) * step;
        ivec2 q = clamp(c + axis * int(floor(o + 0.5)), ivec2(0), last);
        vec2 s = texelFetch(visDepthTex, q, 0).rg;
        if (s.y < 0.0) continue;
        float dz = (s.y - centre.y) / (push.params.w * centre.y);
        float w = exp(-o * o / (2.0 * sigma * sigma) - dz * dz);
        sum += w * s.x;
        weights += w;
    }
    return sum / weights;
}
