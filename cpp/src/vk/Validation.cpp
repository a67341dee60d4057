#include "vk/Validation.h"

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <mutex>
#include <vector>

#include <weft/Device.h>

namespace weft::vk {
namespace {
std::mutex gMessageMutex;
std::vector<std::string> gMessages;
} // namespace

bool envFlag(const char* name) {
    const char* v = std::getenv(name);
    return v && *v && std::strcmp(v, "0") != 0;
}

void recordValidationMessage(const std::string& text) {
    {
        std::lock_guard<std::mutex> lock(gMessageMutex);
        gMessages.push_back(text);
    }
    if (envFlag("WEFT_VALIDATION_PRINT")) std::cerr << "[weft validation] " << text << "\n";
}

} // namespace weft::vk

namespace weft {

bool validationEnabled() { return vk::envFlag("WEFT_VALIDATION"); }

std::vector<std::string> validationMessages() {
    std::lock_guard<std::mutex> lock(vk::gMessageMutex);
    return vk::gMessages;
}

void clearValidationMessages() {
    std::lock_guard<std::mutex> lock(vk::gMessageMutex);
    vk::gMessages.clear();
}

} // namespace weft
