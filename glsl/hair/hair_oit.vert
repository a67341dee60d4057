#version 450
#define HAIR_OIT
#include "hair_vertex.glsl"
