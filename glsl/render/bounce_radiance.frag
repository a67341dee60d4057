#version 450
// The radiance each shadow caster sends out as the proxy sphere of caster_bounce.glsl, in SH9:
// fragment (k, c) writes coefficient R_k of caster c, so that towards direction a (from the
// caster's centre, its cap's band weights w_l as caster_bounce.glsl has them)
//   L(a) = sum_k w_l(k) Y_k(a) R_k,
//   R_k = K_D (B0_k + T_E (S_k I_E - B1_k)) + K_A I_A (delta_k0 / Y_0 - B2_k)
//         + sum_i v_i L_i K_D A_l Y_k(l_i),
// with B0..B2 the caster's bounce sets over its surface (surfaceSets below; bounce_sh.frag,
// E / pi convention), S the environment's
// SH9 (intensity I_E, the caster's environment scale T_E), the ambient term only where no
// ambient dome occludes it, v_i light i's shadow visibility at the caster's lit pole and
// A_l = pi, 2 pi / 3, pi / 4: the clamped cosine max(a.l, 0) is sum_k A_l Y_k(l) Y_k(a), so the
// far band weights (A_l / pi) give the Lambert sphere's phase law and the near ones (1) the
// pole's cosine. Computed every frame with bounce probes (a few dozen fragments).
#include "shading.glsl"

layout(location = 0) out vec4 outRadiance;

// Coefficient k of the caster's three sets over its surface: the irradiance each point of
// its surface gets (towards direction a from the centre, normal a: the points around a,
// bounce.glsl) projected onto SH9 over a, by a Fibonacci quadrature (the centre's own sets
// would light the ground under a sphere with what the centre sees, not the sphere's lower side).
const int kQuadrature = 128;
void surfaceSets(int c, int k, out vec3 e0, out vec3 e1, out float e2) {
    e0 = e1 = vec3(0.0);
    e2 = 0.0;
    for (int i = 0; i < kQuadrature; ++i) {
        float z = 1.0 - (2.0 * float(i) + 1.0) / float(kQuadrature);
        float rho = sqrt(max(0.0, 1.0 - z * z)), phi = float(i) * kGoldenAngle;
        vec3 a = vec3(rho * cos(phi), rho * sin(phi), z);
        BounceRows rows;
        ivec3 points;
        vec3 weights;
        bouncePointsAround(a, points, weights);
        rows.rows = ivec4(c * BOUNCE_POINTS) + ivec4(0, points);
        rows.weights = vec4(0.0, weights);
        float b[9];
        shBasis9(a, vec3(1.0), b);
        e0 += b[k] * bounceSet(rows, 0, a, vec3(1.0));
        e1 += b[k] * bounceSet(rows, 1, a, vec3(1.0));
        e2 += b[k] * bounceSet(rows, 2, a, vec3(1.0)).x;
    }
    float dw = 4.0 * 3.14159265 / float(kQuadrature);
    e0 *= dw;
    e1 *= dw;
    e2 *= dw;
}

void main() {
    ivec2 at = ivec2(gl_FragCoord.xy);
    int k = at.x, c = at.y;
    Instance ci = instances[frame.bounceInstances[c / 4][c % 4]];
    vec3 centre = frame.bounceSpheres[c].xyz;
    float r = frame.bounceSpheres[c].w;
    vec3 e, hidden;
    float covered;
    surfaceSets(c, k, e, hidden, covered);
    if (frame.environment.x > 0.0)
        e += ci.environment.w * (frame.environmentSh[k].rgb * frame.environment.x - hidden);
    vec3 radiance = ci.kd.rgb * e;
    // the ambient's reflection: the multi-bounce fit of the ambient occlusion already has it
    if (frame.sky.w <= 0.5)
        radiance += frame.ambient.rgb * ci.ka.rgb * ((k == 0 ? 1.0 / 0.282095 : 0.0) - covered);
    float band = k == 0 ? 3.14159265 : k < 4 ? 2.09439510 : 0.78539816;
    for (int i = 0; i < frame.counts.x; ++i) { // a few dozen fragments: one generic loop
        int g = lightGroup(lights[i]);
        vec3 l;
        vec3 L = incidentRadiance(lights[i], g, centre, l);
        float vis = 1.0, depth;
        if (lightShadowed(g)) vis = shadowVisibility(lights[i], g, centre + l * r, l, l, depth);
        float b[9];
        shBasis9(l, vec3(1.0), b);
        radiance += vis * L * ci.kd.rgb * band * b[k];
    }
    outRadiance = vec4(radiance, 0.0);
}
