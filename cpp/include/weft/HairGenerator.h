#pragma once
// Procedural hair on a scalp and fur grown from triangle meshes (SPEC §5.1, 002 listing 1).
// Both are deterministic for a seed and for any thread count.
#include <cstdint>

#include <glm/glm.hpp>

#include <weft/HairStrands.h>
#include <weft/Image.h>
#include <weft/Mesh.h>

namespace weft {

enum class HairStyleKind { Straight, Wavy, Curly };

/// Strands rooted on the upper part of an ellipsoid "scalp". `points` is the total over all
/// strands: each strand gets points / strands points and the first points % strands strands one
/// more, so any total is reachable (the seed's 160,000 = 10,000 x 16; 687,532 = 10,000 strands
/// of 68-69; 1,031,268 = 15,000 strands of 68-69).
struct HairStyle {
    HairStyleKind kind = HairStyleKind::Straight;
    uint32_t strands = 1000;
    uint64_t points = 16000;
    float length = 0.25f;        // m, along the centre line
    float lengthJitter = 0.0f;   // relative, each strand's length in [1 - j, 1 + j] * length
    float waveAmplitude = 0.01f; // m (Wavy)
    float waveFrequency = 8.0f;  // waves per metre of strand (Wavy, Curly turns per metre)
    float curlRadius = 0.01f;    // m (Curly)
    float droop = 0.6f;          // in [0, 1]: how far the direction turns from the normal to -Y
    glm::vec3 scalpCenter{0.0f, 1.6f, 0.0f};
    glm::vec3 scalpRadii{0.09f, 0.11f, 0.1f};
    float scalpCutoff = 0.1f; // roots where (y - centre.y) / radii.y >= cutoff, in [-1, 1)
    uint32_t seed = 1;
    int threads = 0; // <= 0: all cores

    /// Throws InvalidArgument for out-of-range values (see the field comments; at least 2
    /// and at most 65,536 points per strand, positive finite sizes).
    void validate() const;
};

HairStrands generateHair(const HairStyle& style);

/// Fur (002 listing 1, plus per-strand variation and density control): every triangle is
/// tessellated into level^2 sub-triangles; one strand per sub-triangle starts at its centroid
/// along the interpolated vertex normal and grows `segments` segments of length
/// length / segments, each bent further: p_{k+1} = p_k + d_k * len, d_{k+1} = d_k + down * len.
struct FurParams {
    int level = 1;                // tessellation level per triangle in [1, 1024]
    float density = 0.0f;         // > 0: per-triangle level = max(1, round(sqrt(area * density)))
    int segments = 10;            // [1, 65535]
    float length = 0.3f;          // m (the seed: 10 segments of 0.03)
    float lengthJitter = 0.0f;    // relative, in [0, 1)
    float directionJitter = 0.0f; // max angle (radians) between normal and start direction
    glm::vec3 down{0.0f, -0.5f, 0.0f};
    uint32_t seed = 1;
    int threads = 0;

    void validate() const;
};

/// `texture` (optional, sRGB RGB(A)) gives each strand the linear colour at its root's UV
/// (bilinear, repeat, v = 0 at the top row); without it the strands have no colour array.
/// Throws InvalidArgument for an invalid mesh or params, or more than 2^32 - 1 points.
HairStrands generateFur(const Mesh& mesh, const FurParams& params,
                        const ImageU8* texture = nullptr);

} // namespace weft
