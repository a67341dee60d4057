// Per-frame data shared by the scene passes. Must match render/GpuTypes.h.
#extension GL_GOOGLE_include_directive : require

const int MAX_SHADOW_LIGHTS = 4;

struct Light {
    vec4 toLight;  // xyz: unit vector towards the light
    vec4 radiance; // rgb: colour * intensity; w: shadow-map layer or -1
};

struct Instance {
    mat4 model;
    mat4 normalMatrix; // inverse transpose of the model matrix (upper 3x3 used)
    vec4 ka;
    vec4 kd;
    vec4 ks;        // w: shininess
    vec4 baseColor;
};

layout(set = 0, binding = 0) uniform FrameUbo {
    mat4 viewProj;
    vec4 cameraPos;
    vec4 ambient;
    vec4 background;
    mat4 lightViewProj[MAX_SHADOW_LIGHTS];
    vec4 normalOffset[MAX_SHADOW_LIGHTS]; // x: receiver offset along n in world units
    vec4 bias;    // x: constant, y: slope, z: max
    ivec4 counts; // x: lights, y: PCF radius, z: shadow-map size, w: debug shadow layer or -1
} frame;

layout(std430, set = 0, binding = 1) readonly buffer Instances { Instance instances[]; };
layout(std430, set = 0, binding = 2) readonly buffer Lights { Light lights[]; };
layout(set = 0, binding = 3) uniform sampler2DArray shadowMaps;

layout(push_constant) uniform Push { uint instance; } push;
