#include "render/RenderTargets.h"

namespace weft::render {

namespace {
vk::Image makeTarget(vk::Context& ctx, uint32_t w, uint32_t h, VkFormat format,
                     VkImageUsageFlags usage, uint32_t samples = 1) {
    vk::ImageDesc d;
    d.samples = VkSampleCountFlagBits(samples);
    d.width = w;
    d.height = h;
    d.format = format;
    d.usage = usage;
    return vk::Image(&ctx, d);
}
} // namespace

void RenderTargets::ensure(vk::Context& ctx, uint32_t w, uint32_t h, bool debug) {
    constexpr VkImageUsageFlags color =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if (w != width || h != height || !hdr) {
        width = w;
        height = h;
        mReadback.clear();
        hdr = makeTarget(ctx, w, h, kHdrFormat, color | VK_IMAGE_USAGE_SAMPLED_BIT);
        depth =
            makeTarget(ctx, w, h, kDepthFormat,
                       VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
        ldr = makeTarget(ctx, w, h, kLdrFormat, color);
        position = vk::Image();
        normal = vk::Image();
        surface = vk::Image();
        albedo = vk::Image();
        dome = vk::Image();
        domeAux = vk::Image();
        domeVisibility = vk::Image();
        domeRows = vk::Image();
        hdrMs = vk::Image();
        depthMs = vk::Image();
        domeMs = vk::Image();
        domeAuxMs = vk::Image();
    }
    if (debug && !position) {
        position = makeTarget(ctx, w, h, kDebugFormat, color);
        normal = makeTarget(ctx, w, h, kDebugFormat, color);
        surface = makeTarget(ctx, w, h, kDebugFormat, color);
        albedo = makeTarget(ctx, w, h, kDebugFormat, color);
    }
}

void RenderTargets::ensureDome(vk::Context& ctx) {
    constexpr VkImageUsageFlags usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    if (!dome) dome = makeTarget(ctx, width, height, kDomeFormat, usage);
    if (!domeAux) domeAux = makeTarget(ctx, width, height, kDomeAuxFormat, usage);
    if (!domeVisibility) domeVisibility = makeTarget(ctx, width, height, kDomeBlurFormat, usage);
    if (!domeRows) domeRows = makeTarget(ctx, width, height, kDomeBlurFormat, usage);
}

void RenderTargets::ensureMultisampled(vk::Context& ctx, uint32_t count, bool withDome) {
    if (count != samples) {
        samples = count;
        hdrMs = vk::Image();
        depthMs = vk::Image();
        domeMs = vk::Image();
        domeAuxMs = vk::Image();
    }
    if (!hdrMs) {
        hdrMs =
            makeTarget(ctx, width, height, kHdrFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, count);
        depthMs = makeTarget(ctx, width, height, kDepthFormat,
                             VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, count);
    }
    if (withDome && !domeMs) {
        domeMs =
            makeTarget(ctx, width, height, kDomeFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, count);
        domeAuxMs = makeTarget(ctx, width, height, kDomeAuxFormat,
                               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, count);
    }
}

vk::Buffer& RenderTargets::readbackFor(vk::Context& ctx, const vk::Image* image) {
    const VkDeviceSize bytes = VkDeviceSize(image->desc().width) * image->desc().height *
                               vk::formatBytes(image->desc().format);
    vk::Buffer& b = mReadback[image];
    if (!b || b.size() != bytes)
        b = vk::Buffer(&ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::Readback);
    return b;
}

} // namespace weft::render
