// Lighting from the scene's environment (SPEC §1.3 Fresnel reflection, §4.4): diffuse
// K_D T E(n) / pi from SH9 irradiance, specular = the GGX-prefiltered environment in
// R = 2(n.v)n - v times Schlick's Fresnel. python/weft/reference/ibl_shading.py evaluates the
// same in NumPy. Included by shading.glsl after frame.glsl.

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

// The environment's contribution at p (normal n, unit view vector v, texture colour T).
vec3 environmentLight(vec3 n, vec3 v, vec3 T, Instance ins) {
    if (frame.environment.x <= 0.0) return vec3(0.0);
    vec3 color = ins.environment.w * ins.kd.rgb * T * environmentIrradiance(n);
    vec3 f0 = ins.environment.rgb;
    if (any(greaterThan(f0, vec3(0.0)))) {
        float ndv = dot(n, v);
        vec3 r = 2.0 * ndv * n - v;
        float lod = environmentRoughness(ins.ks.w) * frame.environment.y;
        vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - clamp(ndv, 0.0, 1.0), 5.0);
        color += fresnel * textureLod(environmentMap, r, lod).rgb * frame.environment.x;
    }
    return color;
}
