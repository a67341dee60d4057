#version 450
// The background behind the forward pass with both (forward_debug_dome.frag).
#define DEBUG_OUTPUTS
#define DOME_OUTPUT
#include "background_main.glsl"
