// The structs the renderer uploads and its scene shaders read, defined once for both: this file
// is valid C++17 (included by cpp/src/render/GpuTypes.h, inside namespace weft::render::gpu)
// and GLSL 450 (included by frame.glsl and environment.glsl). Uniform blocks use std140 and
// buffers std430; every member is a vec4, ivec4, uvec4 or mat4, so both layouts are the C++
// one (GpuTypes.h asserts the sizes). Flags are integer bits, not packed into floats.
#ifndef WEFT_GPU_TYPES_H
#define WEFT_GPU_TYPES_H

#ifdef __cplusplus
#include <cstdint>

#include <glm/glm.hpp>
namespace weft::render::gpu {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = std::uint32_t;
#define WEFT_CONST(type, name, value) constexpr type name = value
#define WEFT_FN inline
#else
#define WEFT_CONST(type, name, value) const type name = value
#define WEFT_FN
#endif

WEFT_CONST(int, MAX_COOKIES, 4);       // distinct spot-light cookie textures per frame
WEFT_CONST(int, MAX_SHADOW_LAYERS, 32); // shadow-map layers per frame (a point light takes 6)
WEFT_CONST(int, MAX_BOUNCE_CASTERS, 8); // casters with a bounce capture (render/BounceProbes.h)
// Points per caster at which its capture is projected (bounce_sh.frag): its centre (0), the
// centres of its bounds' faces (1-6: +x, -x, +y, -y, +z, -z) and its corners (7-14), on the
// ellipsoid its bounds hold; the SH9 sets of caster c are the rows c * BOUNCE_POINTS + point.
WEFT_CONST(int, BOUNCE_POINTS, 15);

// What the forward pass's extra outputs hold where no surface is (the others hold 0): its
// clears (ForwardPasses.cpp) and the background drawn last there (background_main.glsl).
WEFT_CONST(vec4, NO_SURFACE_NORMAL, vec4(0.0f, 0.0f, 0.0f, 1.0f)); // debug normal: not shadowed
WEFT_CONST(vec4, NO_SURFACE_DOME_AUX, vec4(1.0f, 0.0f, 0.0f, 0.0f)); // the proxies' floor 1

// Light::position.w
WEFT_CONST(int, LIGHT_DIRECTIONAL, 0);
WEFT_CONST(int, LIGHT_POINT, 1);
WEFT_CONST(int, LIGHT_SPOT, 2);

// Light groups: the lights of a frame are uploaded sorted by group (Frame.lightStart), so that
// a shader loops over each group with only that group's code (shading.glsl, forEachLight):
// lavapipe runs every branch of a loop body under a mask, so a generic body made an unshadowed
// light pay for every kind of shadow test and the spot lights' cookies.
WEFT_CONST(int, LIGHT_GROUP_DIRECTIONAL, 0);      // no shadow map
WEFT_CONST(int, LIGHT_GROUP_DIRECTIONAL_PCF, 1);  // shadow map, fixed PCF kernel
WEFT_CONST(int, LIGHT_GROUP_DIRECTIONAL_SOFT, 2); // shadow map, PCSS by its angular radius
WEFT_CONST(int, LIGHT_GROUP_POINT, 3);
WEFT_CONST(int, LIGHT_GROUP_POINT_SHADOWED, 4); // six cube-face layers
WEFT_CONST(int, LIGHT_GROUP_SPOT, 5);
WEFT_CONST(int, LIGHT_GROUP_SPOT_SHADOWED, 6);
WEFT_CONST(int, LIGHT_GROUPS, 7);

// The group of a light of kind `type` (LIGHT_*), with or without a shadow map, soft when it is
// a directional light with an angular size (Light::cone.w > 0).
WEFT_FN int lightGroupOf(int type, bool shadowed, bool soft) {
    if (type == LIGHT_DIRECTIONAL)
        return !shadowed ? LIGHT_GROUP_DIRECTIONAL
                         : (soft ? LIGHT_GROUP_DIRECTIONAL_SOFT : LIGHT_GROUP_DIRECTIONAL_PCF);
    if (type == LIGHT_POINT) return shadowed ? LIGHT_GROUP_POINT_SHADOWED : LIGHT_GROUP_POINT;
    return shadowed ? LIGHT_GROUP_SPOT_SHADOWED : LIGHT_GROUP_SPOT;
}

// Instance::flags.x
WEFT_CONST(uint, MAP_NORMAL, 1u);             // tangent-space normal map
WEFT_CONST(uint, MAP_AMBIENT, 2u);            // ambient map replaces I_A
WEFT_CONST(uint, SPECULAR_VERTEX_NORMAL, 4u); // highlight from the vertex normal
WEFT_CONST(uint, GLOSS_IN_ALPHA, 8u);         // the decal's gloss in the base texture's alpha
WEFT_CONST(uint, PHANTOM, 16u);               // shows only the shadows it receives (AR)
WEFT_CONST(uint, AMBIENT_RADIANCE, 32u);      // the ambient map is the ambient term itself
WEFT_CONST(uint, TWO_SIDED, 64u);             // back faces shaded with the flipped normal
WEFT_CONST(uint, MIRRORED, 128u);             // det(model) < 0: front and back swap
WEFT_CONST(uint, DYNAMIC_REFLECTION, 256u);   // reflects the dynamic capture
WEFT_CONST(uint, MAP_BASE, 512u);             // a base texture (else white)
WEFT_CONST(uint, MAP_SPECULAR, 1024u);        // a specular map (else white)
WEFT_CONST(uint, ALPHA_TEST, 2048u);          // alpha cutoff > 0 (ka.w)
WEFT_CONST(uint, SPECULAR_GGX, 4096u);        // a GGX coat (Material::specularModel)
// Not a bit of flags.x: the instance has a bounce capture (flags.y > 0). Only its pipelines
// hold the code that reads one (a receiver's fragments ran the glossy casters' capture lookups
// under a mask: the cloth scene's forward pass 1.5x as long; materialFeatures in FrameData.h)
WEFT_CONST(uint, BOUNCE_CAPTURE, 8192u);
// Nor this: the instance reflects its environment (Instance::environment.rgb, the reflectivity,
// > 0). Only its pipelines hold the reflection's lookups (the demo's matte terrain ran them
// under a mask: 12 ms of lavapipe's forward pass at 1280 x 720)
WEFT_CONST(uint, REFLECTIVE, 16384u);
// the bits above: specialization constant 1 of the forward shader (frame.glsl, kMaterialFlags)
WEFT_CONST(uint, MATERIAL_ALL, 32767u);
// The GGX coat's directional albedo (weft/IblFilter.h coatAlbedo, frame.glsl coatAlbedo): a 2D
// array of COAT_COSINES (sqrt(n.v) from 0 to 1) x COAT_ROUGHNESS (perceptual roughness
// sqrt(alpha)) texels and COAT_F0 layers (sqrt(F0) from 0 to 1), each grid even end to end.
WEFT_CONST(int, COAT_COSINES, 16);
WEFT_CONST(int, COAT_ROUGHNESS, 16);
WEFT_CONST(int, COAT_F0, 12);
// Frame features, specialization constant 0 of the forward shader (frame.glsl, kFrameFeatures)
WEFT_CONST(uint, FEATURE_ENVIRONMENT, 1u);  // an environment, or a dynamic-reflection capture
WEFT_CONST(uint, FEATURE_AMBIENT_SKY, 2u);  // the ambient read as a uniform sky (Frame.ambient.w)
WEFT_CONST(uint, FEATURE_BOUNCE, 4u);       // bounce light (Frame.sky.z)
WEFT_CONST(uint, FEATURE_COOKIES, 8u);      // a spot light with a cookie
// FEATURE_LIGHT_GROUP << g: the frame has lights of group g (LIGHT_GROUP_*)
WEFT_CONST(uint, FEATURE_LIGHT_GROUP, 16u);
// a shadowed directional light without a deep opacity map: the hair shaders need its shadow
// map (hair_lighting.glsl; without this bit they read only the maps)
WEFT_CONST(uint, FEATURE_HAIR_SHADOW_MAPS, 2048u);
// dome lights (Frame.environment.z > 0): their PCSS loop, ~1/4 of the demo's forward pass on
// lavapipe when compiled in but unused
WEFT_CONST(uint, FEATURE_DOME, 4096u);
WEFT_CONST(uint, FEATURE_SPHERE_MAP, 8192u); // the environment as a sphere map (Frame.options.x)
WEFT_CONST(uint, FEATURE_ALL, 16383u);       // every bit above: the generic shaders

struct Light {
    vec4 position;    // xyz: position (point, spot); w: LIGHT_*
    vec4 direction;   // directional: unit vector towards the light; spot: unit axis into the
                      // scene; w: cookie slot or -1
    vec4 radiance;    // rgb: colour * intensity; w: first shadow layer or -1
    vec4 attenuation; // k_c, k_l, k_q, radius (> 0: eq. 2.4)
    vec4 cone;        // spot: cos(inner), cos(outer), tan(outer); directional: w = tan of its
                      // angular radius (0: the fixed PCF kernel)
};

// One layer of the shadow-map array: the light view it was rendered from.
struct ShadowLayer {
    mat4 viewProj;
    vec4 params; // x: normal offset (world units; perspective: per metre of distance),
                 // y: 1 perspective / 0 orthographic, z: near, w: far
};

// A light of the environment's (or the ambient's) shadow dome (SPEC §4.5) and its map layer.
struct DomeLight {
    mat4 viewProj;  // orthographic: rows 0-2 are orthogonal (a rotation times axis scales)
    vec4 direction; // xyz: unit vector towards the light, w: normal offset (world units)
    vec4 intensity; // rgb: T_i / pi, a: tan of the light's angular radius (0: a point light)
};

struct Instance {
    mat4 model;
    mat4 normalMatrix; // inverse transpose of the model matrix (upper 3x3 used)
    vec4 ka;           // w: alpha cutoff (0: opaque)
    vec4 kd;
    vec4 ks;           // w: shininess
    vec4 baseColor;
    vec4 environment;  // rgb: reflectivity (Fresnel F0), w: environment-diffuse weight
    vec4 maps;         // x: log2(shininess max / shininess), the exponent in the specular
                       // map's alpha (0: none); y: normal-map scale of x and y
    uvec4 flags;       // x: MAP_NORMAL ... ALPHA_TEST bits; y: bounce capture + 1 (0: none;
                       // render/BounceProbes.h)
};

// The per-frame uniforms (binding 0 of the scene passes' set 0).
struct Frame {
    mat4 viewProj;
    vec4 cameraPos;
    vec4 ambient;  // rgb: I_A, w: 1 where it reads as a uniform sky (FEATURE_AMBIENT_SKY)
    vec4 background;
    vec4 bias;     // x: constant, y: slope, z: max (units of the light's depth range)
    ivec4 counts;  // x: lights, y: PCF radius, z: shadow-map size, w: debug light or -1
    vec4 environment;      // x: intensity (0: none), y: last chain level, z: dome lights,
                           // w: dome shadow-map size
    vec4 environmentSh[9]; // SH9 of E(n) / pi: A_l L_lm / pi (rgb), see environment.glsl
    mat4 view;             // world -> eye (the sphere-map lookups of SPEC §4.4)
    vec4 options;  // x: sphere-map lookups, y: last glossy sphere level, z: the dome's diffuse
                   // deferred to the blur pass, w: background image (flags: 0 or 1)
    vec4 viewport; // xy: 1 / target size in pixels
    mat4 inverseViewProj; // clip -> world (the background's view rays)
    vec4 sky;      // x: the environment is the background, y: its level in the glossy chain
                   // (< 0: the sharp radiance cube), z: bounce light (BounceProbes.h) in this
                   // frame, w: the dome stands for the ambient's uniform sky (ambient occlusion)
    // The casters with a bounce capture, as the proxy spheres whose light the rest of the scene
    // receives (caster_bounce.glsl): xyz centre, w radius (0: no caster in this slot) ...
    vec4 bounceSpheres[MAX_BOUNCE_CASTERS];
    ivec4 bounceInstances[MAX_BOUNCE_CASTERS / 4]; // ... and their instances, four per vector
    vec4 bounceHalves[MAX_BOUNCE_CASTERS]; // ... and the half extents of their bounds (xyz)
    // The first light of each group g in the lights buffer (LIGHT_GROUP_*) at [g / 4][g % 4];
    // [1][3] = the light count (the end of the last group)
    ivec4 lightStart[2];
};

#ifdef __cplusplus
} // namespace weft::render::gpu
#endif
#undef WEFT_CONST
#undef WEFT_FN
#endif // WEFT_GPU_TYPES_H
