// What lies behind the scene: the scene's background image (a camera frame for AR, SPEC §4.5)
// stretched over the target (sRGB textures decode to linear on sampling), or the environment
// seen along each pixel's view ray (frame.sky.x), times its intensity: the sharp radiance cube
// (mip chosen by the ray's footprint) or, blurred, the glossy chain at frame.sky.y.
#include "frame.glsl"

// What the pipeline draws (ScenePipelines::backgroundFor): 0 the image, 1 the sharp radiance,
// 2 the glossy chain; -1 whichever the frame says. lavapipe would sample all three otherwise.
layout(constant_id = 2) const int kBackground = -1;

// Drawn last in the forward pass (ForwardPasses.cpp), the background fills the pass's other
// attachments too, with what the pass clears them to where nothing is drawn (independent
// colour write masks would need the independentBlend feature).
#include "forward_outputs.glsl"

void main() {
#ifdef DEBUG_OUTPUTS
    outPosition = outSurface = outAlbedo = vec4(0.0); // not covered
    outNormal = NO_SURFACE_NORMAL;
#endif
#ifdef DOME_OUTPUT
    outDome = vec4(0.0); // no light to darken, nothing occluded
    outDomeAux = NO_SURFACE_DOME_AUX.xy;
#endif
    vec2 uv = gl_FragCoord.xy * frame.viewport.xy;
    bool image = kBackground >= 0 ? kBackground == 0 : frame.options.w > 0.5;
    bool sharp = kBackground >= 0 ? kBackground == 1 : frame.sky.y < 0.0;
    if (image) {
        outColor = vec4(textureLod(backgroundImage, uv, 0.0).rgb, 1.0);
        return;
    }
    vec4 far = frame.inverseViewProj * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
    vec4 near = frame.inverseViewProj * vec4(uv * 2.0 - 1.0, 0.0, 1.0);
    vec3 ray = normalize(far.xyz / far.w - near.xyz / near.w);
    vec3 radiance = sharp ? texture(environmentRadiance, ray).rgb
                                      : textureLod(environmentMap, ray, frame.sky.y).rgb;
    outColor = vec4(radiance * frame.environment.x, 1.0);
}
