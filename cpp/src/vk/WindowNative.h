#pragma once
// The window's native side: GLFW window, Vulkan surface and swapchain (private to the library).
#include <functional>
#include <memory>
#include <vector>

#include <GLFW/glfw3.h>

#include <weft/Window.h>

#include "vk/Resources.h"

namespace weft {

struct Window::Native {
    GLFWwindow* window = nullptr;
    std::shared_ptr<vk::Context> ctx;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{0, 0};
    bool vsync = true;
    bool transferSrc = false; // swapchain images can be copied (screenshots)
    bool outOfDate = false;
    std::vector<VkImageView> views;
    std::vector<vk::Image> images;         // non-owning wrappers with tracked state
    std::vector<vk::Semaphore> renderDone; // one per swapchain image
    std::function<void(int, int)> keyCallback;
    std::function<void(int, int, double, double)> mouseButtonCallback;
    std::function<void(double, double)> cursorCallback;

    /// (Re)creates the swapchain for the current framebuffer size; false while minimised.
    bool recreate();
    /// Acquires the next image, recreating the swapchain when it is out of date. Returns false
    /// when no image can be had now (minimised window).
    bool acquire(VkSemaphore signal, uint32_t& index);
    void present(uint32_t index);
    void destroySwapchain();
    ~Native();
};

namespace vk {
/// The native side of a Window, for the renderer and the demo's panel (not on the public API).
struct WindowAccess {
    static Window::Native& native(Window& window) { return *window.mNative; }
};
} // namespace vk

} // namespace weft
