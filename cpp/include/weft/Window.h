#pragma once
// A GLFW window with a Vulkan swapchain. Creating one without a display throws Error.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <weft/Error.h>

namespace weft {

namespace vk {
struct WindowAccess; // the renderer's way to the swapchain (vk/WindowNative.h)
}

class Window {
public:
    Window(int width, int height, const std::string& title, bool vsync = true);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    /// True when a display is available (GLFW can initialise).
    static bool displayAvailable();

    bool shouldClose() const;
    void requestClose();
    void pollEvents();
    void setTitle(const std::string& title);
    /// Framebuffer size in pixels (0 when minimised).
    void framebufferSize(int& width, int& height) const;
    bool vsync() const { return mVsync; }
    /// Key callback: (GLFW key code, action) with action 1 = press, 0 = release, 2 = repeat.
    void onKey(std::function<void(int, int)> callback);
    /// Mouse button callback: (GLFW button, action 1 press / 0 release, cursor x, y in pixels).
    void onMouseButton(std::function<void(int, int, double, double)> callback);
    /// Cursor movement callback: (x, y) in pixels from the top-left corner.
    void onCursor(std::function<void(double, double)> callback);

private:
    friend struct vk::WindowAccess;
    struct Native; // GLFW window + Vulkan surface/swapchain, owned here, used by the renderer
    std::unique_ptr<Native> mNative;
    bool mVsync;
};

} // namespace weft
