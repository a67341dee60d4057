#pragma once
// Where a shader's SPIR-V comes from: a hot-reloaded version (see weft/ShaderReload.h) when
// one was compiled, else the words embedded at build time.
#include <cstdint>
#include <vector>

namespace weft::vk {

/// The SPIR-V of a shader by its path relative to glsl/ ("render/forward.frag").
std::vector<uint32_t> shaderWords(const char* name);

} // namespace weft::vk
