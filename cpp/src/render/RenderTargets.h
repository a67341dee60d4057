#pragma once
// The renderer's offscreen images (sized to the output) and their readback buffers.
#include <unordered_map>

#include "vk/Resources.h"

namespace weft::render {

// Linear radiance in half floats (11-bit mantissa: 0.05% relative, up to 65504): half the
// bytes per sample of RGBA32F for the forward pass's MSAA target, its resolve, the probes and the
// hair composite; blending at full rate on GPUs whose ROPs blend 32-bit floats at a quarter of it.
constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDebugFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr VkFormat kLdrFormat = VK_FORMAT_R8G8B8A8_SRGB;
constexpr VkFormat kDomeFormat = VK_FORMAT_R16G16B16A16_SFLOAT; // dome diffuse + occlusion
constexpr VkFormat kDomeAuxFormat = VK_FORMAT_R16G16_SFLOAT;    // the casters' floor, fit albedo
constexpr VkFormat kDomeBlurFormat = VK_FORMAT_R32G32_SFLOAT;   // visibility, view depth

struct RenderTargets {
    uint32_t width = 0, height = 0;
    vk::Image hdr; // linear radiance
    vk::Image depth;
    vk::Image ldr;      // sRGB 8-bit (offscreen output)
    vk::Image position; // debug outputs, created on first request
    vk::Image normal;
    vk::Image surface;
    vk::Image albedo;
    // The forward pass's dome outputs for the blur (dome_gather.frag), created on first use
    vk::Image dome, domeAux;
    vk::Image domeVisibility; // the gather pass's output
    vk::Image domeRows;       // the blur's first (row) pass
    // Multisampled forward targets, resolved into hdr, depth (sample 0) and the dome's; made
    // when the forward pass renders with more than one sample.
    uint32_t samples = 1;
    vk::Image hdrMs, depthMs, domeMs, domeAuxMs;

    /// Creates the dome images at the current size on first request.
    void ensureDome(vk::Context& ctx);

    /// Creates the multisampled targets for `count` samples (dome: also the dome output's).
    void ensureMultisampled(vk::Context& ctx, uint32_t count, bool dome);

    /// (Re)creates the images for a size; debug images only when asked for.
    void ensure(vk::Context& ctx, uint32_t w, uint32_t h, bool debug);
    /// A host-visible buffer the size of `image` to copy it into.
    vk::Buffer& readbackFor(vk::Context& ctx, const vk::Image* image);

private:
    std::unordered_map<const vk::Image*, vk::Buffer> mReadback;
};

} // namespace weft::render
