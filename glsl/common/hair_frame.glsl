// Data of the hair passes (sets 2 and 3; sets 0 and 1 are the scene's frame and material sets).
// Must match cpp/src/render/HairGpuTypes.h. An index of a hair draw is 2 * point + side: lines
// use side 0, ribbons expand side 0 / 1 to the - / + edge.
#ifndef WEFT_HAIR_FRAME_GLSL
#define WEFT_HAIR_FRAME_GLSL
#include "hair_shading.glsl"

const int HAIR_MAX_DOMS = 4;

struct HairVertex {
    vec4 position; // xyz object space; w: thickness
    vec4 tangent;  // xyz unit tangent; w: opacity alpha
    vec3 color;
    uint strand;
};

struct HairInstance {
    mat4 model;
    HairShading shading;
};

layout(std430, set = 2, binding = 0) readonly buffer HairVertices { HairVertex hairVertices[]; };
layout(std430, set = 2, binding = 1) readonly buffer HairInstances {
    HairInstance hairInstances[];
};
layout(set = 2, binding = 2) uniform HairFrameUbo {
    vec4 cameraForward;                 // xyz: view axis; w: ribbon width per unit thickness
    ivec4 params;                       // x: ribbons, y: OIT weight (7..10), z: DOMs, w: log
    ivec4 domLight;                     // scene light index of DOM slot i, -1 unused
    mat4 domViewProj[HAIR_MAX_DOMS];    // world -> DOM clip space (orthographic)
    vec4 domLayer[HAIR_MAX_DOMS];       // x: layer size d in stored-depth units
    mat4 domMeshViewProj[HAIR_MAX_DOMS]; // same x, y; depth from the nearest caster (meshes)
} hairFrame;
// Pass 2 binds the DOM depth (z0) array here, the shading passes the opacity array.
layout(set = 3, binding = 0) uniform sampler2DArray hairDom;

// Offsets of the three DOM layers' far boundaries from z0: d, 2d, 3d or d, 3d, 7d (log).
vec3 hairDomBounds(float d) {
    return hairFrame.params.w == 1 ? vec3(d, 3.0 * d, 7.0 * d) : vec3(d, 2.0 * d, 3.0 * d);
}

// Layer of a fragment rel = z - z0 behind the first hair: the last boundary it has passed.
int hairDomLayer(float rel, vec3 bounds) {
    return rel >= bounds.y ? 2 : (rel >= bounds.x ? 1 : 0);
}

#endif
