// Lighting from the scene's environment (SPEC §1.3 Fresnel reflection, §4.4): diffuse
// K_D T E(n) / pi from SH9 irradiance, specular = the GGX-prefiltered environment in
// R = 2(n.v)n - v times Schlick's Fresnel. python/weft/reference/ibl_shading.py evaluates the
// same in NumPy. Included by shading.glsl after frame.glsl.

layout(std430, set = 0, binding = 7) readonly buffer DomeLights { DomeLight domeLights[]; };
layout(set = 0, binding = 8) uniform sampler2DArray domeMaps;
layout(set = 0, binding = 9) uniform samplerCube probeMap; // dynamic capture (black while drawn)

// Each dome light stands for the light of its whole cell of the sky, a cone of angular radius a,
// so its shadow is soft: one shadow-map tap per light gives N hard copies of every shadow (the
// seed's ghosting). PCSS (Fernando 2005) per light, for a directional light of angular size a:
// the blockers found within a search disc of radius a_t (z_receiver - z_near) give their mean
// depth z_b; the visibility is the fraction of the disc of radius a_t (z_receiver - z_b) -- the
// penumbra a cone of that angle casts from blockers at z_b -- that is not blocked (PCF), with
// a_t = tan a. Taps lie on a Vogel spiral turned by a hash of the receiver point (and per
// light), so the few taps per light are noise, not banding; the screen-space blur (dome_blur*)
// and the sum over lights average it. Tap depths are compared against the receiver's tangent
// plane (receiver-plane depth), which keeps wide kernels off a flat or convex receiver.
const int kDomeBlockerTaps = 6;
const int kDomePcfTaps = 10;
const float kGoldenAngle = 2.39996323;

// Tap k of n on a Vogel spiral (radius sqrt((k + 0.5) / n), angle k times the golden angle)
// turned by `turn` = (cos, sin) of the spiral's angle. In the unrolled tap loops k and n are
// constants, so the spiral is too, and a spiral costs one cos and one sin instead of one per
// tap: the per-tap trigonometry was ~7 ms of lavapipe's 1280 x 720 demo frame.
vec2 vogelTap(int k, int n, vec2 turn) {
    float rr = sqrt((float(k) + 0.5) / float(n));
    float a = float(k) * kGoldenAngle;
    vec2 d = rr * vec2(cos(a), sin(a));
    return vec2(d.x * turn.x - d.y * turn.y, d.x * turn.y + d.y * turn.x);
}

float domeHash(vec3 p) {
    uvec3 u = floatBitsToUint(p * 1024.0);
    uint h = u.x * 0x8da6b343u ^ u.y * 0xd8163841u ^ u.z * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    return float(h & 0xffffu) / 65536.0;
}

// Depth of dome map `layer` at uv; outside the map (the frustum holds every caster) nothing is.
float domeDepth(vec2 uv, int layer, ivec2 size) {
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return 1.0;
    return texelFetch(domeMaps, ivec3(ivec2(uv * vec2(size)), layer), 0).r;
}

// Interleaved dome lights (Keller & Heidrich 2001, interleaved sampling): a fragment shader
// whose dome goes through the blur pass may set domeFirst to its pixel's place k in its 2 x 2
// block (RenderSettings::domeInterleave); the fragment then evaluates lights k, k + 4, ... with
// weight 4, an unbiased estimate of the whole sum, and dome_gather.frag averages the block's four
// estimates before anything non-linear (the clamps, the multi-bounce fit) is applied.
int domeFirst = 0, domeStride = 1;

// Eq. 2.23 / pi: the irradiance the occluded dome lights would have brought, at p (normal n).
vec3 domeOccluded(vec3 p, vec3 n) {
    vec3 occluded = vec3(0.0);
    float spin = 6.28318531 * domeHash(p);
    for (int i = domeFirst; i < int(frame.environment.z); i += domeStride) {
        DomeLight d = domeLights[i];
        float c = dot(n, d.direction.xyz);
        if (c <= 0.0) continue;
        float sinTheta = sqrt(max(0.0, 1.0 - c * c));
        vec4 clip = d.viewProj * vec4(p + n * (d.direction.w * sinTheta), 1.0);
        vec2 uv = clip.xy * 0.5 + 0.5;
        // Depths beyond the far plane are behind every caster (the frustum is fitted to the
        // casters, and the maps are cleared to 1): compared as 1, sized by their distance.
        float z = clip.z;
        vec3 r0 = vec3(d.viewProj[0][0], d.viewProj[1][0], d.viewProj[2][0]);
        vec3 r1 = vec3(d.viewProj[0][1], d.viewProj[1][1], d.viewProj[2][1]);
        vec3 r2 = vec3(d.viewProj[0][2], d.viewProj[1][2], d.viewProj[2][2]);
        float bias = min(frame.bias.x + frame.bias.y * sinTheta / max(c, 1e-4), frame.bias.z);
        ivec3 size = textureSize(domeMaps, 0);
        float tanA = d.intensity.a;
        if (tanA <= 0.0) { // a point light: one tap
            if (min(z, 1.0) - bias > domeDepth(uv, i, size.xy)) occluded += d.intensity.rgb * c;
            continue;
        }
        // clip-space depth per world unit along the light, uv per world unit across it
        float zPerWorld = length(r2);
        vec2 uvPerWorld = 0.5 * vec2(length(r0), length(r1));
        // receiver plane: with m_k = (row_k . n) / |row_k|^2 (the inverse transpose of an
        // orthogonal-rows matrix applied to n), dz = -(m.x dx + m.y dy) / m.z in clip units
        vec3 m = vec3(dot(r0, n) / dot(r0, r0), dot(r1, n) / dot(r1, r1), dot(r2, n) / dot(r2, r2));
        vec2 slope = clamp(-2.0 * m.xy / max(abs(m.z), 1e-6) * sign(m.z), vec2(-8.0), vec2(8.0));
        float rot = spin + float(i) * kGoldenAngle;
        // blocker search over the widest penumbra any caster (all nearer than z) could cast
        vec2 searchUv = uvPerWorld * (tanA * z / zPerWorld);
        // penumbrae reach past the map's edge by at most the search radius
        vec2 outside = max(-uv, uv - 1.0);
        if (any(greaterThan(outside, searchUv))) continue;
        float blockers = 0.0, blockerZ = 0.0;
        vec2 turn = vec2(cos(rot), sin(rot));
        for (int k = 0; k < kDomeBlockerTaps; ++k) {
            vec2 o = vogelTap(k, kDomeBlockerTaps, turn) * searchUv;
            float b = domeDepth(uv + o, i, size.xy);
            if (min(z + dot(slope, o), 1.0) - bias > b) {
                blockers += 1.0;
                blockerZ += b;
            }
        }
        if (blockers == 0.0) continue;
        blockerZ /= blockers;
        vec2 filterUv = uvPerWorld * (tanA * max(z - blockerZ, 0.0) / zPerWorld);
        // at least a texel wide: the map's own resolution
        filterUv = max(filterUv, vec2(1.0) / vec2(size.xy));
        float hidden = 0.0;
        turn = vec2(cos(rot + 1.3), sin(rot + 1.3));
        for (int k = 0; k < kDomePcfTaps; ++k) {
            vec2 o = vogelTap(k, kDomePcfTaps, turn) * filterUv;
            if (min(z + dot(slope, o), 1.0) - bias > domeDepth(uv + o, i, size.xy)) hidden += 1.0;
        }
        occluded += d.intensity.rgb * c * (hidden / float(kDomePcfTaps));
    }
    return occluded * float(domeStride);
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

// The directional albedo of the GGX coat of perceptual `roughness` and normal-incidence
// reflectance f0 (per channel) towards n.v (weft/IblFilter.h coatAlbedo: the dielectric's
// exact Fresnel, Smith masking): what the split sum weights the prefiltered radiance with. The
// table is bilinear in (sqrt(n.v), roughness) within the two layers around sqrt(f0), and
// linear in f0 between them (the albedo is nearly linear in F0, exactly so with Schlick's
// Fresnel; linear in sqrt(f0) it was 3% high at F0 = 0.04).
vec3 coatReflectance(float ndv, float roughness, vec3 f0) {
    vec2 cells = vec2(float(COAT_COSINES), float(COAT_ROUGHNESS));
    vec2 uv = (vec2(sqrt(clamp(ndv, 0.0, 1.0)), clamp(roughness, 0.0, 1.0)) * (cells - 1.0) + 0.5) /
              cells;
    f0 = clamp(f0, 0.0, 1.0);
    float steps = float(COAT_F0 - 1);
    vec3 below = min(floor(sqrt(f0) * steps), vec3(steps - 1.0));
    vec3 f0Below = below * below / (steps * steps);
    vec3 t = (f0 - f0Below) / ((2.0 * below + 1.0) / (steps * steps));
    vec3 albedo;
    for (int c = 0; c < 3; ++c) {
        float a = textureLod(coatAlbedo, vec3(uv, below[c]), 0.0).r;
        float b = textureLod(coatAlbedo, vec3(uv, below[c] + 1.0), 0.0).r;
        albedo[c] = mix(a, b, t[c]);
    }
    return albedo;
}

// Texture coordinates of world direction d in an eye-space sphere map (SPEC §4.4, the seed's
// path): d goes to eye space, m = normalize(d_eye + A) with A = (0, 0, 1); rows run downwards
// (weft::cubeToSphere). d_eye = -A (straight away from the eye) has no unique point: the rim.
vec2 sphereMapUv(vec3 d) {
    vec3 m = mat3(frame.view) * d + vec3(0.0, 0.0, 1.0);
    float len = length(m);
    m = len > 1e-6 ? m / len : vec3(1.0, 0.0, 0.0);
    return vec2(0.5 + 0.5 * m.x, 0.5 - 0.5 * m.y);
}

// What the environment brings at p (normal n, unit view vector v, texture colour T, base-texture
// alpha `decalAlpha`): the diffuse part before the dome's shadows, the specular part, and the
// fraction of the diffuse light the dome does not occlude (eq. 2.23 as a ratio; 1 without a
// dome). The total is specular + diffuse * visibility; the dome blur multiplies the diffuse part
// with the blurred visibility instead.
struct EnvironmentTerms {
    vec3 diffuse;    // before the dome's shadows
    vec3 diffuseLit; // after them (eq. 2.23, per channel)
    vec3 specular;
    float visibility;
    // the visibility the casters' proxies alone leave (1 without dome lights): the blur pass
    // blurs only the dome's noisy rest, visibility / floorVisibility (shadedColor)
    float floorVisibility;
    // the dome's occluded fraction of the diffuse light, linear (1 - visibility before the
    // clamps; an interleaved estimate where the dome is interleaved)
    float occlusion;
};

// `hidden`: E / pi of the sky the shadow casters' proxy spheres hide from p
// (caster_bounce.glsl). Without dome lights it is what the casters take away; with them it is a
// floor under the dome's occlusion: a dome's few soft directions miss much of what a caster
// hides at contact (the ground at a sphere's foot came out 6-10% too bright against Mitsuba with
// 16 lights), which the proxies have exactly where they are the casters' shapes.
EnvironmentTerms environmentTerms(vec3 p, vec3 n, vec3 v, vec3 T, float decalAlpha, Instance ins,
                                  vec3 hidden) {
    EnvironmentTerms e;
    e.diffuse = e.diffuseLit = vec3(0.0);
    e.specular = vec3(0.0);
    e.visibility = e.floorVisibility = 1.0;
    e.occlusion = 0.0;
    bool probe = hasFlag(ins, DYNAMIC_REFLECTION);
    bool sphere = featureOn(FEATURE_SPHERE_MAP) && frame.options.x > 0.5;
    if (!featureOn(FEATURE_ENVIRONMENT) || (frame.environment.x <= 0.0 && !probe)) return e;
    vec3 irradiance = vec3(0.0), lit = vec3(-1.0);
    if (frame.environment.x > 0.0) {
        irradiance = sphere ? textureLod(sphereIrradiance, sphereMapUv(n), 0.0).rgb *
                                  frame.environment.x
                            : environmentIrradiance(n);
        // the part of the sky the receivers hide from a caster (bounce.glsl)
        int bp = bounceProbe(ins);
        if (bp >= 0)
            irradiance = max(irradiance - bounceIrradiance(bounceRowsAt(bp, p), 1, n), vec3(0.0));
        if (featureOn(FEATURE_DOME) && frame.environment.z > 0.0) {
            vec3 occluded = domeOccluded(p, n) * frame.environment.x;
            lit = max(irradiance - occluded, vec3(0.0));
            vec3 floorLit = max(irradiance - hidden, vec3(0.0));
            lit = min(lit, floorLit);
            float full = dot(irradiance, vec3(0.2126, 0.7152, 0.0722));
            e.visibility = full > 0.0 ? dot(lit, vec3(0.2126, 0.7152, 0.0722)) / full : 1.0;
            e.occlusion = full > 0.0 ? dot(occluded, vec3(0.2126, 0.7152, 0.0722)) / full : 0.0;
            e.floorVisibility =
                full > 0.0 ? dot(floorLit, vec3(0.2126, 0.7152, 0.0722)) / full : 1.0;
        } else {
            irradiance = max(irradiance - hidden, vec3(0.0));
        }
    }
    vec3 diffuse = ins.environment.w * ins.kd.rgb * irradiance;
    vec3 specular = vec3(0.0);
    vec3 f0 = ins.environment.rgb;
    if ((kMaterialFlags & REFLECTIVE) != 0u && any(greaterThan(f0, vec3(0.0)))) {
        float ndv = dot(n, v);
        vec3 r = 2.0 * ndv * n - v;
        float roughness = environmentRoughness(ins.ks.w);
        // the seed's Schlick F(n.v), or a GGX coat's directional albedo (split sum)
        vec3 fresnel = hasFlag(ins, SPECULAR_GGX)
                           ? coatReflectance(ndv, roughness, f0)
                           : f0 + (1.0 - f0) * pow(1.0 - clamp(ndv, 0.0, 1.0), 5.0);
        vec3 radiance;
        if (probe)
            radiance = textureLod(probeMap, r, 0.0).rgb;
        else if (sphere)
            radiance = textureLod(sphereGlossy, sphereMapUv(r), roughness * frame.options.y).rgb *
                       frame.environment.x;
        else
            radiance = textureLod(environmentMap, r, roughness * frame.environment.y).rgb *
                       frame.environment.x;
        // A caster's reflection shows the receivers (the ground) where its bounce capture has
        // them, not the sky they hide: the capture's texel where the reflected ray meets them
        // (bounceHitDirection; the glossy sphere's underside against Mitsuba: -23% -> -10%).
        // Blending it towards the capture's SH9 by the roughness scored a little worse on
        // every reference scene (the spheres' edges FLIP 0.066 / 0.068 against 0.067 / 0.070).
        int bp = bounceProbe(ins);
        if (bp >= 0 && !probe && !sphere) {
            vec4 c = bounceFace(bp, bounceHitDirection(bp, p, r));
            radiance = max(radiance + c.rgb - c.a * radiance, vec3(0.0));
        }
        specular = fresnel * radiance;
    }
    // The seed's decal material keeps its gloss in the base texture's alpha:
    // lighting = lerp(specular, diffuse, alpha), out = lighting * T (SPEC §4.4).
    bool gloss = hasFlag(ins, GLOSS_IN_ALPHA);
    e.diffuse = diffuse * T * (gloss ? decalAlpha : 1.0);
    // Per channel as eq. 2.23 has it (the blur pass uses the scalar visibility).
    e.diffuseLit = lit.x < 0.0 ? e.diffuse : e.diffuse * lit / max(irradiance, vec3(1e-30));
    e.specular = specular * (gloss ? T * (1.0 - decalAlpha) : vec3(1.0));
    return e;
}
