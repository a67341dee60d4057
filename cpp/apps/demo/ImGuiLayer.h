#pragma once
// Dear ImGui (Debian's libimgui-dev, with its GLFW and Vulkan backends) over a weft window: the
// context, the backends, and the pass that draws a frame's widgets over the tone-mapped image
// before it is presented (a render::FrameOverlay). Only weft-demo's window uses it.
#include <unordered_map>

#include <weft/Renderer.h>
#include <weft/Window.h>

#include "render/FrameOverlay.h"
#include "vk/Vk.h"

namespace weft::vk {
class Context;
}

namespace weft::demo {

class ImGuiLayer : public render::FrameOverlay {
public:
    /// Sets ImGui up for `window` and hooks it into `renderer`'s present() frames.
    ImGuiLayer(Window& window, Renderer& renderer);
    /// Unhooks from the renderer, waits for the frames that drew with it and shuts ImGui down.
    ~ImGuiLayer() override;
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    /// Starts a frame's widgets (ImGui::NewFrame); end it with endFrame.
    void beginFrame();
    /// Ends them (ImGui::Render); with `draw` the next present() draws them.
    void endFrame(bool draw);

    void addPasses(render::FrameGraph& g, render::FramePassContext& f) override;

private:
    VkFramebuffer framebuffer(VkImageView view, uint32_t width, uint32_t height);
    void dropFramebuffers();

    Window& mWindow;
    Renderer& mRenderer;
    vk::Context& mCtx;
    VkFormat mFormat;
    VkRenderPass mRenderPass = VK_NULL_HANDLE;
    VkDescriptorPool mPool = VK_NULL_HANDLE;
    bool mDraw = false;
    // One framebuffer per swapchain image view, made again when the swapchain is.
    VkSwapchainKHR mSwapchain = VK_NULL_HANDLE;
    std::unordered_map<VkImageView, VkFramebuffer> mFramebuffers;
};

} // namespace weft::demo
