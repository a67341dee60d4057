#pragma once
// SPIR-V compiled from glsl/ at build time (see glsl/WeftShaders.cmake), looked up by the
// shader's path relative to glsl/, e.g. "render/forward.frag".
#include <cstddef>
#include <cstdint>

namespace weft::vk {

struct EmbeddedShader {
    const char* name;
    const uint32_t* words;
    size_t wordCount;
};

extern const EmbeddedShader kEmbeddedShaders[];
extern const size_t kEmbeddedShaderCount;

/// Throws weft::Error naming the shader when it was not compiled into the library.
const EmbeddedShader& embeddedShader(const char* name);

} // namespace weft::vk
