// Hair strands seen from the camera: lines, or ribbons facing the eye (index = 2 point + side).
// With HAIR_OIT defined it also passes the opacity and view depth the OIT weights need.
// With HAIR_AA defined (anti-aliased frames) both are drawn as screen-space strips around the
// strand's centre line, widened by the pixel square's reach across the strand (half a pixel to
// 0.71 of one) on each side so that every pixel the strand touches gets a fragment; the fragment
// turns its distance from the centre line into the fraction of the pixel the strand covers
// (hair_coverage.glsl); at the strand's ends the strip reaches as far beyond the end point and
// the coverage is cut there. The strand's width in pixels is its projected ribbon width, or one
// pixel for lines. With HAIR_AA_CORE as well the strip is
// narrowed to the pixels the strand covers entirely (none for strands under 1 to 1.4 pixels
// wide, by direction).
#include "frame.glsl"
#include "hair_frame.glsl"

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outTangent;
layout(location = 2) out vec3 outColor;
layout(location = 3) flat out uint outStrand;
#ifdef HAIR_OIT
layout(location = 4) out float outAlpha;
layout(location = 5) out float outViewDepth;
#endif
#ifdef HAIR_AA
// x: signed distance from the centre line, y: the strand's width (both in pixels); linear in
// screen space, so interpolated without perspective
layout(location = 6) noperspective out vec2 outStrip;
layout(location = 7) noperspective out vec2 outAcross; // unit screen direction across the strand
// distances (pixels) along the strand from its root and to its tip; large away from the ends
layout(location = 8) noperspective out vec2 outEnds;
#endif

void main() {
    uint index = uint(gl_VertexIndex);
    HairVertex hv = hairVertices[index >> 1];
    mat4 model = hairInstances[push.instance].model;
    vec3 p = (model * vec4(hv.position.xyz, 1.0)).xyz;
    vec3 t = normalize(mat3(model) * hv.tangent.xyz);
    float side = (index & 1u) == 1u ? 0.5 : -0.5;
    // No branch may depend on uniforms alone here: Mesa 22.3's lavapipe then inlines the
    // uniform's value into a fresh copy of this shader at every draw and keeps each copy until
    // the pipeline is destroyed (0.3 MiB a frame; BENCHMARKS.md "reliability"). So the ribbon
    // is always built and lines select zero width.
    bool ribbons = hairFrame.params.x == 1;
    vec3 e = frame.cameraPos.xyz - p;
    vec3 s = cross(t, e); // the ribbon's half-width vector (world)
    if (dot(s, s) <= 1e-12 * dot(e, e))
        s = cross(t, abs(t.y) > 0.99 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0));
    vec3 ribbonS = normalize(s) * (0.5 * hairFrame.cameraForward.w * hv.position.w);
    s = ribbons ? ribbonS : vec3(0.0);
#ifdef HAIR_AA
    vec4 clip = frame.viewProj * vec4(p, 1.0);
    vec2 pixels = 0.5 / frame.viewport.xy; // pixels per NDC unit
    // the strand's direction on screen: d(clip.xy / clip.w) along t (times clip.w^2)
    vec4 clipT = frame.viewProj * vec4(t, 0.0);
    vec2 dir = (clipT.xy * clip.w - clip.xy * clipT.w) * pixels;
    float len = length(dir);
    vec2 n = len > 1e-20 ? vec2(-dir.y, dir.x) / len : vec2(1.0, 0.0);
    // the ribbon's extent across the strand on screen (selected, not branched: see above)
    vec4 clipS = frame.viewProj * vec4(p + s, 1.0);
    float ribbonWidth = 2.0 * abs(dot((clipS.xy / clipS.w - clip.xy / clip.w) * pixels, n));
    float width = ribbons ? ribbonWidth : 1.0;
    // how far the pixel square reaches across the strand from its centre
    float reach = 0.5 * (abs(n.x) + abs(n.y));
#ifdef HAIR_AA_CORE
    float halfDrawn = max(0.5 * width - reach, 0.0); // pixels whose whole square is inside
    float endReach = 0.0;
#else
    float halfDrawn = 0.5 * width + reach; // every pixel the strand touches
    float endReach = reach; // the pixel square reaches as far along the strand as across it
#endif
    // A strand's end vertices move out along it by endReach, so that every pixel an end touches
    // gets a fragment, and the distances from the root and to the tip (0 at the end points,
    // measured to the neighbouring vertex on screen) cut the coverage there.
    uint k = index >> 1, last = uint(hairVertices.length()) - 1u;
    bool root = k == 0u || hairVertices[k - 1u].strand != hv.strand;
    bool tip = k == last || hairVertices[k + 1u].strand != hv.strand;
    bool afterRoot = !root && (k == 1u || hairVertices[k - 2u].strand != hv.strand);
    bool beforeTip = !tip && (k + 1u == last || hairVertices[k + 2u].strand != hv.strand);
    mat4 mvp = frame.viewProj * model;
    vec4 clipPrev = mvp * vec4(hairVertices[root ? k : k - 1u].position.xyz, 1.0);
    vec4 clipNext = mvp * vec4(hairVertices[tip ? k : k + 1u].position.xyz, 1.0);
    vec2 here = clip.xy / clip.w * pixels;
    const float far = 1e4;
    float fromRoot = root ? -endReach
                          : (afterRoot ? distance(here, clipPrev.xy / clipPrev.w * pixels) +
                                             (tip ? endReach : 0.0)
                                       : far);
    float toTip = tip ? -endReach
                      : (beforeTip ? distance(here, clipNext.xy / clipNext.w * pixels) +
                                         (root ? endReach : 0.0)
                                   : far);
    vec2 along = vec2(n.y, -n.x); // unit screen direction root to tip
    float endShift = (tip ? endReach : 0.0) - (root ? endReach : 0.0);
    float signedHalf = side > 0.0 ? halfDrawn : -halfDrawn;
    clip.xy += (n * signedHalf + along * endShift) / pixels * clip.w;
    outStrip = vec2(signedHalf, width);
    outAcross = n;
    outEnds = vec2(fromRoot, toTip);
    outWorldPos = p + 2.0 * side * s; // shaded across the ribbon's true width
    gl_Position = clip;
#else
    p += 2.0 * side * s;
    outWorldPos = p;
    gl_Position = frame.viewProj * vec4(p, 1.0);
#endif
    outTangent = t;
    outColor = hv.color;
#ifdef HAIR_OIT
    outAlpha = hv.tangent.w;
    outViewDepth = dot(outWorldPos - frame.cameraPos.xyz, hairFrame.cameraForward.xyz);
#endif
    outStrand = hv.strand;
}
