#pragma once
// One line of an OBJ or MTL file as tokens: the '#' comment removed, the rest split at
// whitespace (the loaders in ObjLoader.cpp and MtlLoader.cpp share this).
#include <string_view>
#include <vector>

namespace weft {

inline bool isLineSpace(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// Fills `tokens` (views into `line`) and returns the line without its comment.
inline std::string_view tokenizeLine(std::string_view line, std::vector<std::string_view>& tokens) {
    const size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    tokens.clear();
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && isLineSpace(line[i])) ++i;
        const size_t start = i;
        while (i < line.size() && !isLineSpace(line[i])) ++i;
        if (i > start) tokens.push_back(line.substr(start, i - start));
    }
    return line;
}

} // namespace weft
