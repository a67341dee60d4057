// Renderer: lifecycle (frame slots, shadow-map images), settings, render() and present() around
// one recorded frame (FrameRecording.cpp), frame statistics and read-backs of shadow maps, deep
// opacity maps and the reflection capture.
#include "render/RendererImpl.h"

namespace weft {

using render::Draw;
using render::FrameData;
using render::FrameGraph;
using render::FrameSlot;
using render::kFrameSets;
using render::kFramesInFlight;
using render::kMaxPasses;
using render::ResourceUse;
using render::ShadowView;
using render::Use;

void Renderer::Impl::createSlots() {
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = ctx->queueFamily();
    VkCommandPool pool;
    VK_CHECK(vkCreateCommandPool(ctx->device(), &poolInfo, nullptr, &pool));
    commandPool = vk::CommandPool(ctx.get(), pool, vkDestroyCommandPool);
    for (FrameSlot& s : slots) {
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = commandPool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        VK_CHECK(vkAllocateCommandBuffers(ctx->device(), &alloc, &s.cmd));
        const VkDescriptorPoolSize sizes[] = {
            {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kFrameSets},
            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4 * kFrameSets},
            {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
             // frame sets; the output set (1), the dome's gather and blur sets (3 each), the
             // bounce projection's (4)
             (13 + uint32_t(render::kMaxCookies)) * kFrameSets + 14}};
        VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pool.maxSets = kFrameSets + 5;
        pool.poolSizeCount = 3;
        pool.pPoolSizes = sizes;
        VkDescriptorPool p;
        VK_CHECK(vkCreateDescriptorPool(ctx->device(), &pool, nullptr, &p));
        s.pool = vk::DescriptorPool(ctx.get(), p, vkDestroyDescriptorPool);
        s.timestamps = std::make_unique<render::Timestamps>(*ctx, kMaxPasses);
        VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore handle;
        VK_CHECK(vkCreateSemaphore(ctx->device(), &sem, nullptr, &handle));
        s.acquired = vk::Semaphore(ctx.get(), handle, vkDestroySemaphore);
    }
}

// A 1x1 shadow map cleared to the far plane, bound when no light casts shadows.
void Renderer::Impl::createDummyShadow() {
    vk::ImageDesc d;
    d.format = render::kDepthFormat;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    dummyShadow = vk::Image(ctx.get(), d);
    ctx->immediate([&](VkCommandBuffer cmd) {
        vk::transition(*ctx, cmd, dummyShadow, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkClearDepthStencilValue one{1.0f, 0};
        VkImageSubresourceRange range{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
        vkCmdClearDepthStencilImage(cmd, dummyShadow.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                    &one, 1, &range);
        const render::UseState s = render::useState(Use::Sampled, true);
        vk::transition(*ctx, cmd, dummyShadow, s.layout, s.stage, s.access);
    });
}

void Renderer::Impl::ensureShadowMaps(uint32_t layers) {
    const uint32_t size = settings.shadowMapSize;
    if (shadowMaps && shadowMaps.desc().layers == layers && shadowMaps.desc().width == size) return;
    vk::ImageDesc d;
    d.width = d.height = size;
    d.layers = layers;
    d.format = render::kDepthFormat;
    d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
              VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    shadowMaps = vk::Image(ctx.get(), d);
    shadowSignature.clear();
    // the still casters' depth, copied into the maps before the moving ones are drawn
    d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    stillShadows = vk::Image(ctx.get(), d);
    stillSignature.clear();
}

FrameSlot& Renderer::Impl::beginFrame() {
    // Development: shaders edited in a watched directory replace the pipelines built from them.
    pollShaderChanges();
    if (const uint64_t generation = shaderGeneration(); generation != shaderGenerationBuilt) {
        pipes.createPipelines();
        hair.reset();
        shaderGenerationBuilt = generation;
    }
    FrameSlot& slot = slots[frameCounter % kFramesInFlight];
    ctx->waitFor(slot.serial); // the frame that last used this slot is done
    finishStats(slot);
    ctx->collectGarbage();
    cache->evictExpired();
    if (hair) hair->evictExpired();
    return slot;
}

void Renderer::Impl::finishStats(FrameSlot& slot) {
    if (!slot.statsPending) return;
    slot.statsPending = false;
    const std::vector<double> gpu = slot.timestamps->read(uint32_t(slot.stats.passes.size()));
    double total = 0.0;
    bool all = !gpu.empty();
    for (size_t i = 0; i < slot.stats.passes.size(); ++i) {
        slot.stats.passes[i].gpuMs = gpu[i];
        all &= gpu[i] >= 0.0;
        total += std::max(gpu[i], 0.0);
    }
    slot.stats.gpuMs = all ? total : -1.0;
    stats = slot.stats;
}

// ---- public API -------------------------------------------------------------------------------

Renderer::Renderer(uint32_t width, uint32_t height, const RenderSettings& settings) {
    if (width == 0 || height == 0)
        throw InvalidArgument("render target size must be positive (got " + std::to_string(width) +
                              "x" + std::to_string(height) + ")");
    settings.validate();
    mImpl = std::make_unique<Impl>(width, height, settings);
}

Renderer::~Renderer() = default;

uint32_t Renderer::width() const { return mImpl->width; }
uint32_t Renderer::height() const { return mImpl->height; }
const RenderSettings& Renderer::settings() const { return mImpl->settings; }
const FrameStats& Renderer::stats() const { return mImpl->stats; }
std::string Renderer::deviceName() const { return mImpl->ctx->properties().deviceName; }

void Renderer::setSettings(const RenderSettings& settings) {
    settings.validate();
    mImpl->settings = settings;
    // captures shade the scene with these settings: taken again at the next frame
    mImpl->probe.invalidate();
    mImpl->bounce.invalidate();
}

void Renderer::resize(uint32_t width, uint32_t height) {
    if (width == 0 || height == 0)
        throw InvalidArgument("render target size must be positive (got " + std::to_string(width) +
                              "x" + std::to_string(height) + ")");
    const auto limit = mImpl->ctx->properties().limits.maxImageDimension2D;
    if (width > limit || height > limit)
        throw InvalidArgument("render target size exceeds the device limit " +
                              std::to_string(limit));
    mImpl->width = width;
    mImpl->height = height;
}

Frame Renderer::render(const Scene& scene, const Camera& camera, uint32_t outputs) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    camera.validate();
    if ((outputs & (OutputColor | OutputLinear | OutputDebug)) == 0)
        throw InvalidArgument("render: ask for at least one output");
    Impl& m = *mImpl;
    FrameSlot& slot = m.beginFrame();
    m.targets.ensure(*m.ctx, m.width, m.height, outputs & OutputDebug);
    m.recordFrame(slot, scene, camera, outputs, &m.targets.ldr, false);
    slot.serial = m.ctx->submit(slot.cmd);
    slot.statsPending = true;
    ++m.frameCounter;
    m.ctx->waitFor(slot.serial);
    m.finishStats(slot);

    Frame f;
    f.width = int(m.width);
    f.height = int(m.height);
    const size_t pixels = size_t(m.width) * m.height;
    auto floats = [&](vk::Image& im) {
        return vk::readFloats(m.targets.readbackFor(*m.ctx, &im).mapped(), pixels * 4,
                              im.desc().format);
    };
    if (outputs & OutputColor) {
        f.color = ImageU8(f.width, f.height, 4);
        std::memcpy(f.color.pixels.data(), m.targets.readbackFor(*m.ctx, &m.targets.ldr).mapped(),
                    pixels * 4);
    }
    if (outputs & OutputLinear) f.linear = floats(m.targets.hdr);
    if (outputs & OutputDebug) {
        f.position = floats(m.targets.position);
        f.normal = floats(m.targets.normal);
        f.surface = floats(m.targets.surface);
        f.albedo = floats(m.targets.albedo);
    }
    m.stats.cpuMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    return f;
}

ImageU8 Renderer::present(Window& window, const Scene& scene, const Camera& camera, bool capture) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    camera.validate();
    Impl& m = *mImpl;
    auto& n = vk::WindowAccess::native(window);
    if (capture && !n.transferSrc) throw Error("this swapchain does not allow screenshots");
    FrameSlot& slot = m.beginFrame();
    uint32_t index = 0;
    if (!n.acquire(slot.acquired, index)) return {}; // minimised: nothing to draw
    m.targets.ensure(*m.ctx, n.extent.width, n.extent.height, false);
    m.width = n.extent.width;
    m.height = n.extent.height;
    vk::Image& image = n.images[index];
    // Contents are discarded; the acquire semaphore is waited on at colour-output stage.
    image.layout = VK_IMAGE_LAYOUT_UNDEFINED;
    image.stage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    image.access = VK_ACCESS_2_NONE;
    m.recordFrame(slot, scene, camera, capture ? uint32_t(OutputColor) : 0u, &image, true);
    slot.serial =
        m.ctx->submit(slot.cmd, {slot.acquired}, {VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT},
                      {n.renderDone[index]});
    slot.statsPending = true;
    ++m.frameCounter;
    n.present(index);
    ImageU8 shot;
    if (capture) {
        m.ctx->waitFor(slot.serial);
        m.finishStats(slot);
        shot = ImageU8(int(n.extent.width), int(n.extent.height), 4);
        std::memcpy(shot.pixels.data(), m.targets.readbackFor(*m.ctx, &image).mapped(),
                    shot.pixels.size());
        if (n.format == VK_FORMAT_B8G8R8A8_SRGB || n.format == VK_FORMAT_B8G8R8A8_UNORM)
            for (size_t i = 0; i < shot.pixels.size(); i += 4)
                std::swap(shot.pixels[i], shot.pixels[i + 2]);
    }
    m.stats.cpuMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    return shot;
}

void render::setFrameOverlay(Renderer& renderer, FrameOverlay* overlay) {
    renderer.mImpl->overlay = overlay;
}

uint32_t Renderer::msaaSamples() const { return mImpl->supportedSamples(mImpl->settings.msaa); }

} // namespace weft
