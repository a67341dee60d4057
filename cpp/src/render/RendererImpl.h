#pragma once
// The state of a weft::Renderer, shared by Renderer.cpp (lifecycle, settings, render/present,
// read-backs) and FrameRecording.cpp (one frame's graph of passes).
#include <weft/Debug.h>
#include <weft/Renderer.h>
#include <weft/ShaderReload.h>

#include <array>
#include <chrono>
#include <cstring>
#include <string>
#include <unordered_map>

#include "render/BounceProbes.h"
#include "render/CoatAlbedoGpu.h"
#include "render/DomeShadows.h"
#include "render/EnvironmentGpu.h"
#include "render/FrameData.h"
#include "render/FrameGraph.h"
#include "render/FrameOverlay.h"
#include "render/GpuCache.h"
#include "render/GpuTypes.h"
#include "render/HairPasses.h"
#include "render/PassSetup.h"
#include "render/ReflectionProbe.h"
#include "render/RenderTargets.h"
#include "render/ScenePipelines.h"
#include "render/ShadowFit.h"
#include "vk/Pipeline.h"
#include "vk/WindowNative.h"

namespace weft {

namespace render {

constexpr uint32_t kFramesInFlight = 2;
// timestamp pairs: shadow views + dome maps + probe faces + bounce faces + forward + output +
// readback
constexpr uint32_t kMaxPasses = 256;
constexpr uint32_t kBounceFaces = 6 * BounceProbes::kMaxProbes * BounceProbes::kRounds;
// the frame's, one per face of the reflection capture and one per face of the bounce captures
constexpr uint32_t kFrameSets = 7 + kBounceFaces;

/// The descriptor sets of one frame: the frame's, one per probe face while capturing, one per
/// bounce-capture face while capturing those, the output pass's, the dome's gather and blur
/// passes' and the bounce projection's.
struct FrameSets {
    VkDescriptorSet frame = VK_NULL_HANDLE;
    std::array<VkDescriptorSet, 6> faces{};
    std::array<VkDescriptorSet, kBounceFaces> bounceFaces{}; // 6 (count round + probe) + face
    VkDescriptorSet output = VK_NULL_HANDLE, domeGather = VK_NULL_HANDLE, domeRows = VK_NULL_HANDLE,
                    domeBlur = VK_NULL_HANDLE, bounceSh = VK_NULL_HANDLE;
};

/// Per frame in flight: its command buffer, uploads, descriptors and timestamps.
struct FrameSlot {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    uint64_t serial = 0;
    vk::Buffer ubo, probeUbo, bounceUbo, instances, lights, shadowLayers, domeLights;
    vk::DescriptorPool pool;
    std::unique_ptr<render::Timestamps> timestamps;
    vk::Semaphore acquired;
    FrameStats stats;
    bool statsPending = false;
};

} // namespace render

struct Renderer::Impl {
    using FrameSlot = render::FrameSlot;
    static constexpr uint32_t kFramesInFlight = render::kFramesInFlight;
    std::shared_ptr<vk::Context> ctx = vk::Context::shared();
    RenderSettings settings;
    uint32_t width = 0, height = 0;

    render::ScenePipelines pipes{*ctx};
    render::EnvironmentGpu environment{*ctx};
    render::DomeShadows dome{*ctx};
    render::ReflectionProbe probe{*ctx};
    render::BounceProbes bounce{*ctx};
    std::unique_ptr<render::GpuCache> cache;
    std::unique_ptr<render::HairPasses> hair; // created with the first scene that has hair

    vk::CommandPool commandPool; // this renderer's; recording never contends with others
    std::array<FrameSlot, kFramesInFlight> slots;
    uint64_t frameCounter = 0;
    render::RenderTargets targets;
    vk::Image shadowMaps;
    std::vector<uint64_t> shadowSignature; // what the shadow maps hold (see shadowKey)
    // The depth of the shadow casters that stood still (ShadowPasses.cpp), what it holds (the
    // views and those casters' keys), and each caster's key in the last frame
    vk::Image stillShadows;
    std::vector<uint64_t> stillSignature;
    std::vector<std::vector<uint64_t>> lastCasterKeys;
    std::vector<uint64_t> lastShadowViews;
    uint64_t shaderGenerationBuilt = shaderGeneration(); // hot reload: shaders the pipes use
    vk::Image dummyShadow;
    vk::Image coatAlbedo; // the GGX coat's directional albedo (CoatAlbedoGpu.h)
    std::vector<ShadowInfo> shadowInfos;
    FrameStats stats;
    render::FrameOverlay* overlay = nullptr; // drawn over present() frames (FrameOverlay.h)

    Impl(uint32_t w, uint32_t h, const RenderSettings& s) : settings(s), width(w), height(h) {
        cache =
            std::make_unique<render::GpuCache>(*ctx, pipes.materialSetLayout, pipes.textureSampler);
        createSlots();
        createDummyShadow();
        coatAlbedo = render::uploadCoatAlbedo(*ctx);
    }

    ~Impl() {
        // The pool (and its command buffers) is retired; wait only for this renderer's frames so
        // no slot is mid-flight while its buffers are released.
        for (auto& s : slots) ctx->waitFor(s.serial);
    }

    void createSlots();
    void createDummyShadow();
    FrameSlot& beginFrame();
    void finishStats(FrameSlot& slot);
    void recordFrame(FrameSlot& slot, const Scene& scene, const Camera& camera, uint32_t outputs,
                     vk::Image* ldr, bool present);
    // FrameDescriptors.cpp: the slot's buffers and the frame's descriptor sets.
    void uploadFrame(FrameSlot& slot, const render::FrameData& data, bool captureProbe,
                     bool captureBounce);
    render::FrameSets bindFrame(FrameSlot& slot, const Scene& scene, const render::FrameData& data,
                                bool captureProbe, bool captureBounce, bool domeBlur);
    VkDeviceSize probeFaceStride() const; // the probe faces' uniforms, aligned
    void ensureShadowMaps(uint32_t layers);
    /// The largest sample count <= `wanted` the device renders colour and depth with.
    uint32_t supportedSamples(uint32_t wanted) const {
        const VkPhysicalDeviceLimits& l = ctx->properties().limits;
        const VkSampleCountFlags ok =
            l.framebufferColorSampleCounts & l.framebufferDepthSampleCounts;
        while (wanted > 1 && !(ok & wanted)) wanted /= 2;
        return wanted;
    }
};

} // namespace weft
