#version 450
#include "hair_vertex.glsl"
