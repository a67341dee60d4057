#version 450
// WBOIT accumulation in anti-aliased frames: the strand's opacity times its pixel coverage.
#define HAIR_AA
#include "hair_oit_main.glsl"
