#version 450
// Opaque hair with the renderer's debug outputs: position + coverage, tangent + the debug
// light's visibility, (strand id, 0, 0, -(hair id + 1)), diffuse colour.
#include "hair_lighting.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inTangent;
layout(location = 2) in vec3 inColor;
layout(location = 3) flat in uint inStrand;

layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outPosition;
layout(location = 2) out vec4 outTangent;
layout(location = 3) out vec4 outSurface;
layout(location = 4) out vec4 outAlbedo;

void main() {
    float vis;
    HairShading s = hairInstances[push.instance].shading;
    vec3 t = normalize(inTangent);
    outColor = vec4(hairRadiance(inWorldPos, t, inColor, s, inStrand, vis), 1.0);
    outPosition = vec4(inWorldPos, 1.0);
    outTangent = vec4(t, vis);
    outSurface = vec4(float(inStrand), 0.0, 0.0, -float(push.instance + 1u));
    outAlbedo = vec4(s.diffuse.rgb * inColor, 1.0);
}
