#pragma once
// The renderer's hair passes (SPEC §5): strands in the shadow-map views, deep opacity maps for
// shadow-casting directional lights (pass 1 depth, pass 2 opacity layers), opaque hair shaded
// per fragment, and weighted blended OIT (accumulation + composite over the opaque image).
// Only what the scene needs is added: no hair, no passes; no transparent hair or OIT off, no
// OIT passes; no shadow-casting directional light or DOM off, no DOM passes. Anti-aliased frames
// (msaa > 1, never debug frames) draw strands as screen-space strips with their pixel coverage:
// "hair" the pixels a strand covers entirely, "hair_fringe" the partly covered ones accumulated
// with the OIT targets, "hair_composite" both over the frame (glsl/hair/hair_oit_main.glsl).
// HairPasses.cpp prepares a frame and adds its passes; HairDoms.cpp fits the deep opacity maps'
// views; HairPassResources.cpp holds the images and descriptor sets.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include <weft/Debug.h>
#include <weft/Renderer.h>

#include "render/FrameGraph.h"
#include "render/HairGpu.h"
#include "render/HairGpuTypes.h"
#include "render/HairPipelines.h"

namespace weft::render {

struct ScenePipelines;

class HairPasses {
public:
    HairPasses(vk::Context& ctx, const ScenePipelines& scene);
    ~HairPasses();

    /// Uploads strands and fills this frame's buffers and descriptor sets (frame slot `slot`).
    /// `gpuLightIndex`: each scene light's place in the frame's light buffer, `lightFeatures`
    /// the gpu::FEATURE_* bits of its lights (FrameData).
    void prepare(uint32_t slot, const Scene& scene, const Camera& camera,
                 const RenderSettings& settings, uint32_t width, uint32_t height,
                 const std::vector<int>& gpuLightIndex, uint32_t lightFeatures);
    /// Draws the shadow-casting strands as lines into the bound depth target of a light view.
    void drawDepth(VkCommandBuffer cmd, const glm::mat4& viewProj) const;

    struct Targets {
        int shadow, depth, hdr;
        const int* debug; // 4 debug images, or null
        vk::Image *hdrImage, *depthImage;
        std::array<vk::Image*, 4> debugImages;
        VkDescriptorSet frameSet;
        /// Renders the depth of the scene's mesh casters (no hair) seen by a view-projection into
        /// a depth view of a size: the meshes that shadow hair under a deep opacity map.
        std::function<void(VkCommandBuffer, VkImageView, uint32_t, const glm::mat4&)> meshDepth;
        std::vector<std::string>* reused; // names of the passes skipped: their maps still hold
    };
    /// Adds the DOM, hair, fringe and OIT passes after the forward pass.
    void addPasses(FrameGraph& graph, const Targets& targets);
    /// The last frame's deep opacity map of a light (InvalidArgument if it had none).
    HairDomInfo domInfo(int lightIndex);
    /// Drops GPU copies of strands no scene holds any more.
    void evictExpired() { mCache.evictExpired(); }

private:
    struct HairDraw {
        HairGpu* gpu;
        VkDescriptorSet set;
        uint32_t instance;
        HairModel shading;
        const HairShadedPipelines* shaded; // this frame's, for its lights and model (prepare)
        glm::vec3 lo, hi;                  // object-space bounds of the points
        bool castShadows, transparent;
        glm::mat4 model;
    };
    struct Slot {
        vk::Buffer instances, frame;
        vk::DescriptorPool pool;
        uint32_t poolSets = 0;
    };
    struct Dom {
        int light;
        HairDomInfo info;
        glm::mat4 viewProj;
        glm::mat4 meshViewProj; // viewProj with depth from the nearest mesh caster
        float layerNdc;
    };

    void fitDoms(const Scene& scene, const RenderSettings& settings);
    /// The pixels this frame's strands can cover (see mRect).
    VkRect2D screenRect(const Camera& camera, const RenderSettings& settings, uint32_t width,
                        uint32_t height) const;
    /// What the deep opacity maps would hold this frame: each map's view and the strands drawn
    /// into it.
    std::vector<uint64_t> domKey() const;
    void allocateSets(Slot& slot, uint32_t draws);
    void writeSets(Slot& slot);
    void ensureImages(const RenderSettings& settings, uint32_t width, uint32_t height);
    /// Which of a draw's shading pipelines a pass uses.
    using PipelineOf = std::function<VkPipeline(const HairShadedPipelines&)>;
    /// The camera's view of the opaque or the transparent strands; `strips`: as triangles (the
    /// ribbon indices; anti-aliased frames draw lines as one-pixel strips too).
    void drawCamera(VkCommandBuffer cmd, const Targets& t, const PipelineOf& pipeline,
                    VkDescriptorSet domSet, bool transparent, bool strips) const;
    /// Shadow-casting strands as lines; push constants: light view-projection * model, params.
    void drawFromLight(VkCommandBuffer cmd, VkPipeline pipeline, const glm::mat4& viewProj,
                       const glm::vec4& params) const;

    vk::Context& mCtx;
    const ScenePipelines& mScene;
    HairPipelines mPipes;
    HairGpuCache mCache;
    std::array<Slot, 2> mSlots;
    vk::Image mDomDepth, mDomOpacity, mDomMeshDepth, mDummyDom, mNoMeshes, mAccum, mWeight;
    // What mDomOpacity holds (domKey; empty: nothing yet), and whether this frame's maps are
    // those (RenderSettings::reuseShadowMaps): the strands' depth and opacity passes are skipped
    // (the meshes' depth in each map's view is drawn every frame: a cloth moves).
    std::vector<uint64_t> mDomKey;
    bool mReuseDoms = false;
    // The pixels the strands can cover this frame: where the OIT targets are cleared, drawn
    // into and composited (screenRect)
    VkRect2D mRect{};
    // anti-aliased frames, per pixel (R32_UINT layers): the nearest depth of the partly covering
    // strands at each of kHairAaDepthSamples sample points, which of 128 points they cover, and
    // sums of their coverage (glsl/hair/hair_oit_main.glsl)
    vk::Image mSamples;
    std::vector<HairDraw> mDraws;
    std::vector<Dom> mDoms;
    std::vector<HairDomInfo> mLastDoms; // by scene light, size 0 where none
    VkDescriptorSet mZ0Set = VK_NULL_HANDLE, mOpacitySet = VK_NULL_HANDLE;
    VkDescriptorSet mOitSet = VK_NULL_HANDLE;
    bool mRibbons = false, mOit = false;
    bool mAntialias = false;        // strips with coverage (MSAA frames; debug frames never)
    bool mSampleDepths = false;     // ... and opaque strands with sample depths: mSamples is used
    bool mMeshesShadowHair = false; // DOMs and mesh casters this frame: the hair_dom_meshes pass
    uint32_t mWidth = 0, mHeight = 0, mDomSize = 0;
};

} // namespace weft::render
