#pragma once
// The process-wide Vulkan context: instance (+ validation), the selected physical device, one
// graphics queue, the memory allocator, and deferred destruction keyed to a timeline semaphore
// that every submission signals.
#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

#include "vk/Allocator.h"
#include "vk/Vk.h"

namespace weft::vk {

struct DeviceFunctions {
    PFN_vkCmdBeginRendering cmdBeginRendering = nullptr;
    PFN_vkCmdEndRendering cmdEndRendering = nullptr;
    PFN_vkCmdPipelineBarrier2 cmdPipelineBarrier2 = nullptr;
};

class Context {
public:
    /// The shared context, created on first use and destroyed when the last user lets go.
    static std::shared_ptr<Context> shared();
    /// The shared context if one lives, else null (creates nothing).
    static std::shared_ptr<Context> existing();
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return mInstance; }
    VkPhysicalDevice physicalDevice() const { return mPhysical; }
    VkDevice device() const { return mDevice; }
    VkQueue queue() const { return mQueue; }
    uint32_t queueFamily() const { return mQueueFamily; }
    const VkPhysicalDeviceProperties& properties() const { return mProperties; }
    const DeviceFunctions& fn() const { return mFn; }
    Allocator& allocator() { return *mAllocator; }
    bool hasSwapchain() const { return mHasSwapchain; }
    /// Nanoseconds per timestamp tick, or 0 when the queue cannot write timestamps.
    double timestampPeriodNs() const { return mTimestampPeriodNs; }

    /// Submits to the queue and signals the timeline; returns the serial to wait for.
    uint64_t submit(VkCommandBuffer cmd, const std::vector<VkSemaphore>& waits = {},
                    const std::vector<VkPipelineStageFlags>& waitStages = {},
                    const std::vector<VkSemaphore>& signals = {});
    /// Presents under the queue lock (the queue is shared by every renderer and window).
    VkResult present(const VkPresentInfoKHR& info);
    /// Serial of the last submission.
    uint64_t lastSubmitted() const { return mLastSubmitted.load(); }
    void waitFor(uint64_t serial);
    uint64_t completedSerial() const;

    /// Runs `destroy` once the GPU has finished everything submitted so far.
    void retire(std::function<void()> destroy);
    /// An object made by `make` on the first request for `key` and kept until the context goes
    /// (e.g. the compute pipelines of the offline tools, so repeated calls do not compile them).
    std::shared_ptr<void> cached(const std::string& key,
                                 const std::function<std::shared_ptr<void>()>& make);
    /// Runs the retired destructors whose submissions completed.
    void collectGarbage();

    /// Records commands into a one-time command buffer, submits them and waits (uploads).
    void immediate(const std::function<void(VkCommandBuffer)>& record);

private:
    Context();
    void createInstance();
    void pickPhysicalDevice();
    void createDevice();

    VkInstance mInstance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT mMessenger = VK_NULL_HANDLE;
    VkPhysicalDevice mPhysical = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties mProperties{};
    VkDevice mDevice = VK_NULL_HANDLE;
    VkQueue mQueue = VK_NULL_HANDLE;
    uint32_t mQueueFamily = 0;
    bool mHasSwapchain = false;
    double mTimestampPeriodNs = 0.0;
    DeviceFunctions mFn;
    std::unique_ptr<Allocator> mAllocator;
    std::mutex mCacheMutex;
    std::unordered_map<std::string, std::shared_ptr<void>> mCache; // see cached()

    // Thread safety: the queue and the immediate-upload pool are locked; each Renderer records
    // into command buffers from its own pool.
    VkSemaphore mTimeline = VK_NULL_HANDLE;
    std::atomic<uint64_t> mLastSubmitted{0};
    std::mutex mQueueMutex;
    std::mutex mImmediateMutex;
    VkCommandPool mCommandPool = VK_NULL_HANDLE; // for immediate()

    std::mutex mRetireMutex;
    std::deque<std::pair<uint64_t, std::function<void()>>> mRetired;
};

/// Instance-level helpers shared by Context and listDevices() (vk/Device.cpp).
std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance);
std::string deviceTypeName(VkPhysicalDeviceType type);
std::string versionString(uint32_t version);

} // namespace weft::vk
