#pragma once
// CPU mirrors of the shader-side structs in glsl/common/frame.glsl (std140 / std430).
#include <glm/glm.hpp>

namespace weft::render {

constexpr int kMaxShadowLayers = 32; // shadow-map layers per frame (a point light takes 6)
constexpr int kMaxCookies = 4;       // distinct spot-light cookie textures per frame

enum GpuLightType : int { kLightDirectional = 0, kLightPoint = 1, kLightSpot = 2 };

struct GpuLight {
    glm::vec4 position;    // xyz: position (point, spot); w: GpuLightType
    glm::vec4 direction;   // directional: unit vector towards the light; spot: unit axis into
                           // the scene; w: cookie slot or -1
    glm::vec4 radiance;    // rgb: colour * intensity; w: first shadow layer or -1
    glm::vec4 attenuation; // k_c, k_l, k_q, radius (> 0: eq. 2.4)
    glm::vec4 cone;        // cos(inner), cos(outer), tan(outer), 0
};

/// One layer of the shadow-map array: the light view it was rendered from.
struct GpuShadowLayer {
    glm::mat4 viewProj;
    glm::vec4 params; // x: normal offset (world units; perspective: per metre of distance),
                      // y: 1 perspective / 0 orthographic, z: near, w: far
};

/// A light of the environment's shadow dome (SPEC §4.5) and its shadow-map layer.
struct GpuDomeLight {
    glm::mat4 viewProj;
    glm::vec4 direction; // xyz: unit vector towards the light, w: normal offset (world units)
    glm::vec4 intensity; // rgb: T_i / pi
};

struct GpuInstance {
    glm::mat4 model;
    glm::mat4 normalMatrix;
    glm::vec4 ka; // w: alpha cutoff (0: opaque)
    glm::vec4 kd; // w: bits 1 normal map, 2 ambient map, 4 specular from the vertex normal,
                  //    8 gloss in the base texture's alpha, 16 phantom, 32 ambient map is radiance
    glm::vec4 ks; // w: shininess
    glm::vec4 baseColor;
    glm::vec4 environment; // rgb: reflectivity (Fresnel F0), w: environment-diffuse weight
    glm::vec4 maps; // x: log2(shininessMax / shininess) with the exponent in the specular map's
                    // alpha, else 0; y: normal-map scale of x and y; z: bounce capture + 1
                    // (0: none; BounceProbes.h); w: unused
};

struct GpuFrame {
    glm::mat4 viewProj;
    glm::vec4 cameraPos;
    glm::vec4 ambient;
    glm::vec4 background;
    glm::vec4 bias;     // x: constant, y: slope, z: max (units of the light's depth range)
    glm::ivec4 counts;  // x: lights, y: PCF radius, z: shadow-map size, w: debug light or -1
    glm::vec4 environment; // x: intensity (0: no environment), y: last level of the chain,
                           // z: dome lights, w: dome shadow-map size
    glm::vec4 environmentSh[9]; // SH9 of E(n) / pi: A_l L_lm / pi (rgb), see environment.glsl
    glm::mat4 view;        // world -> eye (the sphere-map lookups of SPEC §4.4)
    glm::vec4 options;     // x: 1 = sphere-map (eye space) lookups, y: last level of the glossy
                           // sphere map, z: 1 = dome diffuse deferred to the blur pass,
                           // w: 1 = background image
    glm::vec4 viewport;    // xy: 1 / target size in pixels
    glm::mat4 inverseViewProj; // clip -> world (the background's view rays)
    glm::vec4 sky;         // x: 1 = the environment is the background, y: its level in the
                           // glossy chain (< 0: the sharp radiance cube), z: 1 = bounce
                           // light (BounceProbes.h) in this frame, w: 1 = the dome stands for
                           // the ambient's uniform sky (ambient occlusion, DomeShadows.h)
};

/// Instance flags in GpuInstance::kd.w.
enum GpuInstanceFlag : int {
    kFlagNormalMap = 1,
    kFlagAmbientMap = 2,
    kFlagSpecularVertexNormal = 4,
    kFlagGlossInAlpha = 8,
    kFlagPhantom = 16,
    kFlagAmbientRadiance = 32,
};

/// Push constants of the dome-shadow blur (glsl/render/dome_blur.frag).
struct DomeBlurPush {
    glm::vec4 params; // x: radius in pixels, y: camera near, z: camera far, w: depth tolerance
};

/// Push constants of the output pass (glsl/render/output.frag).
struct OutputPush {
    glm::vec4 params; // x: exposure scale 2^EV, y: tone map (weft::ToneMap), zw: unused
};

static_assert(sizeof(GpuLight) == 80, "GpuLight must match frame.glsl");
static_assert(sizeof(GpuShadowLayer) == 80, "GpuShadowLayer must match frame.glsl");
static_assert(sizeof(GpuDomeLight) == 96, "GpuDomeLight must match environment.glsl");
static_assert(sizeof(GpuInstance) == 224, "GpuInstance must match frame.glsl");
static_assert(sizeof(GpuFrame) == 64 + 48 + 32 + 16 + 144 + 64 + 32 + 64 + 16,
              "GpuFrame must match frame.glsl");

} // namespace weft::render
