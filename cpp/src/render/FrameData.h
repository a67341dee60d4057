#pragma once
// The CPU side of a frame: what the scene becomes on the GPU (instances, lights, shadow
// frusta, the per-frame uniform block), computed from Scene + Camera + settings.
#include <vector>

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
};

struct ShadowLight {
    int lightIndex; // in the scene
    int layer;      // in the shadow-map array
    ShadowFrustum frustum;
};

struct FrameData {
    std::vector<GpuInstance> instances;
    std::vector<Draw> draws;
    std::vector<GpuLight> lights;
    std::vector<ShadowLight> shadowLights; // at most kMaxShadowLights
    std::vector<ShadowInfo> shadowInfos;   // one per scene light
    GpuFrame frame{};
};

/// Uploads meshes/textures the scene needs (through `cache`) and fills the frame's GPU data.
/// The first kMaxShadowLights shadow-casting lights get shadow maps.
FrameData buildFrameData(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         float aspect, GpuCache& cache);

} // namespace weft::render
