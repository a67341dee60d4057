#version 450
// Holes cast holes: texels whose base-texture alpha is below the cutoff write no depth.
layout(set = 0, binding = 0) uniform sampler2D baseTexture;
layout(push_constant) uniform Push { mat4 lightMvp; float alphaCutoff; } push;

layout(location = 0) in vec2 inUv;

void main() {
    if (texture(baseTexture, inUv).a < push.alphaCutoff) discard;
}
