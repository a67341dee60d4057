// The forward pass's colour attachments as fragment outputs (ScenePipelines' forward colour
// formats): the colour; with DEBUG_OUTPUTS the inputs of its shading; with DOME_OUTPUT the
// dome's light and floor for the gather pass. Included by forward_main.glsl and, for the
// background drawn last in the same pass, background_main.glsl.
layout(location = 0) out vec4 outColor;
#ifdef DEBUG_OUTPUTS
layout(location = 1) out vec4 outPosition; // world xyz, 1 = covered
layout(location = 2) out vec4 outNormal;   // shading normal, shadow visibility
layout(location = 3) out vec4 outSurface;  // uv, light-space depth, instance + 1
layout(location = 4) out vec4 outAlbedo;   // T: base colour * sampled texture; K_S (grey) map
#endif
#ifdef DOME_OUTPUT
#ifdef DEBUG_OUTPUTS
layout(location = 5) out vec4 outDome;
layout(location = 6) out vec2 outDomeAux;
#else
layout(location = 1) out vec4 outDome;
layout(location = 2) out vec2 outDomeAux;
#endif
#endif
