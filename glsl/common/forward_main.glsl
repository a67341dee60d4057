// The forward pass's fragment shader, included by the render/forward*.frag variants:
// DEBUG_OUTPUTS adds the inputs of its shading (for the NumPy shading oracle), DOME_OUTPUT the
// environment's diffuse light, the dome's occlusion and its floor for the gather and blur passes
// (dome_gather.frag, dome_blur*.frag).
#include "shading.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inTangent;

#include "forward_outputs.glsl"

void main() {
    Instance ins = instances[push.instance];
    pixelDx = dFdx(inWorldPos); // before any discard: derivatives need the whole quad
    pixelDy = dFdy(inWorldPos);
    if (alphaDiscarded(inUv, ins)) discard;
    float vis, depth;
#ifdef DOME_OUTPUT
    if (frame.options.z > 1.5) { // interleaved: this pixel's quarter of the dome lights
        ivec2 q = ivec2(gl_FragCoord.xy) & 1;
        domeFirst = q.x + 2 * q.y;
        domeStride = 4;
    }
#endif
    Surface sf = surfaceAt(inWorldPos, inNormal, inTangent, inUv, ins, gl_FrontFacing);
    vec4 dome;
    vec2 domeAux;
    outColor = vec4(shadedColor(shade(sf, ins, vis, depth), ins, dome, domeAux), 1.0);
#ifdef DOME_OUTPUT
    outDome = dome;
    outDomeAux = domeAux;
#endif
#ifdef DEBUG_OUTPUTS
    outAlbedo = vec4(sf.T, texture(specularMap, inUv).g);
    outPosition = vec4(inWorldPos, 1.0);
    outNormal = vec4(sf.n, vis);
    outSurface = vec4(inUv, depth, float(push.instance + 1u));
#endif
}
