// Wavefront .mtl reading: the Blinn-Phong statements weft's Material has (Kd, Ks, Ns, map_Kd).
#include "scene/MtlLoader.h"

#include <weft/Error.h>
#include <weft/Image.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string_view>
#include <vector>

#include "core/FileRead.h"
#include "scene/LineTokens.h"

namespace weft {

namespace {

// Options of map_* statements and how many values follow each (-o, -s, -t take 1 to 3).
const std::map<std::string_view, int> kMapOptions = {
    {"-blendu", 1}, {"-blendv", 1}, {"-cc", 1}, {"-clamp", 1}, {"-bm", 1}, {"-boost", 1},
    {"-mm", 2}, {"-o", 3}, {"-s", 3}, {"-t", 3}, {"-texres", 1}, {"-imfchan", 1}, {"-type", 1}};

bool parseFloat(std::string_view text, float& value) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    return error == std::errc() && end == text.data() + text.size() && !text.empty() &&
           std::isfinite(value);
}

class MtlReader {
public:
    explicit MtlReader(const std::string& path) : mPath(path) {}
    std::unordered_map<std::string, Material> read();

private:
    [[noreturn]] void fail(const std::string& message) const {
        throw IoError(mPath + ":" + std::to_string(mLine) + ": " + message);
    }
    glm::vec3 colour(const std::vector<std::string_view>& tokens) const;
    TexturePtr texture(const std::vector<std::string_view>& tokens, std::string_view text);

    std::string mPath;
    size_t mLine = 0;
    std::map<std::string, TexturePtr> mTextures; // one Texture per file, shared
};

// "Kd r g b" or "Kd r" (grey); "Kd spectral ..." and "Kd xyz ..." are refused.
glm::vec3 MtlReader::colour(const std::vector<std::string_view>& tokens) const {
    if (tokens.size() != 2 && tokens.size() != 4)
        fail("'" + std::string(tokens[0]) + "' needs 1 or 3 numbers");
    glm::vec3 c(0.0f);
    for (size_t i = 1; i < tokens.size(); ++i)
        if (!parseFloat(tokens[i], c[int(i - 1)]) || c[int(i - 1)] < 0.0f)
            fail("'" + std::string(tokens[0]) + "' needs non-negative numbers, not '" +
                 std::string(tokens[i]) + "'");
    if (tokens.size() == 2) c = glm::vec3(c.x);
    return c;
}

TexturePtr MtlReader::texture(const std::vector<std::string_view>& tokens, std::string_view text) {
    size_t i = 1;
    while (i < tokens.size()) {
        const auto option = kMapOptions.find(tokens[i]);
        if (option == kMapOptions.end()) break;
        ++i;
        // Options take up to their count of values; the numeric ones stop at the first
        // token that is not a number (-o 0.5 file.png).
        for (int k = 0; k < option->second && i < tokens.size(); ++k, ++i) {
            float ignored;
            if (k > 0 && !parseFloat(tokens[i], ignored)) break;
        }
    }
    if (i >= tokens.size()) fail("'" + std::string(tokens[0]) + "' names no file");
    // The file name is the rest of the line (it may contain spaces).
    const size_t start = size_t(tokens[i].data() - text.data());
    const size_t end = size_t(tokens.back().data() + tokens.back().size() - text.data());
    const std::string name(text.substr(start, end - start));
    const std::string file = (std::filesystem::path(mPath).parent_path() / name).string();
    const auto cached = mTextures.find(file);
    if (cached != mTextures.end()) return cached->second;
    TexturePtr t;
    try {
        t = std::make_shared<Texture>(loadPng(file), true);
    } catch (const Error& e) {
        fail(std::string("texture: ") + e.what());
    }
    mTextures.emplace(file, t);
    return t;
}

std::unordered_map<std::string, Material> MtlReader::read() {
    checkInputFile(mPath, "MTL file");
    std::ifstream file(mPath, std::ios::binary);
    if (!file) throw IoError("cannot open MTL file '" + mPath + "'");
    std::unordered_map<std::string, Material> materials;
    Material* current = nullptr;
    std::string line;
    std::vector<std::string_view> tokens;
    while (std::getline(file, line)) {
        ++mLine;
        const std::string_view text = tokenizeLine(line, tokens);
        if (tokens.empty()) continue;
        const std::string_view keyword = tokens[0];
        if (keyword == "newmtl") {
            if (tokens.size() < 2) fail("'newmtl' needs a name");
            const size_t start = size_t(tokens[1].data() - text.data());
            const size_t end = size_t(tokens.back().data() + tokens.back().size() - text.data());
            // A repeated name keeps its first definition (tinyobjloader does the same).
            current = &materials.try_emplace(std::string(text.substr(start, end - start)))
                           .first->second;
            continue;
        }
        if (keyword != "Kd" && keyword != "Ks" && keyword != "Ns" && keyword != "map_Kd")
            continue; // Ka, Ke, d, Tr, illum, other maps: no counterpart used here
        if (!current) fail("'" + std::string(keyword) + "' before any 'newmtl'");
        if (keyword == "Kd") {
            current->kd = colour(tokens);
        } else if (keyword == "Ks") {
            current->ks = colour(tokens);
        } else if (keyword == "Ns") {
            float ns = 0.0f;
            if (tokens.size() != 2 || !parseFloat(tokens[1], ns) || ns < 0.0f)
                fail("'Ns' needs one non-negative number");
            current->shininess = std::max(ns, 1.0f); // Ns 0 is common; weft needs > 0
        } else {
            current->texture = texture(tokens, text);
        }
    }
    if (file.bad()) throw IoError("error reading MTL file '" + mPath + "'");
    return materials;
}

} // namespace

std::unordered_map<std::string, Material> loadMtl(const std::string& path) {
    return MtlReader(path).read();
}

} // namespace weft
