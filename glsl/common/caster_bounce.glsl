// The light the shadow casters reflect onto the rest of the scene (issue 18): the ground beside
// a sphere, the sphere beside another. bounce.glsl gives each caster the light of the receivers;
// this is the way back. Each caster with a bounce capture stands in as a proxy sphere (centre c,
// radius r; frame.bounceSpheres) whose radiance towards a point p is that of a diffuse sphere:
// the mean over the cap p sees of the light it reflects,
//   L(a) = K_D <E>_a / pi + K_A I_A (1 - covered),   a = (p - c) / |p - c|.
// Seen from afar the cap is the half facing a, and <E>_a, the irradiance averaged over its
// normals with weight n.a / pi, is E convolved once more with the clamped cosine: in SH9 each
// band l times A_l / pi = 1, 2/3, 1/4 (Ramamoorthi & Hanrahan 2001); for a directional light of
// radiance L_i it is the Lambert sphere's phase law L_i 2 / (3 pi) (sin t + (pi - t) cos t), t
// the angle between a and the light. From close by the cap shrinks to the pole facing p (its
// half-angle b has cos b = r / D = s), whose normal is a itself: the band weights go from the
// far values to 1 as the uniform cap means of the bands do, (2 + s) / 3 and
// 1/4 + (3/4) s (1 + s) / 2 (and the phase law to the pole's max(cos t, 0)). So L(a) is one
// SH9 per caster, its bands weighted by s: bounce_radiance.frag sums it once per frame (each
// light shadowed as at the caster's lit pole, its clamped cosine in SH9), and a fragment reads
// nine coefficients per caster instead of the sets and a shadow lookup per light. The sphere
// lights p (normal n) with
// E / pi = L (r / D)^2 cos(theta) while it is wholly above p's horizon (exact for a sphere), and
// with the C1 blend s^2 (h + s)^2 / (4 s) (s = r / D, h = cos theta) while the horizon cuts it.
// Inside a proxy (a concave caster's hollow) its outside is not what p sees: faded out there.
// The proxy's shape is the ellipsoid the caster's bounds hold (half axes a; bounce_points.glsl's
// points lie on it): seen from p along w it stands in as the sphere of its projected area,
// pi r_w^2 = pi a_x a_y a_z |w / a| (exact for a sphere, r_w = r), and p is inside where
// |(c - p) / a| < 1. A cloth draped over a sphere (bounds 1.5 x 0.85 x 1.5 m) no longer reaches
// below its hem to the ground, which the sphere of the RMS half extent did (the ground in its
// contact shadow came out 1.7-2.6x too bright against Mitsuba).
// What the casters hide of the sky is reported to the caller: `hiddenSky`, E / pi of the
// environment's radiance towards them (blurred over their caps), and `covered`, the
// cosine-weighted fraction of p's sky they fill. Without a dome the caller takes them away;
// with one they are a floor under its occlusion (environmentTerms); so a caster never brightens
// its surroundings by light it also blocks. Proxies whose caps overlap as p sees them (a sphere
// under the cloth draped over it, two spheres in a row) fill about the union of their caps: a
// cap gives up its overlap with the largest cap before it (the depth of the two caps' overlap
// over the smaller's diameter, times the smaller's share), and none fills more than the ones
// before it left. Summed instead, the cloth and the sphere under it covered the whole sky of
// the ground at the sphere's foot: under the ambient alone that ground came out at 0.22-0.27
// of Mitsuba's, at 0.7-1.1 with the union. (The overlap with every cap before, kept in arrays,
// scored the same and made lavapipe's forward pass 1.33x slower; this one is within noise.)
// Not counted: what the casters show each other in the captures (one bounce), the caster's
// texture (its K_D stands for its colour). Included by shading.glsl after the shadow lookups.

vec3 casterRadiance(int c, vec3 a, float s) {
    float b[9];
    shBasis9(a, vec3(1.0, (2.0 + s) / 3.0, 0.25 + 0.375 * s * (1.0 + s)), b);
    vec3 radiance = vec3(0.0);
    for (int k = 0; k < 9; ++k) radiance += b[k] * texelFetch(bounceRadiance, ivec2(k, c), 0).rgb;
    return max(radiance, vec3(0.0));
}

// E / pi at p (normal n) from every caster's proxy but `self` (the surface's own capture);
// `hiddenSky` and `covered` as above.
vec3 casterBounce(vec3 p, vec3 n, int self, out vec3 hiddenSky,
                  out float covered) {
    vec3 e = vec3(0.0);
    hiddenSky = vec3(0.0);
    covered = 0.0;
    // no bounce light in this frame, or a capture
    if (!featureOn(FEATURE_BOUNCE) || frame.sky.z < 0.5) return e;
    bool hideSky = frame.environment.x > 0.0;
    vec4 big = vec4(0.0); // the largest cap before: direction, half-angle asin(s) ...
    float bigShare = 0.0; // ... and the share of p's sky it fills alone
    for (int c = 0; c < MAX_BOUNCE_CASTERS; ++c) {
        float r = frame.bounceSpheres[c].w;
        if (r <= 0.0 || c == self) continue;
        vec3 a = max(frame.bounceHalves[c].xyz, vec3(1e-3 * r));
        vec3 d = frame.bounceSpheres[c].xyz - p;
        float inside = length(d / a); // 1 on the ellipsoid
        if (inside <= 0.5) continue;
        float D = length(d);
        vec3 w = d / D;
        float rw = sqrt(a.x * a.y * a.z * length(w / a)); // its projected area's radius
        float s = min(rw / D, 1.0), h = dot(n, w);
        if (h <= -s) continue;
        float f = h >= s ? h * s * s : s * s * (h + s) * (h + s) / (4.0 * s);
        f *= smoothstep(0.5, 1.0, inside);
        float share = f, alpha = asin(s);
        float apart = acos(clamp(dot(w, big.xyz), -1.0, 1.0));
        float depth = (alpha + big.w - apart) / (2.0 * min(alpha, big.w) + 1e-6);
        f -= clamp(depth, 0.0, 1.0) * min(share, bigShare);
        if (alpha > big.w) {
            big = vec4(w, alpha);
            bigShare = share;
        }
        f = clamp(f, 0.0, 1.0 - covered);
        if (f <= 1e-4) continue;
        e += f * casterRadiance(c, -w, s);
        // the sky behind the proxy, blurred over about its cap (half-angle asin s): the
        // roughest level only at contact, so a caster in front of the bright part of a sky
        // hides that part (the ground beside a sphere, away from a bright sky: 5-10% too
        // bright against Mitsuba with the roughest level throughout)
        if (hideSky)
            hiddenSky += f * frame.environment.x *
                         textureLod(environmentMap, w,
                                    frame.environment.y * sqrt(asin(s) / 1.5707963)).rgb;
        covered += f;
    }
    return e;
}
