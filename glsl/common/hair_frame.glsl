// Data of the hair passes (sets 2 and 3; sets 0 and 1 are the scene's frame and material sets).
// The structs are hair_gpu_types.h's (one definition for C++ and GLSL). An index of a hair draw
// is 2 * point + side: lines use side 0, ribbons expand side 0 / 1 to the - / + edge.
#ifndef WEFT_HAIR_FRAME_GLSL
#define WEFT_HAIR_FRAME_GLSL
#include "hair_shading.glsl"

layout(std430, set = 2, binding = 0) readonly buffer HairVertices { HairVertex hairVertices[]; };
layout(std430, set = 2, binding = 1) readonly buffer HairInstances {
    HairInstance hairInstances[];
};
layout(set = 2, binding = 2) uniform HairFrameUbo { HairFrame hairFrame; };
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
