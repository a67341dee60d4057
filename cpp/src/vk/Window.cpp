#include "vk/WindowNative.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>

namespace weft {
namespace {

std::mutex gGlfwMutex;
int gGlfwUsers = 0;
std::string gGlfwError;

void glfwErrorCallback(int, const char* description) {
    gGlfwError = description ? description : "";
}

// GLFW is initialised while any window exists. Opening the display connection can fail
// transiently (a busy X server refuses a connection now and then), so when a display is
// configured a failed initialisation is retried a few times before it counts.
bool acquireGlfw() {
    std::lock_guard<std::mutex> lock(gGlfwMutex);
    if (gGlfwUsers == 0) {
        glfwSetErrorCallback(glfwErrorCallback);
        const char* display = std::getenv("DISPLAY");
        const char* wayland = std::getenv("WAYLAND_DISPLAY");
        const bool configured = (display && *display) || (wayland && *wayland);
        bool ok = glfwInit();
        for (int attempt = 1; !ok && configured && attempt < 5; ++attempt) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20 * attempt));
            ok = glfwInit();
        }
        if (!ok) return false;
    }
    ++gGlfwUsers;
    return true;
}

void releaseGlfw() {
    std::lock_guard<std::mutex> lock(gGlfwMutex);
    if (--gGlfwUsers == 0) glfwTerminate();
}

} // namespace

bool Window::displayAvailable() {
    if (!acquireGlfw()) return false;
    const bool ok = glfwVulkanSupported() == GLFW_TRUE;
    releaseGlfw();
    return ok;
}

Window::Window(int width, int height, const std::string& title, bool vsync)
    : mNative(std::make_unique<Native>()), mVsync(vsync) {
    if (width <= 0 || height <= 0)
        throw InvalidArgument("window size must be positive (got " + std::to_string(width) + "x" +
                              std::to_string(height) + ")");
    if (!acquireGlfw()) throw Error("cannot open a window: no display (" + gGlfwError + ")");
    Native& n = *mNative;
    n.vsync = vsync;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    n.window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!n.window) {
        releaseGlfw();
        throw Error("glfwCreateWindow failed: " + gGlfwError);
    }
    glfwSetWindowUserPointer(n.window, &n);
    glfwSetKeyCallback(n.window, [](GLFWwindow* w, int key, int, int action, int) {
        auto* native = static_cast<Native*>(glfwGetWindowUserPointer(w));
        if (native->keyCallback) native->keyCallback(key, action);
    });
    glfwSetMouseButtonCallback(n.window, [](GLFWwindow* w, int button, int action, int) {
        auto* native = static_cast<Native*>(glfwGetWindowUserPointer(w));
        double x = 0, y = 0;
        glfwGetCursorPos(w, &x, &y);
        if (native->mouseButtonCallback) native->mouseButtonCallback(button, action, x, y);
    });
    glfwSetCursorPosCallback(n.window, [](GLFWwindow* w, double x, double y) {
        auto* native = static_cast<Native*>(glfwGetWindowUserPointer(w));
        if (native->cursorCallback) native->cursorCallback(x, y);
    });
    glfwSetFramebufferSizeCallback(n.window, [](GLFWwindow* w, int, int) {
        static_cast<Native*>(glfwGetWindowUserPointer(w))->outOfDate = true;
    });
    try {
        n.ctx = vk::Context::shared();
        if (!n.ctx->hasSwapchain())
            throw Error("the Vulkan device cannot present (no VK_KHR_swapchain)");
        VK_CHECK(glfwCreateWindowSurface(n.ctx->instance(), n.window, nullptr, &n.surface));
        VkBool32 supported = VK_FALSE;
        VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(n.ctx->physicalDevice(), n.ctx->queueFamily(),
                                                      n.surface, &supported));
        if (!supported) throw Error("the selected Vulkan queue cannot present to this window");
        n.recreate();
    } catch (...) {
        mNative.reset();
        throw;
    }
}

Window::~Window() = default;

Window::Native::~Native() {
    if (ctx) {
        ctx->waitFor(ctx->lastSubmitted());
        destroySwapchain();
        ctx->collectGarbage();
        ctx->waitFor(ctx->lastSubmitted());
        // Presentation may still reference the swapchain's semaphores; the queue drains first.
        vkQueueWaitIdle(ctx->queue());
        ctx->collectGarbage();
        if (surface) vkDestroySurfaceKHR(ctx->instance(), surface, nullptr);
    }
    if (window) {
        glfwDestroyWindow(window);
        releaseGlfw();
    }
}

void Window::Native::destroySwapchain() {
    images.clear();
    renderDone.clear();
    VkDevice device = ctx->device();
    std::vector<VkImageView> oldViews = std::move(views);
    views.clear();
    VkSwapchainKHR old = swapchain;
    swapchain = VK_NULL_HANDLE;
    ctx->retire([device, oldViews, old] {
        for (VkImageView v : oldViews) vkDestroyImageView(device, v, nullptr);
        if (old) vkDestroySwapchainKHR(device, old, nullptr);
    });
}

bool Window::Native::recreate() {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window, &w, &h);
    if (w == 0 || h == 0) return false;
    VkPhysicalDevice pd = ctx->physicalDevice();
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface, &caps));
    uint32_t n = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(n);
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, formats.data()));
    VkSurfaceFormatKHR chosen = formats.at(0);
    for (const auto& f : formats)
        if ((f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
            f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
            chosen = f;
    VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &n, nullptr));
    std::vector<VkPresentModeKHR> modes(n);
    VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &n, modes.data()));
    VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR; // always available: vsync
    if (!vsync)
        for (VkPresentModeKHR m : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
            if (std::find(modes.begin(), modes.end(), m) != modes.end()) {
                mode = m;
                break;
            }

    VkExtent2D e = caps.currentExtent;
    if (e.width == UINT32_MAX) {
        e.width = std::clamp(uint32_t(w), caps.minImageExtent.width, caps.maxImageExtent.width);
        e.height = std::clamp(uint32_t(h), caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    if (e.width == 0 || e.height == 0) return false;
    uint32_t count = std::max(caps.minImageCount + 1, 2u);
    if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);

    transferSrc = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface;
    info.minImageCount = count;
    info.imageFormat = chosen.format;
    info.imageColorSpace = chosen.colorSpace;
    info.imageExtent = e;
    info.imageArrayLayers = 1;
    info.imageUsage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (transferSrc ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    if (!(caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR))
        info.compositeAlpha = VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha &
                                                          -caps.supportedCompositeAlpha);
    info.presentMode = mode;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain;
    VkSwapchainKHR created;
    VK_CHECK(vkCreateSwapchainKHR(ctx->device(), &info, nullptr, &created));
    destroySwapchain();
    swapchain = created;
    format = chosen.format;
    extent = e;
    outOfDate = false;

    VK_CHECK(vkGetSwapchainImagesKHR(ctx->device(), swapchain, &n, nullptr));
    std::vector<VkImage> raw(n);
    VK_CHECK(vkGetSwapchainImagesKHR(ctx->device(), swapchain, &n, raw.data()));
    vk::ImageDesc desc;
    desc.width = e.width;
    desc.height = e.height;
    desc.format = format;
    desc.usage = info.imageUsage;
    for (VkImage image : raw) {
        VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        v.image = image;
        v.viewType = VK_IMAGE_VIEW_TYPE_2D;
        v.format = format;
        v.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view;
        VK_CHECK(vkCreateImageView(ctx->device(), &v, nullptr, &view));
        views.push_back(view);
        images.push_back(vk::Image::external(image, view, desc));
        VkSemaphoreCreateInfo s{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore sem;
        VK_CHECK(vkCreateSemaphore(ctx->device(), &s, nullptr, &sem));
        renderDone.emplace_back(ctx.get(), sem, vkDestroySemaphore);
    }
    return true;
}

bool Window::Native::acquire(VkSemaphore signal, uint32_t& index) {
    for (int attempt = 0; attempt < 3; ++attempt) {
        if ((outOfDate || swapchain == VK_NULL_HANDLE) && !recreate()) return false;
        VkResult r = vkAcquireNextImageKHR(ctx->device(), swapchain, 5ull * 1000 * 1000 * 1000,
                                           signal, VK_NULL_HANDLE, &index);
        if (r == VK_SUCCESS || r == VK_SUBOPTIMAL_KHR) {
            if (r == VK_SUBOPTIMAL_KHR) outOfDate = true; // recreate after this frame
            return true;
        }
        if (r == VK_ERROR_OUT_OF_DATE_KHR) {
            outOfDate = true;
            continue;
        }
        if (r == VK_TIMEOUT) throw Error("timed out acquiring a swapchain image");
        VK_CHECK(r);
    }
    return false;
}

void Window::Native::present(uint32_t index) {
    VkSemaphore wait = renderDone[index];
    VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &wait;
    info.swapchainCount = 1;
    info.pSwapchains = &swapchain;
    info.pImageIndices = &index;
    VkResult r = ctx->present(info);
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR)
        outOfDate = true;
    else
        VK_CHECK(r);
}

bool Window::shouldClose() const { return glfwWindowShouldClose(mNative->window); }
void Window::requestClose() { glfwSetWindowShouldClose(mNative->window, GLFW_TRUE); }
void Window::pollEvents() { glfwPollEvents(); }
void Window::setTitle(const std::string& title) {
    glfwSetWindowTitle(mNative->window, title.c_str());
}
void Window::framebufferSize(int& width, int& height) const {
    glfwGetFramebufferSize(mNative->window, &width, &height);
}
void Window::onKey(std::function<void(int, int)> callback) {
    mNative->keyCallback = std::move(callback);
}
void Window::onMouseButton(std::function<void(int, int, double, double)> callback) {
    mNative->mouseButtonCallback = std::move(callback);
}
void Window::onCursor(std::function<void(double, double)> callback) {
    mNative->cursorCallback = std::move(callback);
}

} // namespace weft
