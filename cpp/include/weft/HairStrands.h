#pragma once
// Hair strands as the .hair format stores them (SPEC §5.1, shared/formats/hair.md): points root
// to tip, strand after strand, with optional per-strand segment counts and per-point thickness,
// transparency and colour.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace weft {

struct HairStrands {
    std::vector<glm::vec3> points;   // every point of every strand, root to tip
    std::vector<uint16_t> segments;  // per strand; empty: every strand has defaultSegments
    std::vector<float> thickness;    // per point; empty: defaultThickness
    std::vector<float> transparency; // per point; empty: defaultTransparency
    std::vector<glm::vec3> colors;   // per point, linear RGB; empty: defaultColor
    uint32_t defaultSegments = 0;
    float defaultThickness = 1.0f;
    float defaultTransparency = 0.0f;
    glm::vec3 defaultColor{1.0f};
    std::string info;                  // free text (at most 88 ASCII characters in a file)
    std::vector<std::string> warnings; // what a loader noticed but tolerated

    size_t pointCount() const { return points.size(); }
    size_t strandCount() const;
    /// First point of every strand plus the total: strandCount() + 1 entries.
    std::vector<uint64_t> offsets() const;

    /// Throws InvalidArgument unless: at least one strand; Σ(segments + 1) (or strands *
    /// (defaultSegments + 1)) equals the point count; optional arrays have one entry per point;
    /// every value finite; thickness >= 0; transparency in [0, 1]; colours >= 0; defaults alike;
    /// info at most 88 characters.
    void validate() const;
};

} // namespace weft
