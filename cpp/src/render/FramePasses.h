#pragma once
// The renderer's pass modules. recordFrame (FrameRecording.cpp) prepares a frame's data, fills a
// FramePassContext and calls each module's add function in order; a module adds only the passes
// its part of the scene needs. A new pass group is one new file defining an add function, its
// shaders and its test, plus one line in recordFrame.
#include <string>
#include <vector>

#include <weft/Renderer.h>

#include "render/FrameData.h"
#include "render/FrameGraph.h"

namespace weft::render {

struct FrameSets;
struct ScenePipelines;
struct RenderTargets;
class DomeShadows;
class ReflectionProbe;
class BounceProbes;
class FrameOverlay;
class HairPasses;
struct MeshGpu;

/// What every pass module of one frame sees: the renderer's parts, the frame's data and
/// descriptor sets, and the frame-graph resources registered so far (-1: absent). Modules
/// register the resources they produce here for the modules after them.
struct FramePassContext {
    vk::Context& ctx;
    const RenderSettings& settings;
    ScenePipelines& pipes;
    RenderTargets& targets;
    DomeShadows& dome;
    ReflectionProbe& probe;
    BounceProbes& bounce;
    HairPasses* hair;        // null without hair
    vk::Image& shadowMaps;   // the scene lights' maps (a dummy layer when there are none)
    vk::Image& stillShadows; // the depth of the casters that stood still (splitShadows)
    const std::vector<ShadowInfo>& shadowInfos;
    const Scene& scene;
    const Camera& camera;
    const FrameData& data;
    const FrameSets& sets;
    vk::Image* ldr;   // the output image (offscreen or the swapchain's)
    uint32_t outputs; // FrameOutput bits
    bool present;     // the output goes to a swapchain
    bool debug;       // debug outputs (rendered without MSAA: one surface per pixel)
    bool hasHair;
    bool domeBlur;            // the dome's diffuse light goes through the blur passes
    bool background;          // a background image or the environment is drawn behind the scene
    bool captureProbe;        // the dynamic reflection probe is captured this frame
    bool captureBounce;       // the bounce captures are taken (and projected) this frame
    bool reuseShadows;        // the scene lights' shadow maps hold this frame's views
    std::vector<int> domeDue; // dome layers rendered this frame (the rest are reused)
    uint32_t samples = 1;     // MSAA samples of the forward pass
    // The scene lights' maps in two parts: the casters that stood still since the last frame,
    // kept in stillShadows (drawn there again only when `drawStill`) and copied into the maps,
    // then the ones that moved (`moving`, per draw; `hairMoving`) drawn over them.
    bool splitShadows = false, drawStill = false, hairMoving = false;
    std::vector<uint8_t> moving;
    FrameOverlay* overlay = nullptr; // drawn after tone mapping (present() frames only)

    // frame-graph resources
    int rShadow = -1, rDepth = -1, rHdr = -1, rLdr = -1;
    int rDebug[4] = {-1, -1, -1, -1};
    int rDomeMaps = -1, rProbe = -1, rDomeLight = -1, rDomeAux = -1, rBounceSh = -1,
        rBounceFaces = -1, rBounceDepth = -1, rBounceRadiance = -1;
    std::vector<std::string> reused; // passes skipped because their output is still valid
};

/// Binds a mesh's buffers and draws it (ShadowPasses.cpp).
void drawMesh(VkCommandBuffer cmd, const MeshGpu& mesh);
/// Which shadow casters drawCasters draws: all, those that stood still since the last frame or
/// those that moved (FramePassContext::moving, hairMoving).
enum class Casters { All, Still, Moving };
// Depth of the shadow casters (meshes, alpha-tested ones with holes, and hair if `withHair`)
// seen by viewProj, into a depth view of size x size, cleared first or (`clear` false) drawn
// over what it holds (ShadowPasses.cpp).
void drawCasters(const FramePassContext& f, VkCommandBuffer cmd, VkImageView view, uint32_t size,
                 const glm::mat4& viewProj, bool withHair, Casters which = Casters::All,
                 bool clear = true);
/// One cube-capture face: the draws `include` accepts (phantoms never), shaded with the face's
/// frame set into `color` (cleared to `clear`) over a `size` x `size` depth, stored when
/// `keepDepth` (its pass then declares Use::DepthWrite, else Use::DepthScratch); with
/// `background` the environment is drawn behind them (ProbePasses.cpp).
void drawCaptureFace(const FramePassContext& f, VkCommandBuffer cmd, VkImageView color,
                     VkImageView depth, bool keepDepth, uint32_t size, VkDescriptorSet faceSet,
                     const glm::vec4& clear, bool background, bool (*include)(const Draw&, int),
                     int arg);
/// One full-screen triangle into one colour target of the output's size (OutputPasses.cpp).
void drawFullscreen(const FramePassContext& f, VkCommandBuffer cmd, VkImageView target,
                    VkAttachmentLoadOp load, VkPipeline pipeline, VkPipelineLayout layout,
                    VkDescriptorSet set, const void* push, uint32_t pushBytes);
/// Begins rendering into one colour target of w x h (`load`: what it starts with), the
/// viewport and scissor over it; the caller binds, draws and ends.
void beginColorTarget(const FramePassContext& f, VkCommandBuffer cmd, VkImageView target,
                      uint32_t w, uint32_t h, VkAttachmentLoadOp load);
/// The same into a target of w x h.
void drawFullscreen(const FramePassContext& f, VkCommandBuffer cmd, VkImageView target, uint32_t w,
                    uint32_t h, VkAttachmentLoadOp load, VkPipeline pipeline,
                    VkPipelineLayout layout, VkDescriptorSet set, const void* push,
                    uint32_t pushBytes);

// The modules, in the order recordFrame calls them.
void addShadowPasses(FrameGraph& g, FramePassContext& f);   // scene lights' shadow maps
void addDomePasses(FrameGraph& g, FramePassContext& f);     // the environment dome's maps
void addProbePasses(FrameGraph& g, FramePassContext& f);    // dynamic reflection capture
void addBouncePasses(FrameGraph& g, FramePassContext& f);   // bounce captures, their SH9
void addForwardPasses(FrameGraph& g, FramePassContext& f);  // background + forward shading
void addDomeBlurPasses(FrameGraph& g, FramePassContext& f); // dome shadows blurred, added
void addHairPasses(FrameGraph& g, FramePassContext& f);     // DOM, hair, OIT (HairPasses)
void addOutputPasses(FrameGraph& g, FramePassContext& f);   // tone mapping, readback, present

} // namespace weft::render
