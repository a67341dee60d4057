// weft/Device.h: the Vulkan devices weft can use and the device memory it holds.
#include <weft/Device.h>

#include <memory>
#include <string>
#include <vector>

#include "vk/Context.h"

namespace weft::vk {

std::string deviceTypeName(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
    }
}

std::string versionString(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
           "." + std::to_string(VK_API_VERSION_PATCH(v));
}

} // namespace weft::vk

namespace weft {

std::vector<DeviceInfo> listDevices() {
    auto ctx = vk::Context::shared();
    const auto devices = vk::physicalDevices(ctx->instance());
    std::vector<DeviceInfo> out;
    for (size_t i = 0; i < devices.size(); ++i) {
        VkPhysicalDeviceProperties2 p{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
        VkPhysicalDeviceDriverProperties driver{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
        p.pNext = &driver;
        vkGetPhysicalDeviceProperties2(devices[i], &p);
        DeviceInfo d;
        d.index = uint32_t(i);
        d.name = p.properties.deviceName;
        d.type = vk::deviceTypeName(p.properties.deviceType);
        d.apiVersion = vk::versionString(p.properties.apiVersion);
        d.driver = std::string(driver.driverName) + " " + driver.driverInfo;
        d.selected = devices[i] == ctx->physicalDevice();
        out.push_back(d);
    }
    return out;
}

DeviceMemoryStats deviceMemoryStats() {
    const std::shared_ptr<vk::Context> ctx = vk::Context::existing();
    DeviceMemoryStats out;
    if (!ctx) return out;
    const vk::Allocator::Stats s = ctx->allocator().stats();
    out.blocks = s.blocks;
    out.reservedBytes = uint64_t(s.reserved);
    out.usedBytes = uint64_t(s.used);
    return out;
}

} // namespace weft
