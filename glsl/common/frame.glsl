// Per-frame data shared by the scene passes. Must match render/GpuTypes.h.
#extension GL_GOOGLE_include_directive : require

const int MAX_COOKIES = 4;
const int LIGHT_DIRECTIONAL = 0;
const int LIGHT_POINT = 1;
const int LIGHT_SPOT = 2;

struct Light {
    vec4 position;    // xyz: position (point, spot); w: type
    vec4 direction;   // directional: unit vector towards the light; spot: unit axis; w: cookie
    vec4 radiance;    // rgb: colour * intensity; w: first shadow layer or -1
    vec4 attenuation; // k_c, k_l, k_q, radius (> 0: eq. 2.4)
    vec4 cone;        // cos(inner), cos(outer), tan(outer), 0
};

struct ShadowLayer {
    mat4 viewProj;
    vec4 params; // x: normal offset (perspective: per metre), y: perspective, z: near, w: far
};

struct Instance {
    mat4 model;
    mat4 normalMatrix; // inverse transpose of the model matrix (upper 3x3 used)
    vec4 ka;        // w: alpha cutoff (0: opaque)
    vec4 kd;        // w: bits 1 normal map, 2 ambient map, 4 specular from the vertex normal,
                    //    8 gloss in the base texture's alpha, 16 phantom, 32 ambient map is
                    //    radiance
    vec4 ks;        // w: shininess
    vec4 baseColor;
    vec4 environment; // rgb: reflectivity (Fresnel F0), w: environment-diffuse weight
    vec4 maps;      // x: log2(shininess max / shininess), exponent in the specular map's
                    //    alpha; 0: none. y: normal-map scale of x and y. z: bounce capture + 1
                    //    (0: none; bounce.glsl)
};

layout(set = 0, binding = 0) uniform FrameUbo {
    mat4 viewProj;
    vec4 cameraPos;
    vec4 ambient;
    vec4 background;
    vec4 bias;    // x: constant, y: slope, z: max (units of the light's depth range)
    ivec4 counts; // x: lights, y: PCF radius, z: shadow-map size, w: debug light or -1
    vec4 environment;      // x: intensity (0: none), y: last chain level, z: dome lights, w: size
    vec4 environmentSh[9]; // SH9 of E(n) / pi (environment.glsl)
    mat4 view;             // world -> eye (sphere-map lookups)
    vec4 options;  // x: sphere-map lookups, y: last glossy sphere level, z: dome deferred to the
                   // blur pass, w: background image
    vec4 viewport; // xy: 1 / target size
    mat4 inverseViewProj; // clip -> world (the background's view rays)
    vec4 sky;      // x: environment drawn as background, y: its chain level (< 0: radiance cube),
                   // z: bounce light (bounce.glsl) in this frame, w: the dome occludes the
                   // ambient (no environment; RenderSettings::ambientOcclusion)
} frame;

layout(std430, set = 0, binding = 1) readonly buffer Instances { Instance instances[]; };
layout(std430, set = 0, binding = 2) readonly buffer Lights { Light lights[]; };
layout(set = 0, binding = 3) uniform sampler2DArray shadowMaps;
layout(std430, set = 0, binding = 4) readonly buffer ShadowLayers { ShadowLayer shadowLayers[]; };
layout(set = 0, binding = 5) uniform sampler2D cookies[MAX_COOKIES];
layout(set = 0, binding = 6) uniform samplerCube environmentMap; // GGX chain by roughness
layout(set = 0, binding = 10) uniform sampler2D backgroundImage;   // camera image (AR) or black
layout(set = 0, binding = 11) uniform sampler2D sphereIrradiance;  // eye-space sphere maps
layout(set = 0, binding = 12) uniform sampler2D sphereGlossy;      // mips by roughness
layout(set = 0, binding = 13) uniform samplerCube environmentRadiance; // the background's source

layout(push_constant) uniform Push { uint instance; } push;
