#version 450
#define HAIR_OIT
#define HAIR_AA
#include "hair_vertex.glsl"
