#version 450
// The background behind the forward pass with its debug outputs (forward_debug.frag).
#define DEBUG_OUTPUTS
#include "background_main.glsl"
