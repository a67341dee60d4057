#version 450
// Forward shading (glsl/common/forward_main.glsl).
#include "forward_main.glsl"
