#pragma once
// What every dynamic-rendering pass sets up: its attachments and a viewport with scissor over
// the target (used by FrameRecording.cpp and HairPasses.cpp).
#include <algorithm>
#include <cstring>

#include <glm/glm.hpp>

#include "vk/Resources.h"

namespace weft::render {

/// Grows a host-visible buffer to hold `bytes` (half as much again, so that a slowly growing
/// frame does not make a new one each time).
inline void ensureBuffer(vk::Context& ctx, vk::Buffer& buffer, VkDeviceSize bytes,
                         VkBufferUsageFlags usage) {
    bytes = std::max<VkDeviceSize>(bytes, 256);
    if (buffer && buffer.size() >= bytes) return;
    buffer = vk::Buffer(&ctx, bytes * 3 / 2, usage, vk::MemoryUsage::Upload);
}

/// An attachment stored after the pass; `clear`: cleared first (values below), else loaded.
inline VkRenderingAttachmentInfo attachment(VkImageView view, VkImageLayout layout, bool clear) {
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = view;
    a.imageLayout = layout;
    a.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    return a;
}

/// A colour attachment cleared to `value`.
inline VkRenderingAttachmentInfo clearedColor(VkImageView view, const glm::vec4& value) {
    VkRenderingAttachmentInfo a = attachment(view, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true);
    std::memcpy(a.clearValue.color.float32, &value, sizeof(value));
    return a;
}

/// A depth attachment cleared to the far plane (1); `store`: kept after the pass.
inline VkRenderingAttachmentInfo clearedDepth(VkImageView view, bool store = true) {
    VkRenderingAttachmentInfo a = attachment(view, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, true);
    a.storeOp = store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.clearValue.depthStencil = {1.0f, 0};
    return a;
}

inline void setViewport(VkCommandBuffer cmd, uint32_t w, uint32_t h) {
    VkViewport vp{0, 0, float(w), float(h), 0.0f, 1.0f};
    VkRect2D sc{{0, 0}, {w, h}};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &sc);
}

} // namespace weft::render
