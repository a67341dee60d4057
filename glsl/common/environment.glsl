// Lighting from the scene's environment (SPEC §1.3 Fresnel reflection, §4.4): diffuse
// K_D T E(n) / pi from SH9 irradiance, specular = the GGX-prefiltered environment in
// R = 2(n.v)n - v times Schlick's Fresnel. python/weft/reference/ibl_shading.py evaluates the
// same in NumPy. Included by shading.glsl after frame.glsl.

struct DomeLight {
    mat4 viewProj;
    vec4 direction; // xyz: towards the light, w: normal offset (world units)
    vec4 intensity; // rgb: T_i / pi
};
layout(std430, set = 0, binding = 7) readonly buffer DomeLights { DomeLight domeLights[]; };
layout(set = 0, binding = 8) uniform sampler2DArray domeMaps;
layout(set = 0, binding = 9) uniform samplerCube probeMap; // dynamic capture (black while drawn)

// Eq. 2.23 / pi: the irradiance the occluded dome lights would have brought, at p (normal n).
// One tap per map, receiver pushed along n by the normal offset, slope-scaled bias.
vec3 domeOccluded(vec3 p, vec3 n) {
    vec3 occluded = vec3(0.0);
    int size = int(frame.environment.w);
    for (int i = 0; i < int(frame.environment.z); ++i) {
        DomeLight d = domeLights[i];
        float c = dot(n, d.direction.xyz);
        if (c <= 0.0) continue;
        float sinTheta = sqrt(max(0.0, 1.0 - c * c));
        vec4 clip = d.viewProj * vec4(p + n * (d.direction.w * sinTheta), 1.0);
        vec2 uv = clip.xy * 0.5 + 0.5;
        if (uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0 || clip.z > 1.0) continue;
        float bias = min(frame.bias.x + frame.bias.y * sinTheta / max(c, 1e-4), frame.bias.z);
        ivec2 t = clamp(ivec2(floor(uv * float(size))), ivec2(0), ivec2(size - 1));
        if (clip.z - bias > texelFetch(domeMaps, ivec3(t, i), 0).r)
            occluded += d.intensity.rgb * c;
    }
    return occluded;
}

// E(n) / pi times the intensity: the nine coefficients hold A_l L_lm / pi (Ramamoorthi &
// Hanrahan 2001), in the basis order of weft::sh9Basis.
vec3 environmentIrradiance(vec3 n) {
    float b[9] = float[9](0.282095, 0.488603 * n.y, 0.488603 * n.z, 0.488603 * n.x,
                          1.092548 * n.x * n.y, 1.092548 * n.y * n.z,
                          0.315392 * (3.0 * n.z * n.z - 1.0), 1.092548 * n.x * n.z,
                          0.546274 * (n.x * n.x - n.y * n.y));
    vec3 e = vec3(0.0);
    for (int k = 0; k < 9; ++k) e += b[k] * frame.environmentSh[k].rgb;
    return max(e, vec3(0.0)) * frame.environment.x;
}

// Perceptual GGX roughness of a Blinn-Phong exponent: alpha = sqrt(2 / (n + 2)) (the Beckmann
// match of the lobe widths), roughness = sqrt(alpha); the chain's level l holds roughness
// l / (levels - 1).
float environmentRoughness(float shininess) {
    return clamp(sqrt(sqrt(2.0 / (shininess + 2.0))), 0.0, 1.0);
}

// The environment's contribution at p (normal n, unit view vector v, texture colour T); with a
// dome of shadow lights the diffuse part loses what the occluded ones bring (eq. 2.23).
vec3 environmentLight(vec3 p, vec3 n, vec3 v, vec3 T, Instance ins) {
    bool probe = (int(ins.baseColor.w) & 4) != 0;
    if (frame.environment.x <= 0.0 && !probe) return vec3(0.0);
    vec3 color = vec3(0.0);
    if (ins.environment.w > 0.0 && frame.environment.x > 0.0) {
        vec3 irradiance = environmentIrradiance(n);
        if (frame.environment.z > 0.0)
            irradiance = max(irradiance - domeOccluded(p, n) * frame.environment.x, vec3(0.0));
        color = ins.environment.w * ins.kd.rgb * T * irradiance;
    }
    vec3 f0 = ins.environment.rgb;
    if (any(greaterThan(f0, vec3(0.0)))) {
        float ndv = dot(n, v);
        vec3 r = 2.0 * ndv * n - v;
        float lod = environmentRoughness(ins.ks.w) * frame.environment.y;
        vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - clamp(ndv, 0.0, 1.0), 5.0);
        color += fresnel * (probe ? textureLod(probeMap, r, 0.0).rgb
                                  : textureLod(environmentMap, r, lod).rgb * frame.environment.x);
    }
    return color;
}
