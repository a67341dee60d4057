#version 450
// The background alone: a cube capture's, or the forward pass's without extra outputs.
#include "background_main.glsl"
