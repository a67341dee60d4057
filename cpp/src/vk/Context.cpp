#include "vk/Context.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

#include <weft/Device.h>

#include "vk/Validation.h"

namespace weft::vk {
namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void*) {
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
    std::string text =
        (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error: " : "warning: ");
    text += data && data->pMessage ? data->pMessage : "(no message)";
    recordValidationMessage(text);
    return VK_FALSE;
}

bool hasLayer(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

std::vector<std::string> instanceExtensions() {
    uint32_t n = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> props(n);
    vkEnumerateInstanceExtensionProperties(nullptr, &n, props.data());
    std::vector<std::string> names;
    for (auto& p : props) names.emplace_back(p.extensionName);
    return names;
}

bool deviceHasExtension(VkPhysicalDevice pd, const char* name) {
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> props(n);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, props.data());
    for (auto& p : props)
        if (std::strcmp(p.extensionName, name) == 0) return true;
    return false;
}

int typeRank(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
    }
}

// A device weft can drive: Vulkan 1.2+ with dynamic rendering and synchronization2 (core in 1.3),
// and a graphics queue.
bool usable(VkPhysicalDevice pd) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    if (p.apiVersion < VK_API_VERSION_1_2) return false;
    if (p.apiVersion < VK_API_VERSION_1_3 && !(deviceHasExtension(pd, "VK_KHR_dynamic_rendering") &&
                                               deviceHasExtension(pd, "VK_KHR_synchronization2")))
        return false;
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
    std::vector<VkQueueFamilyProperties> q(n);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, q.data());
    for (auto& f : q)
        if (f.queueFlags & VK_QUEUE_GRAPHICS_BIT) return true;
    return false;
}

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// Index (into `devices`) of the device to use: WEFT_DEVICE wins, else the best-ranked type.
size_t chooseDevice(const std::vector<VkPhysicalDevice>& devices) {
    if (devices.empty())
        throw Error("no Vulkan device found (install mesa-vulkan-drivers for lavapipe)");
    if (const char* want = std::getenv("WEFT_DEVICE"); want && *want) {
        std::string w = want;
        bool numeric = std::all_of(w.begin(), w.end(), [](char c) { return std::isdigit(c); });
        if (numeric) {
            size_t i = std::stoul(w);
            if (i >= devices.size())
                throw Error("WEFT_DEVICE=" + w + " but only " + std::to_string(devices.size()) +
                            " Vulkan device(s) exist");
            if (!usable(devices[i]))
                throw Error("WEFT_DEVICE=" + w + " lacks Vulkan 1.2 + dynamic rendering");
            return i;
        }
        for (size_t i = 0; i < devices.size(); ++i) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(devices[i], &p);
            if (lower(p.deviceName).find(lower(w)) != std::string::npos && usable(devices[i]))
                return i;
        }
        throw Error("WEFT_DEVICE='" + w + "' matches no usable Vulkan device");
    }
    size_t best = devices.size();
    int bestRank = 99;
    for (size_t i = 0; i < devices.size(); ++i) {
        if (!usable(devices[i])) continue;
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        if (typeRank(p.deviceType) < bestRank) {
            bestRank = typeRank(p.deviceType);
            best = i;
        }
    }
    if (best == devices.size())
        throw Error("no Vulkan device supports Vulkan 1.2 with dynamic rendering");
    return best;
}

std::mutex gSharedMutex;
std::weak_ptr<Context> gShared;

} // namespace

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
    uint32_t n = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, nullptr));
    std::vector<VkPhysicalDevice> devices(n);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, devices.data()));
    return devices;
}

std::shared_ptr<Context> Context::existing() {
    std::lock_guard<std::mutex> lock(gSharedMutex);
    return gShared.lock();
}

std::shared_ptr<Context> Context::shared() {
    std::lock_guard<std::mutex> lock(gSharedMutex);
    if (auto ctx = gShared.lock()) return ctx;
    std::shared_ptr<Context> ctx(new Context());
    gShared = ctx;
    return ctx;
}

Context::Context() {
    createInstance();
    try {
        pickPhysicalDevice();
        createDevice();
    } catch (...) {
        if (mDevice) vkDestroyDevice(mDevice, nullptr);
        if (mMessenger) {
            auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(mInstance, "vkDestroyDebugUtilsMessengerEXT"));
            destroy(mInstance, mMessenger, nullptr);
        }
        vkDestroyInstance(mInstance, nullptr);
        throw;
    }
}

Context::~Context() {
    mCache.clear(); // its Vulkan objects retire into the queue emptied below
    if (mDevice) {
        vkDeviceWaitIdle(mDevice); // teardown only, never in a frame loop
        collectGarbage();
        while (!mRetired.empty()) {
            mRetired.front().second();
            mRetired.pop_front();
        }
        mAllocator.reset();
        vkDestroyCommandPool(mDevice, mCommandPool, nullptr);
        vkDestroySemaphore(mDevice, mTimeline, nullptr);
        vkDestroyDevice(mDevice, nullptr);
    }
    if (mMessenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(mInstance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(mInstance, mMessenger, nullptr);
    }
    vkDestroyInstance(mInstance, nullptr);
}

void Context::createInstance() {
    const bool validation = validationEnabled();
    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    const auto available = instanceExtensions();
    auto has = [&](const char* e) {
        return std::find(available.begin(), available.end(), e) != available.end();
    };
    if (validation) {
        if (!hasLayer("VK_LAYER_KHRONOS_validation"))
            throw Error("WEFT_VALIDATION=1 but VK_LAYER_KHRONOS_validation is not installed "
                        "(Debian: apt-get install vulkan-validationlayers)");
        layers.push_back("VK_LAYER_KHRONOS_validation");
    }
    // Synchronization validation too: lavapipe runs every command in order, so a missing barrier
    // shows only on a GPU; the layer finds it on any device (measured: no slower on the tests).
    uint32_t count = 0;
    std::vector<VkExtensionProperties> layerExtensions;
    if (validation && vkEnumerateInstanceExtensionProperties("VK_LAYER_KHRONOS_validation", &count,
                                                             nullptr) == VK_SUCCESS) {
        layerExtensions.resize(count);
        vkEnumerateInstanceExtensionProperties("VK_LAYER_KHRONOS_validation", &count,
                                               layerExtensions.data());
    }
    const bool syncValidation =
        std::any_of(layerExtensions.begin(), layerExtensions.end(), [](const auto& e) {
            return std::strcmp(e.extensionName, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME) == 0;
        });
    if (syncValidation) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    if (validation || has("VK_EXT_debug_utils")) {
        if (has("VK_EXT_debug_utils")) extensions.push_back("VK_EXT_debug_utils");
    }
    // Surface extensions are enabled whenever present so a window can be opened later.
    for (const char* e : {"VK_KHR_surface", "VK_KHR_xcb_surface", "VK_KHR_xlib_surface",
                          "VK_KHR_wayland_surface", "VK_KHR_win32_surface", "VK_EXT_metal_surface"})
        if (has(e)) extensions.push_back(e);
    bool portability = has("VK_KHR_portability_enumeration");
    if (portability) extensions.push_back("VK_KHR_portability_enumeration");

    uint32_t loaderVersion = VK_API_VERSION_1_0;
    vkEnumerateInstanceVersion(&loaderVersion);
    if (loaderVersion < VK_API_VERSION_1_2)
        throw Error("the Vulkan loader supports only " + versionString(loaderVersion) +
                    "; weft needs 1.2 or newer");

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "weft";
    app.pEngineName = "weft";
    app.apiVersion = loaderVersion >= VK_API_VERSION_1_3 ? VK_API_VERSION_1_3 : VK_API_VERSION_1_2;

    VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    dbg.pfnUserCallback = debugCallback;

    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    if (portability) info.flags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;
    if (validation) info.pNext = &dbg;
    const VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    if (syncValidation) {
        features.pNext = &dbg;
        info.pNext = &features;
    }
    VK_CHECK(vkCreateInstance(&info, nullptr, &mInstance));

    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(mInstance, "vkCreateDebugUtilsMessengerEXT"));
        if (!create) throw Error("validation requested but VK_EXT_debug_utils is unavailable");
        VK_CHECK(create(mInstance, &dbg, nullptr, &mMessenger));
    }
}

void Context::pickPhysicalDevice() {
    const auto devices = physicalDevices(mInstance);
    mPhysical = devices[chooseDevice(devices)];
    vkGetPhysicalDeviceProperties(mPhysical, &mProperties);
}

void Context::createDevice() {
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(mPhysical, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(mPhysical, &n, families.data());
    mQueueFamily = UINT32_MAX;
    for (uint32_t i = 0; i < n; ++i) {
        if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) &&
            (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) {
            mQueueFamily = i;
            break;
        }
    }
    if (mQueueFamily == UINT32_MAX) throw Error("the Vulkan device has no graphics+compute queue");
    if (families[mQueueFamily].timestampValidBits > 0)
        mTimestampPeriodNs = mProperties.limits.timestampPeriod;

    const bool core13 = mProperties.apiVersion >= VK_API_VERSION_1_3;
    std::vector<const char*> extensions;
    if (!core13) {
        extensions.push_back("VK_KHR_dynamic_rendering");
        extensions.push_back("VK_KHR_synchronization2");
    }
    mHasSwapchain = deviceHasExtension(mPhysical, VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    if (mHasSwapchain) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);

    VkPhysicalDeviceDynamicRenderingFeatures dyn{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
    dyn.dynamicRendering = VK_TRUE;
    VkPhysicalDeviceSynchronization2Features sync2{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES};
    sync2.synchronization2 = VK_TRUE;
    sync2.pNext = &dyn;
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    v12.timelineSemaphore = VK_TRUE;
    v12.hostQueryReset = VK_TRUE;
    v12.pNext = &sync2;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &v12;
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(mPhysical, &supported);
    // hair anti-aliasing ORs each strand's sample coverage into a storage image
    features.features.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    q.queueFamilyIndex = mQueueFamily;
    q.queueCount = 1;
    q.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.pNext = &features;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &q;
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VK_CHECK(vkCreateDevice(mPhysical, &info, nullptr, &mDevice));
    vkGetDeviceQueue(mDevice, mQueueFamily, 0, &mQueue);

    auto load = [&](const char* core, const char* khr) {
        PFN_vkVoidFunction f = core13 ? vkGetDeviceProcAddr(mDevice, core) : nullptr;
        if (!f) f = vkGetDeviceProcAddr(mDevice, khr);
        if (!f) throw Error(std::string("Vulkan function missing: ") + core);
        return f;
    };
    mFn.cmdBeginRendering = reinterpret_cast<PFN_vkCmdBeginRendering>(
        load("vkCmdBeginRendering", "vkCmdBeginRenderingKHR"));
    mFn.cmdEndRendering =
        reinterpret_cast<PFN_vkCmdEndRendering>(load("vkCmdEndRendering", "vkCmdEndRenderingKHR"));
    mFn.cmdPipelineBarrier2 = reinterpret_cast<PFN_vkCmdPipelineBarrier2>(
        load("vkCmdPipelineBarrier2", "vkCmdPipelineBarrier2KHR"));

    mAllocator = std::make_unique<Allocator>(mPhysical, mDevice);

    VkSemaphoreTypeCreateInfo timeline{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
    timeline.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
    VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    sem.pNext = &timeline;
    VK_CHECK(vkCreateSemaphore(mDevice, &sem, nullptr, &mTimeline));

    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = mQueueFamily;
    VK_CHECK(vkCreateCommandPool(mDevice, &pool, nullptr, &mCommandPool));
}

uint64_t Context::submit(VkCommandBuffer cmd, const std::vector<VkSemaphore>& waits,
                         const std::vector<VkPipelineStageFlags>& waitStages,
                         const std::vector<VkSemaphore>& signals) {
    std::lock_guard<std::mutex> lock(mQueueMutex);
    const uint64_t serial = mLastSubmitted.load() + 1;
    std::vector<VkSemaphore> signalAll = signals;
    signalAll.push_back(mTimeline);
    std::vector<uint64_t> signalValues(signalAll.size(), 0);
    signalValues.back() = serial;
    std::vector<uint64_t> waitValues(waits.size(), 0);

    VkTimelineSemaphoreSubmitInfo tl{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    tl.waitSemaphoreValueCount = uint32_t(waitValues.size());
    tl.pWaitSemaphoreValues = waitValues.data();
    tl.signalSemaphoreValueCount = uint32_t(signalValues.size());
    tl.pSignalSemaphoreValues = signalValues.data();
    VkSubmitInfo info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    info.pNext = &tl;
    info.waitSemaphoreCount = uint32_t(waits.size());
    info.pWaitSemaphores = waits.data();
    info.pWaitDstStageMask = waitStages.data();
    info.commandBufferCount = 1;
    info.pCommandBuffers = &cmd;
    info.signalSemaphoreCount = uint32_t(signalAll.size());
    info.pSignalSemaphores = signalAll.data();
    VK_CHECK(vkQueueSubmit(mQueue, 1, &info, VK_NULL_HANDLE));
    mLastSubmitted = serial;
    return serial;
}

VkResult Context::present(const VkPresentInfoKHR& info) {
    std::lock_guard<std::mutex> lock(mQueueMutex);
    return vkQueuePresentKHR(mQueue, &info);
}

void Context::waitFor(uint64_t serial) {
    if (serial == 0) return;
    VkSemaphoreWaitInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
    info.semaphoreCount = 1;
    info.pSemaphores = &mTimeline;
    info.pValues = &serial;
    // Bounded wait: a hung GPU becomes an error instead of a hang.
    VkResult r = vkWaitSemaphores(mDevice, &info, 60ull * 1000 * 1000 * 1000);
    if (r == VK_TIMEOUT) throw Error("GPU did not finish a submission within 60 s");
    VK_CHECK(r);
}

uint64_t Context::completedSerial() const {
    uint64_t value = 0;
    VK_CHECK(vkGetSemaphoreCounterValue(mDevice, mTimeline, &value));
    return value;
}

void Context::retire(std::function<void()> destroy) {
    std::lock_guard<std::mutex> lock(mRetireMutex);
    mRetired.emplace_back(mLastSubmitted.load(), std::move(destroy));
}

void Context::collectGarbage() {
    const uint64_t done = completedSerial();
    std::vector<std::function<void()>> ready;
    {
        std::lock_guard<std::mutex> lock(mRetireMutex);
        while (!mRetired.empty() && mRetired.front().first <= done) {
            ready.push_back(std::move(mRetired.front().second));
            mRetired.pop_front();
        }
    }
    for (auto& f : ready) f();
}

void Context::immediate(const std::function<void(VkCommandBuffer)>& record) {
    std::lock_guard<std::mutex> lock(mImmediateMutex);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = mCommandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd;
    VK_CHECK(vkAllocateCommandBuffers(mDevice, &alloc, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));
    waitFor(submit(cmd));
    vkFreeCommandBuffers(mDevice, mCommandPool, 1, &cmd);
}

std::shared_ptr<void> Context::cached(const std::string& key,
                                      const std::function<std::shared_ptr<void>()>& make) {
    std::lock_guard<std::mutex> lock(mCacheMutex);
    std::shared_ptr<void>& slot = mCache[key];
    if (!slot) slot = make();
    return slot;
}

} // namespace weft::vk
