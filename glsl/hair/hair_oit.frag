#version 450
#include "hair_oit_main.glsl"
