#version 450
// The background behind the forward pass with its dome output (forward_dome.frag).
#define DOME_OUTPUT
#include "background_main.glsl"
