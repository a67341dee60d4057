#pragma once
// The Vulkan validation layers' messages, collected for weft/Device.h's validationMessages():
// kept outside any context so tests can read them after a renderer is gone.
#include <string>

namespace weft::vk {

/// True when the environment variable is set to anything but "" or "0".
bool envFlag(const char* name);

/// Keeps one message (printed to stderr as well when WEFT_VALIDATION_PRINT is set).
void recordValidationMessage(const std::string& text);

} // namespace weft::vk
