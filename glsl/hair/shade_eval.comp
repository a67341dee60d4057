#version 450
// Evaluates hairShade() for a batch of directions (weft::evaluateHairShading, for tests and
// benchmarks against the NumPy reference).
#include "hair_shading.glsl"

layout(local_size_x = 64) in;

struct EvalInput {
    vec4 t;
    vec4 l;
    vec4 v;
    uvec4 strand; // x: strand id
};

layout(std430, set = 0, binding = 0) readonly buffer Params { HairShading params; };
layout(std430, set = 0, binding = 1) readonly buffer Inputs { EvalInput inputs[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Outputs { vec4 outputs[]; };
layout(push_constant) uniform Push { uint count; } pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    EvalInput e = inputs[i];
    outputs[i] = vec4(hairShade(params, e.t.xyz, e.l.xyz, e.v.xyz, e.strand.x), 0.0);
}
