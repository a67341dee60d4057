#version 450
// Forward shading plus the inputs of its shading, for the NumPy shading oracle.
#define DEBUG_OUTPUTS
#include "forward_main.glsl"
