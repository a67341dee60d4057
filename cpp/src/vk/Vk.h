#pragma once
// Vulkan include and the VK_CHECK macro: every failing call becomes a weft::Error that names
// the call, the result, the file and the line.
#include <string>

#include <vulkan/vulkan.h>

#include <weft/Error.h>

namespace weft::vk {

const char* resultName(VkResult result);
[[noreturn]] void throwVkError(VkResult result, const char* call, const char* file, int line);

} // namespace weft::vk

#define VK_CHECK(call)                                                                             \
    do {                                                                                           \
        VkResult weftVkResult_ = (call);                                                           \
        if (weftVkResult_ != VK_SUCCESS)                                                           \
            ::weft::vk::throwVkError(weftVkResult_, #call, __FILE__, __LINE__);                    \
    } while (0)
