// Hair strands seen from the camera: lines, or ribbons facing the eye (index = 2 point + side).
// With HAIR_OIT defined it also passes the opacity and view depth the OIT weights need.
#include "frame.glsl"
#include "hair_frame.glsl"

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outTangent;
layout(location = 2) out vec3 outColor;
layout(location = 3) flat out uint outStrand;
#ifdef HAIR_OIT
layout(location = 4) out float outAlpha;
layout(location = 5) out float outViewDepth;
#endif

void main() {
    uint index = uint(gl_VertexIndex);
    HairVertex hv = hairVertices[index >> 1];
    mat4 model = hairInstances[push.instance].model;
    vec3 p = (model * vec4(hv.position.xyz, 1.0)).xyz;
    vec3 t = normalize(mat3(model) * hv.tangent.xyz);
    if (hairFrame.params.x == 1) {
        vec3 e = frame.cameraPos.xyz - p;
        vec3 s = cross(t, e);
        if (dot(s, s) <= 1e-12 * dot(e, e))
            s = cross(t, abs(t.y) > 0.99 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0));
        float side = (index & 1u) == 1u ? 0.5 : -0.5;
        p += normalize(s) * (side * hairFrame.cameraForward.w * hv.position.w);
    }
    outWorldPos = p;
    outTangent = t;
    outColor = hv.color;
#ifdef HAIR_OIT
    outAlpha = hv.tangent.w;
    outViewDepth = dot(p - frame.cameraPos.xyz, hairFrame.cameraForward.xyz);
#endif
    outStrand = hv.strand;
    gl_Position = frame.viewProj * vec4(p, 1.0);
}
