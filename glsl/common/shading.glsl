// Blinn-Phong shading with shadow-mapped directional lights (SPEC §1.3, eq. 2.5, 2.8-2.10;
// §1.5). python/weft/reference/shading.py implements the same equations in NumPy.
#include "frame.glsl"

layout(set = 1, binding = 0) uniform sampler2D baseTexture;

// Fraction of PCF taps that see the light. `lightDepth` returns the receiver's depth.
float shadowVisibility(int layer, vec3 p, vec3 n, float ndl, out float lightDepth) {
    float c = clamp(ndl, -1.0, 1.0);
    float sinTheta = sqrt(max(0.0, 1.0 - c * c));
    vec3 offsetPos = p + n * (frame.normalOffset[layer].x * sinTheta);
    vec4 clip = frame.lightViewProj[layer] * vec4(offsetPos, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    lightDepth = ndc.z;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    if (uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0 || ndc.z > 1.0) return 1.0;
    float bias = min(frame.bias.x + frame.bias.y * sinTheta / max(c, 1e-4), frame.bias.z);
    int size = frame.counts.z;
    int r = frame.counts.y;
    ivec2 texel = ivec2(floor(uv * float(size)));
    float lit = 0.0;
    for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
            ivec2 t = clamp(texel + ivec2(dx, dy), ivec2(0), ivec2(size - 1));
            float stored = texelFetch(shadowMaps, ivec3(t, layer), 0).r;
            lit += (ndc.z - bias <= stored) ? 1.0 : 0.0;
        }
    }
    return lit / float((2 * r + 1) * (2 * r + 1));
}

// T of eq. 2.10: the material's base colour times its texture.
vec3 albedo(vec2 uv, Instance ins) { return ins.baseColor.rgb * texture(baseTexture, uv).rgb; }

// Eq. 2.10 summed over lights. `debugVis`/`debugDepth` report the debug shadow light.
vec3 shade(vec3 p, vec3 n, vec3 T, Instance ins, out float debugVis, out float debugDepth) {
    vec3 v = normalize(frame.cameraPos.xyz - p);
    vec3 color = frame.ambient.rgb * ins.ka.rgb * T;
    debugVis = 1.0;
    debugDepth = 0.0;
    for (int i = 0; i < frame.counts.x; ++i) {
        vec3 l = lights[i].toLight.xyz;
        vec3 L = lights[i].radiance.rgb;
        int layer = int(lights[i].radiance.w);
        float ndl = dot(n, l);
        float vis = 1.0;
        if (layer >= 0) {
            float depth;
            vis = shadowVisibility(layer, p, n, ndl, depth);
            if (layer == frame.counts.w) {
                debugVis = vis;
                debugDepth = depth;
            }
        }
        if (ndl > 0.0) {
            vec3 h = normalize(l + v);
            float s = pow(max(dot(n, h), 0.0), ins.ks.w);
            color += vis * (ndl * L * ins.kd.rgb * T + s * L * ins.ks.rgb);
        }
    }
    return color;
}
