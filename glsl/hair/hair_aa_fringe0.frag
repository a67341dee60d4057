#version 450
// The partly covered pixels of opaque strands, pass 0: the nearest depth at each sample point
// (hair_oit_main.glsl).
#define HAIR_AA
#define HAIR_AA_MASK
#define HAIR_AA_PASS 0
#include "hair_oit_main.glsl"
