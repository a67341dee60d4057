#version 450
// Writes linear radiance to an sRGB target (the hardware encodes), clamped to [0, 1].
layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(location = 0) out vec4 outColor;

void main() {
    vec3 c = texelFetch(hdr, ivec2(gl_FragCoord.xy), 0).rgb;
    outColor = vec4(clamp(c, 0.0, 1.0), 1.0);
}
