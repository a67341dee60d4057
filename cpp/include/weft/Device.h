#pragma once
// Vulkan devices weft can use, and the validation-layer messages it collected.
#include <cstdint>
#include <string>
#include <vector>
#include <weft/Error.h>

namespace weft {

struct DeviceInfo {
    uint32_t index = 0; // position in Vulkan's enumeration (what WEFT_DEVICE=<n> means)
    std::string name;
    std::string type;       // "discrete", "integrated", "virtual", "cpu" or "other"
    std::string apiVersion; // e.g. "1.3.239"
    std::string driver;     // driver name/info when the device reports it
    bool selected = false;  // the device weft renders with
};

/// Every Vulkan device in the system. Selection prefers discrete, then integrated, then
/// virtual, then CPU devices; the environment variable WEFT_DEVICE (an index or a
/// case-insensitive name substring) overrides it. Throws Error when Vulkan is unusable.
std::vector<DeviceInfo> listDevices();

/// Validation messages (warnings and errors) seen since the last clear. Validation layers are
/// enabled when WEFT_VALIDATION=1 is set before the first Vulkan use.
std::vector<std::string> validationMessages();

/// Device memory weft holds through its allocator (all Renderers share one device): blocks
/// obtained from Vulkan, their bytes, and the bytes handed out of them. Zero when no Renderer
/// (or other Vulkan user) exists. For soak tests: flat after warm-up means no GPU leak.
struct DeviceMemoryStats {
    size_t blocks = 0;
    uint64_t reservedBytes = 0;
    uint64_t usedBytes = 0;
};
DeviceMemoryStats deviceMemoryStats();
void clearValidationMessages();
bool validationEnabled();

} // namespace weft
