#pragma once
// The CPU side of a frame: what the scene becomes on the GPU (instances, lights, shadow
// views, cookie textures, the per-frame uniform block), computed from Scene + Camera + settings.
#include <vector>

#include <weft/Debug.h>
#include <weft/Renderer.h>

#include "render/GpuCache.h"
#include "render/GpuTypes.h"
#include "render/ShadowFit.h"

namespace weft::render {

struct Draw {
    const MeshGpu* mesh;
    VkDescriptorSet material;
    uint32_t instance; // index into `instances`, also the scene's mesh id
    bool castShadows;
    glm::mat4 model;
    float alphaCutoff; // > 0: alpha-tested (also in shadow maps)
    bool mirrored;     // det(model) < 0: the triangles' winding is reversed
    bool twoSided;     // no culling; back faces shaded with the flipped normal
    bool phantom;      // shows only the shadows it receives (not in reflection captures)
};

/// One shadow-map layer to render: a view of a shadow-casting light.
struct ShadowView {
    int lightIndex; // in the scene
    int layer;      // in the shadow-map array
    ShadowFrustum frustum;
};

struct FrameData {
    std::vector<GpuInstance> instances;
    std::vector<Draw> draws;
    std::vector<GpuLight> lights;        // sorted by group (gpu::LIGHT_GROUP_*, Frame::lightStart)
    std::vector<int> gpuLightIndex;      // scene light index -> its place in `lights`
    uint32_t lightFeatures = 0;          // gpu::FEATURE_LIGHT_GROUP bits and FEATURE_COOKIES
    std::vector<ShadowView> shadowViews; // at most kMaxShadowLayers
    std::vector<GpuShadowLayer> shadowLayers;
    std::vector<ShadowInfo> shadowInfos; // one per scene light
    std::vector<TexturePtr> cookies;     // by cookie slot, at most kMaxCookies
    GpuFrame frame{};
    int meshUploads = 0;
    uint64_t uploadBytes = 0;
};

/// Uploads meshes/textures the scene needs (through `cache`) and fills the frame's GPU data.
/// Shadow-casting lights get shadow-map layers in scene order while kMaxShadowLayers last
/// (directional and spot lights one, point lights six); later ones are unshadowed.
FrameData buildFrameData(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         float aspect, GpuCache& cache);

/// Whether the scene's ambient reads as a uniform sky (Frame.ambient.w): ambient occlusion on,
/// a non-zero ambient and no environment to stand for the sky. Such a sky is reflected by glossy
/// surfaces (shading.glsl skyReflection) and occluded by a dome where something casts a shadow
/// (DomeShadows).
bool ambientReadsAsSky(const Scene& scene, const RenderSettings& settings);

/// The gpu::FEATURE_* bits the frame's uniform, instances and lights can turn on: the
/// specialization of the pipelines that shade it (frame.glsl, kFrameFeatures).
uint32_t frameFeatures(const FrameData& data);

/// The material bits of instance `instance` that specialize the pipelines drawing it (frame.glsl,
/// kMaterialFlags): its Instance::flags.x, plus gpu::BOUNCE_CAPTURE where it has a capture and
/// gpu::REFLECTIVE where it reflects the environment.
uint32_t materialFeatures(const FrameData& data, uint32_t instance);

} // namespace weft::render
