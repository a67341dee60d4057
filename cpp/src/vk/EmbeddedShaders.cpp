#include "vk/EmbeddedShaders.h"

#include <cstring>
#include <string>

#include <weft/Error.h>

namespace weft::vk {

const EmbeddedShader& embeddedShader(const char* name) {
    for (size_t i = 0; i < kEmbeddedShaderCount; ++i)
        if (std::strcmp(kEmbeddedShaders[i].name, name) == 0) return kEmbeddedShaders[i];
    throw Error(std::string("shader not embedded in the library: ") + name);
}

} // namespace weft::vk
