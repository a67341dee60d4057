// One frame of a Renderer: its data (uploaded, and its descriptor sets written, by
// FrameDescriptors.cpp) and the frame graph the pass modules build (render/FramePasses.h:
// shadow views, dome maps, reflection capture, bounce captures, forward shading, dome blur, hair,
// output, readback or present), recorded into the frame slot's command buffer.
#include "render/FramePasses.h"
#include "render/RendererImpl.h"

namespace weft {

using render::FrameData;
using render::FrameGraph;
using render::FrameSlot;

namespace {

// Everything a shadow map's contents depend on besides its view, per caster: each draw's
// geometry, transform and alpha test (an empty key for a draw that casts no shadow), then the
// hair's (its strands objects, which are immutable, and transforms) as one.
std::vector<std::vector<uint64_t>> casterKeys(const render::FrameData& data, const Scene& scene) {
    std::vector<std::vector<uint64_t>> keys;
    std::vector<uint64_t> key;
    auto put = [&](const void* p, size_t bytes) {
        const size_t at = key.size();
        key.resize(at + (bytes + 7) / 8, 0);
        std::memcpy(key.data() + at, p, bytes);
    };
    for (const render::Draw& d : data.draws) {
        key.clear();
        if (d.castShadows) {
            key.push_back(d.mesh->contentId);
            put(&d.model, sizeof(glm::mat4));
            put(&d.alphaCutoff, sizeof(float));
            if (d.alphaCutoff > 0.0f) put(&d.material, sizeof(d.material));
        }
        keys.push_back(key);
    }
    key.clear();
    for (const HairInstance& h : scene.hairs()) {
        if (!h.castShadows) continue;
        const HairStrands* strands = h.strands.get();
        put(&strands, sizeof(strands));
        key.push_back(h.strands->points.size());
        put(&h.transform, sizeof(glm::mat4));
    }
    keys.push_back(key);
    return keys;
}

// The casters' keys in one after `all` (empty without casters: DomeShadows builds no dome
// then), those `skip` accepts left out.
template <class Skip = bool (*)(size_t)>
std::vector<uint64_t> flatten(
    const std::vector<std::vector<uint64_t>>& keys, std::vector<uint64_t> all = {},
    Skip skip = [](size_t) { return false; }) {
    for (size_t i = 0; i < keys.size(); ++i) {
        if (keys[i].empty() || skip(i)) continue; // casts no shadow, or left out
        all.push_back(i);                         // which caster each part belongs to
        all.insert(all.end(), keys[i].begin(), keys[i].end());
    }
    return all;
}

// The scene lights' shadow views; with the casters' keys after them, equal keys mean the maps
// can be reused.
std::vector<uint64_t> viewsKey(const render::FrameData& data) {
    std::vector<uint64_t> key;
    for (const render::ShadowView& v : data.shadowViews) {
        const size_t at = key.size();
        key.resize(at + sizeof(glm::mat4) / 8);
        std::memcpy(key.data() + at, &v.frustum.viewProj, sizeof(glm::mat4));
    }
    return key;
}

} // namespace

void Renderer::Impl::recordFrame(FrameSlot& slot, const Scene& scene, const Camera& camera,
                                 uint32_t outputs, vk::Image* ldr, bool present) {
    vk::Context& c = *ctx;
    const bool debug = outputs & OutputDebug;
    const float aspect = float(targets.width) / float(targets.height);

    FrameData data = buildFrameData(scene, camera, settings, aspect, *cache);
    double environmentBakeMs = 0.0;
    const bool environmentBaked = environment.prepare(scene.environment(), environmentBakeMs);
    environment.fillFrame(scene.environment(), data.frame);
    shadowInfos = data.shadowInfos;
    if (!data.shadowViews.empty()) ensureShadowMaps(uint32_t(data.shadowViews.size()));
    std::vector<std::vector<uint64_t>> keys = casterKeys(data, scene);
    const std::vector<uint64_t> casters = flatten(keys);
    std::vector<uint64_t> views = viewsKey(data);
    std::vector<uint64_t> key = views;
    key.insert(key.end(), casters.begin(), casters.end());
    std::vector<int> domeDue = dome.prepare(scene, settings, casters, frameCounter);
    data.frame.environment.z = float(dome.lights().size());
    data.frame.environment.w = float(dome.mapSize());
    // The dome's diffuse light goes through the blur pass (SPEC §4.5) when a blur is asked for.
    const bool domeBlur = dome.active() && dome.blurRadius() > 0.0f;
    // 2: each pixel of a 2 x 2 block evaluates a quarter of the dome's lights (dome_gather.frag)
    data.frame.options.z = domeBlur ? (settings.domeInterleave ? 2.0f : 1.0f) : 0.0f;
    data.frame.sky.w = dome.occludesAmbient() ? 1.0f : 0.0f;
    data.frame.options.w = scene.backgroundImage() != nullptr ? 1.0f : 0.0f;
    // Something behind the scene: the background image, or the environment (EnvironmentGpu).
    const bool background = scene.backgroundImage() != nullptr || data.frame.sky.x > 0.5f;
    data.frame.viewport =
        glm::vec4(1.0f / float(targets.width), 1.0f / float(targets.height), 0, 0);
    const bool captureProbe = probe.prepare(scene, data, settings.probeSize);
    // Debug frames keep one bounce: their colour is the colour render() draws.
    const bool captureBounce = bounce.prepare(scene, data, settings);
    const bool reuseShadows =
        settings.reuseShadowMaps && !data.shadowViews.empty() && key == shadowSignature;
    shadowSignature = std::move(key);
    // While the light views stand still, the casters that moved since the last frame are drawn
    // over the still ones' depth, which is drawn only when they change (ShadowPasses.cpp).
    std::vector<uint8_t> moving;
    bool splitShadows = false, drawStill = false, hairMoving = false;
    if (settings.reuseShadowMaps && !reuseShadows && !data.shadowViews.empty() &&
        views == lastShadowViews && keys.size() == lastCasterKeys.size()) {
        bool anyMoving = false, anyStill = false;
        moving.assign(data.draws.size(), 0);
        auto moved = [&](size_t i) { return keys[i] != lastCasterKeys[i]; };
        for (size_t i = 0; i < keys.size(); ++i) {
            if (keys[i].empty()) continue; // casts no shadow
            (moved(i) ? anyMoving : anyStill) = true;
            if (i < moving.size()) // a draw; the last key is the hair's
                moving[i] = moved(i);
            else
                hairMoving = moved(i);
        }
        std::vector<uint64_t> still = flatten(keys, views, moved);
        splitShadows = anyMoving && anyStill;
        drawStill = splitShadows && still != stillSignature;
        if (splitShadows) stillSignature = std::move(still);
    }
    lastShadowViews = std::move(views);
    lastCasterKeys = std::move(keys);
    const bool hasHair = !scene.hairs().empty();
    if (hasHair) {
        if (!hair) hair = std::make_unique<render::HairPasses>(c, pipes);
        hair->prepare(uint32_t(frameCounter % kFramesInFlight), scene, camera, settings,
                      targets.width, targets.height, data.gpuLightIndex, data.lightFeatures);
    }
    // Debug outputs hold one surface per pixel: those frames are not multisampled.
    const uint32_t samples = debug ? 1u : supportedSamples(settings.msaa);
    if (samples > 1) targets.ensureMultisampled(c, samples, domeBlur);

    uploadFrame(slot, data, captureProbe, captureBounce);
    const render::FrameSets sets =
        bindFrame(slot, scene, data, captureProbe, captureBounce, domeBlur);

    render::FramePassContext f{c,
                               settings,
                               pipes,
                               targets,
                               dome,
                               probe,
                               bounce,
                               hasHair ? hair.get() : nullptr,
                               data.shadowViews.empty() ? dummyShadow : shadowMaps,
                               stillShadows,
                               shadowInfos,
                               scene,
                               camera,
                               data,
                               sets,
                               ldr,
                               outputs,
                               present,
                               debug,
                               hasHair,
                               domeBlur,
                               background,
                               captureProbe,
                               captureBounce,
                               reuseShadows,
                               std::move(domeDue),
                               samples};
    if (scene.environment().environment && !environmentBaked) f.reused.push_back("environment");
    f.splitShadows = splitShadows;
    f.drawStill = drawStill;
    f.hairMoving = hairMoving;
    f.moving = std::move(moving);
    if (present) f.overlay = overlay;

    FrameGraph g;
    f.rDepth = g.addResource("depth", &targets.depth);
    f.rHdr = g.addResource("hdr", &targets.hdr);
    f.rLdr = g.addResource("ldr", ldr);
    if (debug) {
        f.rDebug[0] = g.addResource("position", &targets.position);
        f.rDebug[1] = g.addResource("normal", &targets.normal);
        f.rDebug[2] = g.addResource("surface", &targets.surface);
        f.rDebug[3] = g.addResource("albedo", &targets.albedo);
    }
    // The pass modules, in order (render/FramePasses.h).
    render::addShadowPasses(g, f);
    render::addDomePasses(g, f);
    render::addProbePasses(g, f);
    render::addBouncePasses(g, f);
    render::addForwardPasses(g, f);
    render::addDomeBlurPasses(g, f);
    render::addHairPasses(g, f);
    render::addOutputPasses(g, f);

    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkResetCommandBuffer(slot.cmd, 0));
    VK_CHECK(vkBeginCommandBuffer(slot.cmd, &begin));
    slot.timestamps->reset(slot.cmd);
    slot.stats = FrameStats{};
    slot.stats.frameIndex = frameCounter;
    slot.stats.reused = std::move(f.reused);
    slot.stats.meshUploads = data.meshUploads;
    slot.stats.uploadBytes = data.uploadBytes;
    slot.stats.environmentBakes = environmentBaked ? 1 : 0;
    slot.stats.environmentBakeMs = environmentBakeMs;
    g.execute(c, slot.cmd, slot.timestamps.get(), slot.stats);
    // The present pseudo-pass only transitions; it is not a pass users should time.
    if (present && !slot.stats.passes.empty() && slot.stats.passes.back().name == "present")
        slot.stats.passes.pop_back();
    VK_CHECK(vkEndCommandBuffer(slot.cmd));
}

} // namespace weft
