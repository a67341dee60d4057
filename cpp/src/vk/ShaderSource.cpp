// Shader hot reload: a watched directory of GLSL sources, their include dependencies, change
// detection by file stamps, recompilation with libshaderc, and the SPIR-V that replaces the
// embedded words. All state is behind one mutex (renderers on several threads poll it).
#include "vk/ShaderSource.h"

#include <weft/Error.h>
#include <weft/ShaderReload.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#if WEFT_HAVE_SHADERC
#include <shaderc/shaderc.h>
#endif

#include "vk/EmbeddedShaders.h"

namespace fs = std::filesystem;

namespace weft {

namespace {

struct Stamp {
    fs::file_time_type time{};
    uintmax_t size = 0;
    bool operator!=(const Stamp& o) const { return time != o.time || size != o.size; }
};

struct ReloadState {
    std::mutex mutex;
    fs::path root;                                      // empty: not watching
    std::map<std::string, Stamp> stamps;                // every file under root, by rel. path
    std::map<std::string, std::vector<uint32_t>> spirv; // reloaded shaders by name
    std::vector<std::string> errors;
    uint64_t generation = 0;
};

ReloadState& state() {
    static ReloadState s;
    return s;
}

bool isStage(const fs::path& p) {
    static const std::set<std::string> stages = {".vert", ".frag", ".comp",
                                                 ".geom", ".tesc", ".tese"};
    return stages.count(p.extension().string()) > 0;
}

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Where `#include "name"` from file `from` resolves: next to it, then in common/ (glslc -I).
fs::path resolveInclude(const fs::path& root, const fs::path& from, const std::string& name) {
    const fs::path local = from.parent_path() / name;
    if (fs::exists(local)) return local;
    return root / "common" / name;
}

// The files a shader reads: itself and, recursively, what it #includes.
std::set<std::string> dependencies(const fs::path& root, const fs::path& file) {
    std::set<std::string> seen;
    std::vector<fs::path> todo{file};
    while (!todo.empty()) {
        const fs::path f = todo.back();
        todo.pop_back();
        if (!seen.insert(fs::relative(f, root).generic_string()).second || !fs::exists(f)) continue;
        std::istringstream lines(readText(f));
        for (std::string line; std::getline(lines, line);) {
            const size_t at = line.find("#include");
            if (at == std::string::npos) continue;
            const size_t q0 = line.find('"', at), q1 = line.find('"', q0 + 1);
            if (q0 != std::string::npos && q1 != std::string::npos)
                todo.push_back(resolveInclude(root, f, line.substr(q0 + 1, q1 - q0 - 1)));
        }
    }
    return seen;
}

std::map<std::string, Stamp> scan(const fs::path& root) {
    std::map<std::string, Stamp> out;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(root, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (!it->is_regular_file(ec)) continue;
        Stamp s;
        s.time = it->last_write_time(ec);
        s.size = it->file_size(ec);
        out[fs::relative(it->path(), root).generic_string()] = s;
    }
    return out;
}

#if WEFT_HAVE_SHADERC
// The (set, binding) pairs a SPIR-V module's resources are decorated with (OpDecorate, opcode
// 71, with DescriptorSet = 34 and Binding = 33).
std::set<std::pair<uint32_t, uint32_t>> descriptorBindings(const uint32_t* words, size_t count) {
    std::map<uint32_t, std::pair<uint32_t, uint32_t>> byId; // id -> (set, binding)
    std::set<uint32_t> hasBinding;
    for (size_t i = 5; i < count;) {
        const uint32_t length = words[i] >> 16, opcode = words[i] & 0xffffu;
        if (length == 0 || i + length > count) break;
        if (opcode == 71 && length >= 4) {
            const uint32_t id = words[i + 1], decoration = words[i + 2], value = words[i + 3];
            if (decoration == 34) byId[id].first = value;
            if (decoration == 33) {
                byId[id].second = value;
                hasBinding.insert(id);
            }
        }
        i += length;
    }
    std::set<std::pair<uint32_t, uint32_t>> out;
    for (uint32_t id : hasBinding) out.insert(byId[id]);
    return out;
}

// A reloaded shader may only use descriptors its built-in version uses: the pipeline layouts
// were made for those, and a pipeline whose shader reads a binding its layout lacks is
// undefined behaviour (lavapipe crashes). Returns "" when it fits, else why not.
std::string layoutMismatch(const std::string& name, const std::vector<uint32_t>& words) {
    const vk::EmbeddedShader& built = vk::embeddedShader(name.c_str());
    const auto allowed = descriptorBindings(built.words, built.wordCount);
    for (const auto& [set, binding] : descriptorBindings(words.data(), words.size()))
        if (!allowed.count({set, binding}))
            return "uses descriptor set " + std::to_string(set) + " binding " +
                   std::to_string(binding) +
                   ", which the built-in version does not; new "
                   "descriptors need a rebuild of weft";
    return "";
}

struct IncludeContext {
    fs::path root;
};

struct IncludeResult {
    shaderc_include_result result{};
    std::string name, content;
};

shaderc_include_result* resolveCallback(void* user, const char* requested, int,
                                        const char* requesting, size_t) {
    auto* ctx = static_cast<IncludeContext*>(user);
    auto* r = new IncludeResult;
    const fs::path path = resolveInclude(ctx->root, ctx->root / requesting, requested);
    if (fs::exists(path)) {
        r->name = fs::relative(path, ctx->root).generic_string();
        r->content = readText(path);
    } else {
        r->content = std::string("cannot find include '") + requested + "'";
    }
    r->result = {r->name.c_str(), r->name.size(), r->content.c_str(), r->content.size(), r};
    return &r->result;
}

void releaseCallback(void*, shaderc_include_result* result) {
    delete static_cast<IncludeResult*>(result->user_data);
}

// Compiles root/name; returns false with `error` set on failure.
bool compile(const fs::path& root, const std::string& name, std::vector<uint32_t>& words,
             std::string& error) {
    static const std::map<std::string, shaderc_shader_kind> kinds = {
        {".vert", shaderc_vertex_shader},       {".frag", shaderc_fragment_shader},
        {".comp", shaderc_compute_shader},      {".geom", shaderc_geometry_shader},
        {".tesc", shaderc_tess_control_shader}, {".tese", shaderc_tess_evaluation_shader}};
    const std::string source = readText(root / name);
    shaderc_compiler_t compiler = shaderc_compiler_initialize();
    shaderc_compile_options_t options = shaderc_compile_options_initialize();
    shaderc_compile_options_set_target_env(options, shaderc_target_env_vulkan,
                                           shaderc_env_version_vulkan_1_2);
    shaderc_compile_options_set_optimization_level(options, shaderc_optimization_level_performance);
    IncludeContext ctx{root};
    shaderc_compile_options_set_include_callbacks(options, resolveCallback, releaseCallback, &ctx);
    shaderc_compilation_result_t result = shaderc_compile_into_spv(
        compiler, source.data(), source.size(), kinds.at(fs::path(name).extension().string()),
        name.c_str(), "main", options);
    const bool ok =
        shaderc_result_get_compilation_status(result) == shaderc_compilation_status_success;
    if (ok) {
        words.resize(shaderc_result_get_length(result) / sizeof(uint32_t));
        std::memcpy(words.data(), shaderc_result_get_bytes(result),
                    words.size() * sizeof(uint32_t));
    } else {
        error = shaderc_result_get_error_message(result);
    }
    shaderc_result_release(result);
    shaderc_compile_options_release(options);
    shaderc_compiler_release(compiler);
    return ok;
}
#endif

} // namespace

bool shaderHotReloadAvailable() { return WEFT_HAVE_SHADERC != 0; }

void setShaderDirectory(const std::string& directory) {
    ReloadState& s = state();
    std::lock_guard<std::mutex> lock(s.mutex);
    if (directory.empty()) {
        s.root.clear();
        s.stamps.clear();
        if (!s.spirv.empty()) ++s.generation; // back to the embedded shaders
        s.spirv.clear();
        return;
    }
    if (!shaderHotReloadAvailable())
        throw Error(
            "shader hot reload needs libshaderc, which this build of weft was made without");
    if (!fs::is_directory(directory))
        throw InvalidArgument("shader directory '" + directory + "' does not exist");
    s.root = fs::absolute(directory);
    s.stamps = scan(s.root);
}

std::string shaderDirectory() {
    std::lock_guard<std::mutex> lock(state().mutex);
    return state().root.string();
}

int pollShaderChanges() {
    ReloadState& s = state();
    std::lock_guard<std::mutex> lock(s.mutex);
    if (s.root.empty()) return 0;
    const std::map<std::string, Stamp> now = scan(s.root);
    std::set<std::string> changed;
    for (const auto& [name, stamp] : now) {
        auto it = s.stamps.find(name);
        if (it == s.stamps.end() || it->second != stamp) changed.insert(name);
    }
    s.stamps = now;
    if (changed.empty()) return 0;
    int compiled = 0;
#if WEFT_HAVE_SHADERC
    for (const auto& [name, stamp] : now) {
        if (!isStage(name)) continue;
        const std::set<std::string> deps = dependencies(s.root, s.root / name);
        bool affected = false;
        for (const std::string& c : changed) affected |= deps.count(c) > 0;
        if (!affected) continue;
        std::vector<uint32_t> words;
        std::string error;
        bool known = true;
        try {
            vk::embeddedShader(name.c_str());
        } catch (const Error&) {
            known = false; // not a shader of the library: nothing uses it
        }
        if (known && compile(s.root, name, words, error) &&
            (error = layoutMismatch(name, words)).empty()) {
            s.spirv[name] = std::move(words);
            ++compiled;
        } else if (known) {
            std::cerr << "weft: shader " << name << " failed to compile; the previous version "
                      << "stays in use:\n"
                      << error << std::flush;
            s.errors.push_back(name + ": " + error);
        }
    }
    if (compiled) ++s.generation;
#endif
    return compiled;
}

uint64_t shaderGeneration() {
    std::lock_guard<std::mutex> lock(state().mutex);
    return state().generation;
}

std::vector<std::string> shaderErrors() {
    std::lock_guard<std::mutex> lock(state().mutex);
    return state().errors;
}

void clearShaderErrors() {
    std::lock_guard<std::mutex> lock(state().mutex);
    state().errors.clear();
}

namespace vk {

std::vector<uint32_t> shaderWords(const char* name) {
    {
        ReloadState& s = state();
        std::lock_guard<std::mutex> lock(s.mutex);
        auto it = s.spirv.find(name);
        if (it != s.spirv.end()) return it->second;
    }
    const EmbeddedShader& e = embeddedShader(name);
    return std::vector<uint32_t>(e.words, e.words + e.wordCount);
}

} // namespace vk

} // namespace weft
