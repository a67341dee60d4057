// Radiance of a hair fragment: hairShade() for every light of the frame (SPEC §5.2) times the
// light's incident radiance and visibility - the deep opacity map's exp(-occlusion) for a
// directional light with a DOM (SPEC §5.3), else the ordinary shadow map.
#include "shading.glsl"
#include "hair_frame.glsl"

// The depth of the scene's mesh casters in each DOM's view (the meshes shadow hair too).
layout(set = 3, binding = 1) uniform sampler2DArray hairDomMeshes;

// exp(-occlusion) of DOM slot `slot` at world point p: occlusion interpolated linearly inside
// the layer holding p's depth between the opacity at its start and at its end
// (python/weft/reference/hair_shadow.py occlusion_at); 0 behind a mesh caster (one tap, the
// scene's constant + 45-degree slope bias: a fibre has no normal).
float hairDomTransmittance(int slot, vec3 p) {
    vec4 clip = hairFrame.domViewProj[slot] * vec4(p, 1.0);
    vec2 uv = clip.xy * 0.5 + 0.5;
    if (uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0) return 1.0;
    int size = textureSize(hairDom, 0).x;
    ivec2 texel = clamp(ivec2(floor(uv * float(size))), ivec2(0), ivec2(size - 1));
    float meshBias = min(frame.bias.x + frame.bias.y, frame.bias.z);
    ivec2 meshTexel = min(texel, textureSize(hairDomMeshes, 0).xy - 1); // 1x1 when no mesh casts
    float meshZ = (hairFrame.domMeshViewProj[slot] * vec4(p, 1.0)).z; // same x, y as clip
    if (min(meshZ, 1.0) - meshBias > texelFetch(hairDomMeshes, ivec3(meshTexel, slot), 0).r)
        return 0.0;
    vec4 o = texelFetch(hairDom, ivec3(texel, slot), 0);
    float rel = clip.z - o.a;
    if (rel <= 0.0) return 1.0;
    vec3 b = hairDomBounds(hairFrame.domLayer[slot].x);
    int k = hairDomLayer(rel, b);
    float start = k == 0 ? 0.0 : b[k - 1];
    float t = clamp((rel - start) / (b[k] - start), 0.0, 1.0);
    float before = k == 0 ? 0.0 : o[k - 1];
    return exp(-(before + (o[k] - before) * t));
}

int hairDomSlot(int light) {
    for (int s = 0; s < hairFrame.params.z; ++s)
        if (hairFrame.domLight[s] == light) return s;
    return -1;
}

// The environment's diffuse light on a fibre of tangent t, per unit diffuse colour:
// (1 / pi^2) integral of L(w) sin(t, w) dw, the Kajiya-Kay kernel normalised so that a constant
// environment L gives L (a diffuse fibre in a furnace looks like a Lambertian surface).
// sin(t, w) = sqrt(1 - (t.w)^2) is rotationally symmetric about t, so by Funk-Hecke the integral
// over the SH9 radiance is sum_l Lambda_l sum_m L_lm Y_lm(t), Lambda_l = 2 pi integral over
// [-1, 1] of sqrt(1 - x^2) P_l(x) dx: Lambda_0 = pi^2, Lambda_1 = 0 (odd), Lambda_2 = -pi^2 / 8.
// environmentSh holds A_l L_lm / pi (L_00, 2/3 L_1m, 1/4 L_2m), so the result is
// c_00 Y_00 - (1/2) sum_m c_2m Y_2m(t): a fibre along a bright direction sees it only at grazing.
vec3 hairEnvironmentDiffuse(vec3 t) {
    float y2[5] = float[5](1.092548 * t.x * t.y, 1.092548 * t.y * t.z,
                           0.315392 * (3.0 * t.z * t.z - 1.0), 1.092548 * t.x * t.z,
                           0.546274 * (t.x * t.x - t.y * t.y));
    vec3 e = 0.282095 * frame.environmentSh[0].rgb;
    for (int k = 0; k < 5; ++k) e -= 0.5 * y2[k] * frame.environmentSh[4 + k].rgb;
    return max(e, vec3(0.0)) * frame.environment.x;
}

// Light i (group g) on a fibre: L * visibility * f(t, l, v).
vec3 hairLight(int i, int g, vec3 p, vec3 t, vec3 v, HairShading s, uint strand,
               inout float debugVis) {
    vec3 l;
    vec3 L = incidentRadiance(lights[i], g, p, l);
    float vis = 1.0;
    int slot = hairDomSlot(i);
    if (slot >= 0) {
        vis = hairDomTransmittance(slot, p);
    } else if (lightShadowed(g) &&
               (g > LIGHT_GROUP_DIRECTIONAL_SOFT || featureOn(FEATURE_HAIR_SHADOW_MAPS))) {
        float depth;
        vis = shadowVisibility(lights[i], g, p, l, l, depth); // a fibre has no normal: n = l
    }
    if (i == frame.counts.w) debugVis = vis;
    return vis * L * hairShade(s, t, l, v, strand);
}

// Ambient * diffuse colour + sum over lights of hairLight, plus, in a scene lit by an
// environment, its diffuse light along the fibre (hairEnvironmentDiffuse; the specular lobes
// get no environment light). `debugVis` is the visibility of the frame's debug light
// (frame.counts.w).
vec3 hairRadiance(vec3 p, vec3 t, vec3 color, HairShading s, uint strand, out float debugVis) {
    vec3 v = normalize(frame.cameraPos.xyz - p);
    s.diffuse.rgb *= color;
    vec3 c = frame.ambient.rgb * s.diffuse.rgb;
    c += hairEnvironmentDiffuse(t) * s.diffuse.rgb;
    debugVis = 1.0;
#define HAIR_LIGHT(I, G) c += hairLight(I, G, p, t, v, s, strand, debugVis)
    forEachLight(HAIR_LIGHT)
#undef HAIR_LIGHT
    return c;
}
