// weft/Debug.h: the last frame's shadow maps, reflection probe and deep opacity maps, read back.
#include <weft/Debug.h>

#include <cstring>
#include <string>

#include "render/RendererImpl.h"

namespace weft::debug {

using render::Use;

struct RendererAccess {
    static Renderer::Impl& impl(Renderer& r) { return *r.mImpl; }
    static const Renderer::Impl& impl(const Renderer& r) { return *r.mImpl; }
};

ShadowInfo shadowInfo(const Renderer& renderer, int lightIndex) {
    const auto& m = RendererAccess::impl(renderer);
    if (lightIndex < 0 || size_t(lightIndex) >= m.shadowInfos.size())
        throw InvalidArgument("light index " + std::to_string(lightIndex) +
                              " is not a light of the last rendered scene");
    return m.shadowInfos[size_t(lightIndex)];
}

HairDomInfo hairDeepOpacity(const Renderer& renderer, int lightIndex) {
    const auto& m = RendererAccess::impl(renderer);
    if (!m.hair) throw InvalidArgument("the last rendered scene had no hair");
    return m.hair->domInfo(lightIndex);
}

std::vector<float> reflectionProbe(Renderer& renderer, uint32_t* sizeOut) {
    auto& m = RendererAccess::impl(renderer);
    if (m.probe.instance() < 0)
        throw InvalidArgument("the last rendered scene had no material with dynamic_reflection");
    vk::Image& cube = m.probe.cube();
    const uint32_t size = cube.desc().width;
    const size_t values = size_t(6) * size * size * 4;
    const VkDeviceSize bytes = VkDeviceSize(6) * size * size * vk::formatBytes(cube.desc().format);
    vk::Buffer buffer(m.ctx.get(), bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      vk::MemoryUsage::Readback);
    m.ctx->immediate([&](VkCommandBuffer cmd) {
        const render::UseState s = render::useState(Use::TransferRead, false);
        vk::transition(*m.ctx, cmd, cube, s.layout, s.stage, s.access);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 6};
        region.imageExtent = {size, size, 1};
        vkCmdCopyImageToBuffer(cmd, cube.get(), s.layout, buffer.get(), 1, &region);
    });
    std::vector<float> out = vk::readFloats(buffer.mapped(), values, cube.desc().format);
    if (sizeOut) *sizeOut = size;
    return out;
}

std::vector<float> shadowMap(Renderer& renderer, int lightIndex, uint32_t* sizeOut, int view) {
    const ShadowInfo info = shadowInfo(renderer, lightIndex);
    if (!info.active)
        throw InvalidArgument("light " + std::to_string(lightIndex) +
                              " cast no shadow in the last frame");
    if (view < 0 || size_t(view) >= info.views.size())
        throw InvalidArgument("light " + std::to_string(lightIndex) + " has " +
                              std::to_string(info.views.size()) + " shadow view(s), not view " +
                              std::to_string(view));
    auto& m = RendererAccess::impl(renderer);
    const uint32_t size = m.shadowMaps.desc().width;
    vk::Buffer buffer(m.ctx.get(), VkDeviceSize(size) * size * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      vk::MemoryUsage::Readback);
    m.ctx->immediate([&](VkCommandBuffer cmd) {
        const render::UseState s = render::useState(Use::TransferRead, true);
        vk::transition(*m.ctx, cmd, m.shadowMaps, s.layout, s.stage, s.access);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, uint32_t(info.layer + view), 1};
        region.imageExtent = {size, size, 1};
        vkCmdCopyImageToBuffer(cmd, m.shadowMaps.get(), s.layout, buffer.get(), 1, &region);
    });
    std::vector<float> out(size_t(size) * size);
    std::memcpy(out.data(), buffer.mapped(), out.size() * sizeof(float));
    if (sizeOut) *sizeOut = size;
    return out;
}

} // namespace weft::debug
