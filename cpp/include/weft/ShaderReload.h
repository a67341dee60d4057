#pragma once
// Shader hot reload for development: GLSL files in a directory laid out like glsl/ replace the
// SPIR-V compiled into the library once they change. Renderers check for changes at the start
// of every frame, recompile what changed with libshaderc and swap their pipelines; a shader that
// fails to compile is reported (file and line) and the previous version stays in use.
#include <cstdint>
#include <string>
#include <vector>

namespace weft {

/// True when the library was built with libshaderc (hot reload available).
bool shaderHotReloadAvailable();

/// Watches `directory` (same layout as glsl/: render/forward.frag, common/*.glsl, ...). Files as
/// they are now are taken to match the embedded shaders; only later changes are compiled. An
/// empty string stops watching and drops all reloaded shaders. Throws Error without libshaderc
/// and InvalidArgument when the directory does not exist.
void setShaderDirectory(const std::string& directory);
std::string shaderDirectory();

/// Recompiles the shaders whose file or included files changed since the last check. Returns
/// how many compiled; failures are added to shaderErrors() and printed to stderr.
int pollShaderChanges();

/// Increases whenever a reloaded shader replaced the one in use (pipelines must be rebuilt).
uint64_t shaderGeneration();

/// Compile errors since the last clear, each "name: compiler message (file:line: ...)".
std::vector<std::string> shaderErrors();
void clearShaderErrors();

} // namespace weft
