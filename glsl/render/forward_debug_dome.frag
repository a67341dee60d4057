#version 450
// forward_debug.frag with the dome output of forward_dome.frag.
#define DEBUG_OUTPUTS
#define DOME_OUTPUT
#include "forward_main.glsl"
