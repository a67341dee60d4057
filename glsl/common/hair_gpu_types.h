// The structs the hair passes upload and their shaders read, defined once for both as
// gpu_types.h defines the scene passes' (valid C++17 inside namespace weft::render::gpu, and
// GLSL 450): every member is a vec4, ivec4 or mat4, except HairVertex's colour, a vec3 followed
// by a uint, which std430 and C++ both pack into 16 bytes. cpp/src/render/HairGpuTypes.h and
// cpp/src/render/HairShadingGpu.h name them for the C++ side and assert their sizes.
#ifndef WEFT_HAIR_GPU_TYPES_H
#define WEFT_HAIR_GPU_TYPES_H

#include "gpu_types.h"

#ifdef __cplusplus
namespace weft::render::gpu {
using vec3 = glm::vec3;
#define WEFT_CONST(type, name, value) constexpr type name = value
#else
#define WEFT_CONST(type, name, value) const type name = value
#endif

WEFT_CONST(int, HAIR_MAX_DOMS, 4); // directional lights with a deep opacity map per frame

// HairShading::model.x (weft::HairModel)
WEFT_CONST(int, HAIR_MODEL_KAJIYA_KAY, 0);
WEFT_CONST(int, HAIR_MODEL_MARSCHNER, 1);
WEFT_CONST(int, HAIR_MODEL_SADEGHI, 2);

// A HairMaterial's parameters (packHairShading).
struct HairShading {
    ivec4 model;     // x: HAIR_MODEL_*
    vec4 diffuse;    // rgb: diffuse colour (every model)
    vec4 specular;   // Kajiya-Kay: rgb colour, w: exponent
    vec4 colorR;     // Sadeghi: rgb C_R, w: I_R
    vec4 colorTT;    // Sadeghi: rgb C_TT, w: I_TT
    vec4 colorTRT;   // Sadeghi: rgb C_TRT, w: I_TRT
    vec4 shift;      // alpha_R, alpha_TT, alpha_TRT; w: Marschner eta
    vec4 width;      // beta_R, beta_TT, beta_TRT; w: Sadeghi xi_TT
    vec4 glint;      // Sadeghi: I_g, xi_g, min and max half-angle
    vec4 absorption; // Marschner: sigma_a rgb; w: caustic regularisation width
};

struct HairVertex {
    vec4 position; // xyz object space; w: thickness
    vec4 tangent;  // xyz unit tangent (root to tip); w: opacity alpha = 1 - transparency
    vec3 color;    // linear RGB
    uint strand;   // strand index (Sadeghi's per-strand glint)
};

struct HairInstance {
    mat4 model;
    HairShading shading;
};

// The hair passes' per-frame uniforms (set 2, binding 2).
struct HairFrame {
    vec4 cameraForward;                  // xyz: unit view axis; w: ribbon width per thickness
    ivec4 params;                        // x: ribbons, y: OIT weight (7..10), z: DOMs, w: log
    ivec4 domLight;                      // scene light index of DOM slot i, -1 unused
    mat4 domViewProj[HAIR_MAX_DOMS];     // world -> DOM clip (orthographic, depth [0, 1])
    vec4 domLayer[HAIR_MAX_DOMS];        // x: layer size d in stored-depth units
    mat4 domMeshViewProj[HAIR_MAX_DOMS]; // the same x, y; depth from the casters nearest the
                                         // light to the DOM's far plane (mesh shadows)
};

#ifdef __cplusplus
} // namespace weft::render::gpu
#endif
#undef WEFT_CONST
#endif // WEFT_HAIR_GPU_TYPES_H
