#version 450
// The partly covered pixels of opaque strands, pass 1: shading with their visible shares
// (hair_oit_main.glsl).
#define HAIR_AA
#define HAIR_AA_MASK
#define HAIR_AA_PASS 1
#include "hair_oit_main.glsl"
