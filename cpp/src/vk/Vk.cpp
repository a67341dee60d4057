#include "vk/Vk.h"

#include <sstream>

namespace weft::vk {

const char* resultName(VkResult result) {
    switch (result) {
#define WEFT_CASE(x)                                                                               \
    case x: return #x;
        WEFT_CASE(VK_SUCCESS)
        WEFT_CASE(VK_NOT_READY)
        WEFT_CASE(VK_TIMEOUT)
        WEFT_CASE(VK_INCOMPLETE)
        WEFT_CASE(VK_SUBOPTIMAL_KHR)
        WEFT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        WEFT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        WEFT_CASE(VK_ERROR_INITIALIZATION_FAILED)
        WEFT_CASE(VK_ERROR_DEVICE_LOST)
        WEFT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        WEFT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        WEFT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        WEFT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        WEFT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        WEFT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        WEFT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        WEFT_CASE(VK_ERROR_SURFACE_LOST_KHR)
        WEFT_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        WEFT_CASE(VK_ERROR_OUT_OF_DATE_KHR)
        WEFT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
#undef WEFT_CASE
    default: return "VkResult(unknown)";
    }
}

void throwVkError(VkResult result, const char* call, const char* file, int line) {
    std::ostringstream msg;
    msg << "Vulkan call failed: " << call << " returned " << resultName(result) << " ("
        << int(result) << ") at " << file << ":" << line;
    throw Error(msg.str());
}

} // namespace weft::vk
