// Per-frame data shared by the scene passes: the structs of gpu_types.h (one definition for
// C++ and GLSL) and the set-0 bindings.
#extension GL_GOOGLE_include_directive : require

#include "gpu_types.h"

layout(set = 0, binding = 0) uniform FrameUbo { Frame frame; };

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
// the GGX coat's directional albedo (weft/IblFilter.h coatAlbedo, COAT_* of gpu_types.h)
layout(set = 0, binding = 18) uniform sampler2DArray coatAlbedo;

layout(push_constant) uniform Push { uint instance; } push;

// What the frame may use (specialization constant 0, FEATURE_* of gpu_types.h): a pipeline made
// for a frame without an environment, an ambient dome or bounce light has that code removed when
// lavapipe compiles it, instead of running it under a mask that is false everywhere (which it
// does: those unused terms were a third of the forward pass). The runtime tests stay, so the
// default, every feature, draws exactly what a specialized pipeline draws.
layout(constant_id = 0) const uint kFrameFeatures = 0xFFFFFFFFu;
bool featureOn(uint feature) { return (kFrameFeatures & feature) != 0u; }
// The same for the drawn material (specialization constant 1, Instance::flags.x bits): a
// pipeline for a material without a normal map, a texture, an alpha test, ... has none of
// their code (texture samples under a mask cost lavapipe as much as taken ones).
layout(constant_id = 1) const uint kMaterialFlags = 0xFFFFFFFFu;
