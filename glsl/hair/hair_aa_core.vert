#version 450
#define HAIR_AA
#define HAIR_AA_CORE
#include "hair_vertex.glsl"
