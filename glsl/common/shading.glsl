// Blinn-Phong shading with directional, point and spot lights and their shadow maps
// (SPEC §1.2, §1.3 eq. 2.3-2.5, 2.8-2.10; §1.5). python/weft/reference/shading.py and
// shadow.py implement the same equations in NumPy.
#include "frame.glsl"

bool hasFlag(Instance ins, uint flag) {
    return (kMaterialFlags & flag) != 0u && (ins.flags.x & flag) != 0u;
}

#include "bounce.glsl"
#include "environment.glsl"
#include "multi_bounce.glsl"

layout(set = 1, binding = 0) uniform sampler2D baseTexture;
layout(set = 1, binding = 1) uniform sampler2D normalMap;   // linear, tangent space
layout(set = 1, binding = 2) uniform sampler2D specularMap; // linear, multiplies K_S; alpha:
                                                            // log-encoded exponent (optional)
layout(set = 1, binding = 3) uniform sampler2D ambientMap;  // linear, replaces I_A (or I_A K_A T)


// Depth of a perspective shadow map's NDC depth d as distance along the view axis.
float linearShadowDepth(float d, float zNear, float zFar) {
    return zNear * zFar / (zFar - d * (zFar - zNear));
}

// Layer of a point light's six views (+X, -X, +Y, -Y, +Z, -Z) that sees direction d.
int cubeFace(vec3 d) {
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0 : 1;
    if (a.y >= a.z) return d.y >= 0.0 ? 2 : 3;
    return d.z >= 0.0 ? 4 : 5;
}

// Depth of shadow-map layer `layer` at uv; outside the map nothing is (the views hold every
// caster).
float shadowDepth(vec2 uv, int layer, int size) {
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return 1.0;
    return texelFetch(shadowMaps, ivec3(ivec2(uv * float(size)), layer), 0).r;
}

// The shadow of a directional light of angular radius a (tanA = tan a) from its orthographic
// layer: PCSS (Fernando 2005) as the dome lights' (environment.glsl, domeOccluded) -- blockers
// searched within the widest penumbra, the lit fraction of the disc that the blockers' mean
// depth gives, taps on a Vogel spiral turned per receiver point, depths against the receiver's
// plane -- with more taps, because nothing blurs the result afterwards.
const int kSunBlockerTaps = 8;
const int kSunPcfTaps = 24;
float softShadow(ShadowLayer s, int layer, vec2 uv, float z, float bias, vec3 p, vec3 n,
                 float tanA) {
    vec3 r0 = vec3(s.viewProj[0][0], s.viewProj[1][0], s.viewProj[2][0]);
    vec3 r1 = vec3(s.viewProj[0][1], s.viewProj[1][1], s.viewProj[2][1]);
    vec3 r2 = vec3(s.viewProj[0][2], s.viewProj[1][2], s.viewProj[2][2]);
    float zPerWorld = length(r2);
    vec2 uvPerWorld = 0.5 * vec2(length(r0), length(r1));
    vec3 m = vec3(dot(r0, n) / dot(r0, r0), dot(r1, n) / dot(r1, r1), dot(r2, n) / dot(r2, r2));
    vec2 slope = clamp(-2.0 * m.xy / max(abs(m.z), 1e-6) * sign(m.z), vec2(-8.0), vec2(8.0));
    int size = frame.counts.z;
    float spin = 6.28318531 * domeHash(p);
    vec2 searchUv = uvPerWorld * (tanA * z / zPerWorld);
    float blockers = 0.0, blockerZ = 0.0;
    vec2 turn = vec2(cos(spin), sin(spin));
    for (int k = 0; k < kSunBlockerTaps; ++k) {
        vec2 o = vogelTap(k, kSunBlockerTaps, turn) * searchUv;
        float b = shadowDepth(uv + o, layer, size);
        if (min(z + dot(slope, o), 1.0) - bias > b) {
            blockers += 1.0;
            blockerZ += b;
        }
    }
    if (blockers == 0.0) return 1.0;
    blockerZ /= blockers;
    vec2 filterUv = max(uvPerWorld * (tanA * max(z - blockerZ, 0.0) / zPerWorld),
                        vec2(1.0 / float(size)));
    float lit = 0.0;
    turn = vec2(cos(spin + 1.3), sin(spin + 1.3));
    for (int k = 0; k < kSunPcfTaps; ++k) {
        vec2 o = vogelTap(k, kSunPcfTaps, turn) * filterUv;
        if (min(z + dot(slope, o), 1.0) - bias <= shadowDepth(uv + o, layer, size)) lit += 1.0;
    }
    return lit / float(kSunPcfTaps);
}

// The group of light L (gpu_types.h), as render/FrameData.cpp sorts the lights.
int lightGroup(Light L) {
    return lightGroupOf(int(L.position.w), L.radiance.w >= 0.0, L.cone.w > 0.0);
}

bool lightShadowed(int g) {
    return g == LIGHT_GROUP_DIRECTIONAL_PCF || g == LIGHT_GROUP_DIRECTIONAL_SOFT ||
           g == LIGHT_GROUP_POINT_SHADOWED || g == LIGHT_GROUP_SPOT_SHADOWED;
}

// The pixel's footprint on the surface being shaded: the world-space change of its position
// from one pixel to the next, across (pixelDx) and down (pixelDy). The forward pass sets them
// (forward_main.glsl); shaders without pixels (the hair's lighting, the bounce captures) leave
// them zero.
vec3 pixelDx = vec3(0.0), pixelDy = vec3(0.0);

// The step d (world) from q in shadow layer s as (uv, NDC depth), ndc being q's own.
vec3 shadowFootprint(ShadowLayer s, vec3 q, vec3 d, vec3 ndc) {
    vec4 c = s.viewProj * vec4(q + d, 1.0);
    vec3 e = c.xyz / c.w - ndc;
    return vec3(0.5 * e.xy, e.z);
}

// A receiver's depth z in layer s's map as the PCF test compares it, biased (linear for a
// perspective map), and a stored depth in the same measure.
float receiverDepth(float z, float bias, bool perspective, ShadowLayer s) {
    return perspective ? linearShadowDepth(z, s.params.z, s.params.w) -
                             bias * (s.params.w - s.params.z)
                       : z - bias;
}
float storedDepth(float stored, bool perspective, ShadowLayer s) {
    return perspective ? linearShadowDepth(stored, s.params.z, s.params.w) : stored;
}

// Fraction of the shadow taps of light L (group g, shadowed) that see the light from p.
// `lightDepth` returns the receiver's NDC depth in the layer used. With g a constant (the
// group loops of forEachLight) the other groups' tests are compiled out.
float shadowVisibility(Light L, int g, vec3 p, vec3 n, vec3 l, out float lightDepth) {
    int layer = int(L.radiance.w);
    float c = clamp(dot(n, l), -1.0, 1.0);
    float sinTheta = sqrt(max(0.0, 1.0 - c * c));
    ShadowLayer s = shadowLayers[layer];
    bool perspective = g == LIGHT_GROUP_POINT_SHADOWED || g == LIGHT_GROUP_SPOT_SHADOWED;
    float offset = perspective ? s.params.x * length(L.position.xyz - p) : s.params.x;
    vec3 q = p + n * (offset * sinTheta);
    if (g == LIGHT_GROUP_POINT_SHADOWED) {
        layer += cubeFace(q - L.position.xyz);
        s = shadowLayers[layer];
    }
    vec4 clip = s.viewProj * vec4(q, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    lightDepth = ndc.z;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    if (clip.w <= 0.0 || uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0) return 1.0;
    // The views enclose the shadow casters only: a receiver beyond the far plane is compared
    // as if on it (shadowed where a caster was drawn, lit where the map is empty).
    float z = min(ndc.z, 1.0);
    float bias = min(frame.bias.x + frame.bias.y * sinTheta / max(c, 1e-4), frame.bias.z);
    if (g == LIGHT_GROUP_DIRECTIONAL_SOFT)
        return softShadow(s, layer, uv, ndc.z, bias, p, n, L.cone.w);
    int size = frame.counts.z;
    int r = frame.counts.y;
    // Where a pixel covers more of the map than the kernel (a distant or small frame), its
    // (2r + 1)^2 taps sample the pixel's footprint instead, each against its own depth on the
    // receiver's plane (never deeper than the centre's): the shadow's edge is then filtered over
    // the pixel, as the image's other edges are by MSAA, instead of stair-stepping and
    // flickering at the pixel scale (pixelDx / pixelDy, set by the forward pass; zero
    // elsewhere, which keeps the kernel). The taps span the central half of the pixel: the
    // plane is a poor guess across a whole pixel of a folded cloth, whose folds then shadowed
    // themselves. Cloth scene against Mitsuba (128 x 96, 4096 spp), FLIP whole / objects /
    // edges: 0.0445 / 0.0791 / 0.0762 with the kernel, 0.0438 / 0.0779 / 0.0746 with this (the
    // whole pixel: 0.0437 / 0.0803 / 0.0746).
    vec3 fx = shadowFootprint(s, q, pixelDx, ndc), fy = shadowFootprint(s, q, pixelDy, ndc);
    float kernel = float(2 * r + 1);
    if (max(length(fx.xy), length(fy.xy)) * float(size) > kernel) {
        float lit = 0.0;
        for (int j = -r; j <= r; ++j) {
            for (int i = -r; i <= r; ++i) {
                vec2 ab = 0.5 * vec2(i, j) / kernel; // an N x N grid on the pixel's centre
                vec3 t = vec3(uv, ndc.z) + ab.x * fx + ab.y * fy;
                float rt = receiverDepth(min(min(t.z, ndc.z), 1.0), bias, perspective, s);
                float stored = storedDepth(shadowDepth(t.xy, layer, size), perspective, s);
                lit += (rt <= stored) ? 1.0 : 0.0;
            }
        }
        return lit / (kernel * kernel);
    }
    float receiver = receiverDepth(z, bias, perspective, s);
    ivec2 texel = ivec2(floor(uv * float(size)));
    float lit = 0.0;
    for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
            ivec2 t = clamp(texel + ivec2(dx, dy), ivec2(0), ivec2(size - 1));
            float stored = texelFetch(shadowMaps, ivec3(t, layer), 0).r;
            lit += (receiver <= storedDepth(stored, perspective, s)) ? 1.0 : 0.0;
        }
    }
    return lit / float((2 * r + 1) * (2 * r + 1));
}

// The cookie frame of a spot light: `right` and `up` span its texture.
void spotBasis(vec3 axis, out vec3 right, out vec3 up) {
    vec3 ref = abs(axis.y) > 0.99 ? vec3(0.0, 0.0, 1.0) : vec3(0.0, 1.0, 0.0);
    right = normalize(cross(axis, ref));
    up = cross(right, axis);
}

// Cookie slot `slot` at uv (bilinear, level 0). Constant indices only: lavapipe's LLVM
// miscompiles (crashes on) a sampler array indexed in a loop.
vec3 cookieSample(int slot, vec2 uv) {
    if (slot == 0) return textureLod(cookies[0], uv, 0.0).rgb;
    if (slot == 1) return textureLod(cookies[1], uv, 0.0).rgb;
    if (slot == 2) return textureLod(cookies[2], uv, 0.0).rgb;
    return textureLod(cookies[3], uv, 0.0).rgb;
}

// Unit vector l towards light L (group g) from p, and the radiance arriving there: colour *
// intensity times the distance attenuation a (eq. 2.3 / 2.4), the spot cone and the cookie.
vec3 incidentRadiance(Light L, int g, vec3 p, out vec3 l) {
    if (g <= LIGHT_GROUP_DIRECTIONAL_SOFT) {
        l = L.direction.xyz;
        return L.radiance.rgb;
    }
    vec3 d = L.position.xyz - p;
    float dist = length(d);
    l = d / max(dist, 1e-20);
    vec4 k = L.attenuation;
    float a = k.w > 0.0 ? max(0.0, 1.0 - dist * dist / (k.w * k.w))
                        : 1.0 / (k.x + k.y * dist + k.z * dist * dist);
    vec3 radiance = L.radiance.rgb * a;
    if (g >= LIGHT_GROUP_SPOT) {
        vec3 axis = L.direction.xyz;
        float cosAngle = dot(-l, axis);
        radiance *= smoothstep(L.cone.y, L.cone.x, cosAngle);
        int cookie = int(L.direction.w);
        if (featureOn(FEATURE_COOKIES) && cookie >= 0 && cosAngle > 0.0) {
            vec3 right, up;
            spotBasis(axis, right, up);
            vec3 q = p - L.position.xyz;
            float z = dot(q, axis) * L.cone.z;
            vec2 uv = 0.5 + 0.5 * vec2(dot(q, right), -dot(q, up)) / z;
            radiance *= cookieSample(cookie, uv);
        }
    }
    return radiance;
}

// forEachLight(BODY): BODY(i, g) for every light i of the frame, g its group. A pipeline
// specialized to a frame (kFrameFeatures: the groups present) loops over each group present
// with g a constant, so each loop holds only its group's code; the generic pipeline (every
// feature bit) loops over all lights and finds each one's group.
#define LIGHT_GROUP_LOOP(BODY, G)                                                              \
    if (featureOn(FEATURE_LIGHT_GROUP << G))                                                   \
        for (int i = frame.lightStart[G / 4][G % 4];                                           \
             i < frame.lightStart[(G + 1) / 4][(G + 1) % 4]; ++i)                              \
            BODY(i, G);
#define forEachLight(BODY)                                                                     \
    if ((kFrameFeatures & FEATURE_ALL) == FEATURE_ALL) {                                       \
        for (int i = 0; i < frame.counts.x; ++i) BODY(i, lightGroup(lights[i]));               \
    } else {                                                                                   \
        LIGHT_GROUP_LOOP(BODY, 0)                                                              \
        LIGHT_GROUP_LOOP(BODY, 1)                                                              \
        LIGHT_GROUP_LOOP(BODY, 2)                                                              \
        LIGHT_GROUP_LOOP(BODY, 3)                                                              \
        LIGHT_GROUP_LOOP(BODY, 4)                                                              \
        LIGHT_GROUP_LOOP(BODY, 5)                                                              \
        LIGHT_GROUP_LOOP(BODY, 6)                                                              \
    }

// Alpha test (SPEC §1.5): true when the fragment is a hole.
bool alphaDiscarded(vec2 uv, Instance ins) {
    return hasFlag(ins, ALPHA_TEST) && texture(baseTexture, uv).a < ins.ka.w;
}

// What eq. 2.10 needs at a fragment: position, shading normal n (normal-mapped, eq. 2.11-2.12),
// the normal of the specular term (n, or the vertex normal for n_s = (0, 0, 1), eq. 4.30),
// T, K_S, the exponent and the ambient I_A (the scene's, or the material's ambient map; with
// AMBIENT_RADIANCE the map is the ambient term itself, before K_A).
struct Surface {
    vec3 p;
    vec3 n;
    vec3 ns;
    vec3 T;
    vec3 ks;
    float shininess;
    vec3 ambient;
    float alpha; // the base texture's alpha (the decal's gloss with GLOSS_IN_ALPHA)
};

// The shading normal: the interpolated vertex normal, perturbed by the tangent-space normal
// map (eq. 2.11: m = texel * 2 - 1, x and y times Material::normalScale as glTF's
// normalTexture.scale; eq. 2.12: the frame t, b = w (n x t), n). `vertexOut` returns the
// (possibly flipped) vertex normal.
vec3 shadingNormal(vec3 vertexNormal, vec4 tangent, vec2 uv, Instance ins, bool frontFacing,
                   out vec3 vertexOut) {
    vec3 n = normalize(vertexNormal);
    // Two-sided: the back face is shaded with the flipped normal; a mirroring transform
    // reverses which side the rasteriser calls front.
    if (hasFlag(ins, TWO_SIDED) && frontFacing == hasFlag(ins, MIRRORED)) {
        n = -n;
        tangent.w = -tangent.w;
    }
    vertexOut = n;
    if (!hasFlag(ins, MAP_NORMAL)) return n;
    vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
    float tl = length(t);
    if (tl < 1e-12) return n;
    t /= tl;
    vec3 b = tangent.w * cross(n, t);
    vec3 m = (texture(normalMap, uv).rgb * 2.0 - 1.0) * vec3(ins.maps.yy, 1.0);
    return normalize(t * m.x + b * m.y + n * m.z);
}

Surface surfaceAt(vec3 p, vec3 vertexNormal, vec4 tangent, vec2 uv, Instance ins,
                  bool frontFacing) {
    Surface s;
    s.p = p;
    vec3 vertexN;
    s.n = shadingNormal(vertexNormal, tangent, uv, ins, frontFacing, vertexN);
    s.ns = hasFlag(ins, SPECULAR_VERTEX_NORMAL) ? vertexN : s.n;
    vec4 base = hasFlag(ins, MAP_BASE) ? texture(baseTexture, uv) : vec4(1.0);
    s.T = ins.baseColor.rgb * base.rgb;
    s.alpha = base.a;
    // K_S times the specular map; a fitted BTF's per-texel exponent is in the map's alpha,
    // e = shininess * 2^(alpha * log2(max / shininess)) (Material::shininessMax)
    vec4 spec = hasFlag(ins, MAP_SPECULAR) ? texture(specularMap, uv) : vec4(1.0);
    s.ks = ins.ks.rgb * spec.rgb;
    s.shininess = ins.maps.x > 0.0 ? ins.ks.w * exp2(spec.a * ins.maps.x) : ins.ks.w;
    s.ambient = hasFlag(ins, MAP_AMBIENT) ? texture(ambientMap, uv).rgb : frame.ambient.rgb;
    return s;
}

#include "caster_bounce.glsl"

// The terms of eq. 2.10 summed over lights, plus the environment's (environment.glsl).
struct Shading {
    vec3 ambient;           // I_A K_A T (less what receivers hide from a caster: bounce.glsl)
    float ambientVisibility; // the part of the ambient's sky no caster occludes (ambient dome)
    float ambientFloor;     // ... the part the casters' proxies alone leave (unblurred)
    float ambientFloorLinear; // ... that part before the multi-bounce fit
    float ambientOccluded;  // the dome's occluded part of that sky, linear (before any clamp)
    float ambientRho;       // the albedo of the multi-bounce fit
    vec3 bounce;            // light bounced off receivers and casters (caster_bounce.glsl)
    vec3 diffuse;           // direct diffuse, shadows applied
    vec3 diffuseUnshadowed; // direct diffuse without shadows (phantoms' reference)
    vec3 specular;          // direct specular, shadows applied
    vec3 skySpecular;       // the ambient's sky reflected (only where it stands for a sky),
                            // occluded as the ambient (shadedColor)
    EnvironmentTerms environment;
};

// F0 of the material's GGX coat (Material::specularModel, skyReflection): the reflectivity, else
// 8 K_S / (s + 2), the F0 whose highlight peak at normal incidence is the Blinn-Phong one's K_S
// (and whose lobe reflects K_S 8 / (s + 2) of a uniform sky at normal view).
vec3 coatF0(Surface sf, Instance ins) {
    return any(greaterThan(ins.environment.rgb, vec3(0.0))) ? ins.environment.rgb
                                                            : sf.ks * (8.0 / (sf.shininess + 2.0));
}

// Smith's G1 of GGX with alpha^2 = a2 at cos c (Walter et al. 2007, eq. 34).
float smithG1(float c, float a2) {
    return 2.0 / (1.0 + sqrt(1.0 + a2 * (1.0 / (c * c) - 1.0)));
}

// The unpolarised Fresnel reflectance at cos c of the dielectric whose normal-incidence
// reflectance is f0 (relative IOR eta = (1 + sqrt f0) / (1 - sqrt f0), f0 < 1); Walter et al.
// 2007, eq. 22. Schlick's approximation is ~20% low at 60 degrees for f0 = 0.04.
vec3 dielectricFresnel(float c, vec3 f0) {
    vec3 r = sqrt(clamp(f0, 0.0, 0.999));
    vec3 eta = (1.0 + r) / (1.0 - r);
    vec3 g = sqrt(eta * eta - 1.0 + c * c);
    vec3 a = (g - c) / (g + c), b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

// The highlight of a light of radiance 1 from l, seen from v: the seed's K_S (n.h)^s, or with
// SPECULAR_GGX the GGX lobe of the environment reflection (Material.h SpecularModel::Ggx):
// pi (n.l) F D G / (4 (n.l)(n.v)) (weft's lights bring the irradiance pi L), D of
// alpha^2 = 2 / (s + 2), Smith's separable G1 (Walter et al. 2007, eqs. 33-34), the dielectric's
// F. Against Mitsuba's GGX coat the Blinn-Phong lobe, matched at its peak, lacks the tail: a
// glossy ground under a sun came out ~1% dark, and the cloth scene's FLIP 0.044 against 0.038.
vec3 highlight(Surface sf, Instance ins, vec3 l, vec3 v) {
    vec3 h = normalize(l + v);
    float nh = max(dot(sf.ns, h), 0.0);
    if (!hasFlag(ins, SPECULAR_GGX)) return pow(nh, sf.shininess) * sf.ks;
    vec3 f0 = coatF0(sf, ins);
    if (!any(greaterThan(f0, vec3(0.0)))) return vec3(0.0); // no coat: Schlick's rim is not one
    float a2 = 2.0 / (sf.shininess + 2.0);
    float nl = max(dot(sf.ns, l), 1e-4), nv = max(dot(sf.ns, v), 1e-4);
    float q = nh * nh * (a2 - 1.0) + 1.0;
    vec3 fresnel = dielectricFresnel(clamp(dot(v, h), 0.0, 1.0), f0);
    return fresnel * (a2 * smithG1(nl, a2) * smithG1(nv, a2) / (4.0 * q * q * nv));
}

// Light i (group g) on the surface: eq. 2.10's diffuse and specular terms, shadowed.
void shadeLight(int i, int g, Surface sf, Instance ins, vec3 v, inout Shading sh,
                inout float debugVis, inout float debugDepth) {
    vec3 l;
    vec3 L = incidentRadiance(lights[i], g, sf.p, l);
    float ndl = dot(sf.n, l);
    float vis = 1.0;
    if (lightShadowed(g)) {
        float depth;
        vis = shadowVisibility(lights[i], g, sf.p, sf.n, l, depth);
        if (i == frame.counts.w) {
            debugVis = vis;
            debugDepth = depth;
        }
    }
    if (ndl > 0.0) {
        vec3 d = ndl * L * ins.kd.rgb * sf.T;
        sh.diffuseUnshadowed += d;
        sh.diffuse += vis * d;
        sh.specular += vis * L * highlight(sf, ins, l, v);
    }
}

// A sky reflects as well as lights: the ambient's uniform sky reflected, I_A A(n.v), A the
// coat's directional albedo (coatReflectance); `dfg` returns that weight. (Karis's analytic fit
// of it, with Schlick's Fresnel, left a lone glossy ground ~1% dark against Mitsuba.)
vec3 skyReflection(Surface sf, Instance ins, float ndv, out vec3 dfg) {
    vec3 f0 = coatF0(sf, ins);
    // a matte surface has no lobe to reflect with
    dfg = any(greaterThan(f0, vec3(0.0)))
              ? coatReflectance(ndv, environmentRoughness(sf.shininess), f0)
              : vec3(0.0);
    return sf.ambient * dfg;
}

// `debugVis`/`debugDepth` report the debug light's shadow test.
Shading shade(Surface sf, Instance ins, out float debugVis, out float debugDepth) {
    vec3 p = sf.p, n = sf.n;
    vec3 v = normalize(frame.cameraPos.xyz - p);
    Shading sh;
    sh.ambient = sf.ambient * ins.ka.rgb * (hasFlag(ins, AMBIENT_RADIANCE) ? vec3(1.0) : sf.T);
    sh.diffuse = sh.diffuseUnshadowed = sh.specular = sh.bounce = sh.skySpecular = vec3(0.0);
    // A scene without an environment reads its ambient as a uniform sky of radiance 1 times
    // I_A; its dome (frame.sky.w) gives the fraction of that sky's light that reaches p. The sky
    // an occluder hides is partly replaced by the light the occluder reflects, which nothing
    // here traces: Jimenez et al. 2016 ("Practical real-time strategies for accurate indirect
    // occlusion", eq. 10) fit that multi-bounce visibility as a cubic in the visibility v whose
    // coefficients depend on the albedo rho around p (taken as the surface's own).
    sh.ambientVisibility = sh.ambientFloor = sh.ambientFloorLinear = 1.0;
    sh.ambientOccluded = sh.ambientRho = 0.0;
    float ndv = clamp(dot(n, v), 0.0, 1.0);
    vec3 dfg = vec3(0.0);
    // The casters' light (caster_bounce.glsl) and what their proxies cover of p's sky
    int bp = bounceProbe(ins);
    float casterCovered;
    vec3 hiddenSky;
    sh.bounce = casterBounce(p, n, bp, hiddenSky, casterCovered) * ins.kd.rgb * sf.T;
    if (featureOn(FEATURE_AMBIENT_SKY) && frame.ambient.w > 0.5) {
        sh.skySpecular = skyReflection(sf, ins, ndv, dfg);
        if (featureOn(FEATURE_DOME) && frame.sky.w > 0.5) { // a dome occludes the sky
            // the proxies' cover is a floor under the dome's occlusion (see environmentTerms)
            float f = 1.0 - casterCovered;
            float o = dot(domeOccluded(p, n), vec3(0.2126, 0.7152, 0.0722));
            float rho = clamp(dot(ins.kd.rgb * sf.T, vec3(0.2126, 0.7152, 0.0722)), 0.0, 1.0);
            sh.ambientVisibility = multiBounceVisibility(clamp(1.0 - o, 0.0, f), rho);
            sh.ambientFloor = multiBounceVisibility(f, rho);
            sh.ambientFloorLinear = f;
            sh.ambientOccluded = o;
            sh.ambientRho = rho;
        }
        // A caster reflects the receivers where its bounce capture has them, in place of the
        // sky they hide: the capture's texel where the reflected ray meets them. Not occluded
        // by the dome (the receivers are not its sky). Without it the sphere under the draped
        // cloth was 12% too dark on its unlit side against Mitsuba (with a Lambertian sphere
        // both agree to 0.2%): it reflects the sunlit ground. Blended towards the capture's SH9
        // by the roughness it scored a little worse on that scene (edges FLIP 0.079 against
        // 0.076) and made lavapipe's forward pass 4% longer (environmentTerms reflects it alike
        // under an environment).
        if (bp >= 0 && any(greaterThan(dfg, vec3(0.0)))) {
            vec4 c = bounceFace(bp, bounceHitDirection(bp, p, reflect(-v, n)));
            sh.skySpecular *= 1.0 - clamp(c.a, 0.0, 1.0);
            sh.specular = dfg * c.rgb;
        }
    }
    debugVis = 1.0;
    debugDepth = 0.0;
#define SHADE_LIGHT(I, G) shadeLight(I, G, sf, ins, v, sh, debugVis, debugDepth)
    forEachLight(SHADE_LIGHT)
#undef SHADE_LIGHT
    sh.environment = environmentTerms(p, n, v, sf.T, sf.alpha, ins, hiddenSky);
    // One bounce (bounce.glsl): the receivers keep the ambient out of the solid angle they
    // cover and send their own radiance instead, as diffuse light not darkened by the dome.
    if (bp >= 0) {
        BounceRows rows = bounceRowsAt(bp, p);
        float covered = min(bounceIrradiance(rows, 2, n).x, 1.0);
        sh.ambient *= 1.0 - covered;
        sh.bounce += bounceIrradiance(rows, 0, n) * ins.kd.rgb * sf.T;
    }
    // an ambient no dome occludes loses what the casters' proxies cover
    if (frame.sky.w <= 0.5) sh.ambient *= 1.0 - casterCovered;
    return sh;
}

// The colour of a shaded fragment. With the dome's diffuse deferred to the blur pass
// (frame.options.z), `dome` receives that part before the dome's shadows but after the casters'
// proxies' floor (rgb), and the dome's linear occlusion (a); `domeAux` the floor before the
// multi-bounce fit and the fit's albedo. The gather pass (dome_gather.frag) turns them into the
// visibility over the floor that the blur averages, and the colour leaves the part out. The part
// is the environment's diffuse light, or the ambient when the dome stands for the ambient's sky
// (frame.sky.w). A phantom (SPEC §4.5, AR) shows the background image darkened by the shadows it
// receives: background * lit / unlit diffuse light (differential rendering of a diffuse stand-in).
vec3 shadedColor(Shading sh, Instance ins, out vec4 dome, out vec2 domeAux) {
    bool deferDome = frame.options.z > 0.5;
    bool ambientDome = frame.sky.w > 0.5;
    EnvironmentTerms e = sh.environment;
    // what the dome darkens, before (domed) and after (domedLit) its shadows; the rest (direct).
    // A phantom, a diffuse stand-in, reflects no sky.
    bool phantom = hasFlag(ins, PHANTOM);
    vec3 sky = sh.ambient + (phantom ? vec3(0.0) : sh.skySpecular); // the ambient's sky's light
    vec3 domed = ambientDome ? sky : e.diffuse;
    vec3 domedLit = ambientDome ? domed * sh.ambientVisibility : e.diffuseLit;
    vec3 direct = (ambientDome ? e.diffuseLit : sky) + sh.diffuse + sh.bounce;
    // the blur pass gets the dome's rest over the proxies' floor, which is exact and noise-free
    // where it applies (a contact shadow kept sharp)
    float floorVisibility = ambientDome ? sh.ambientFloor : e.floorVisibility;
    domeAux = ambientDome ? vec2(sh.ambientFloorLinear, sh.ambientRho)
                          : vec2(e.floorVisibility, 0.0);
    float occlusion = ambientDome ? sh.ambientOccluded : e.occlusion;
    if (phantom) {
        vec3 unlit = max(sh.ambient + sh.diffuseUnshadowed + e.diffuse, vec3(1e-30));
        vec3 bg = frame.options.w > 0.5
                      ? textureLod(backgroundImage, gl_FragCoord.xy * frame.viewport.xy, 0.0).rgb
                      : frame.background.rgb;
        dome = vec4(bg * domed / unlit * floorVisibility, occlusion);
        return bg * (deferDome ? direct : direct + domedLit) / unlit;
    }
    dome = vec4(domed * floorVisibility, occlusion);
    return direct + sh.specular + e.specular + (deferDome ? vec3(0.0) : domedLit);
}
