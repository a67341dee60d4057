#version 450
// Forward shading; the dome-shadowed diffuse light goes to the blur pass.
#define DOME_OUTPUT
#include "forward_main.glsl"
