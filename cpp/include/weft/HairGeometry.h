#pragma once
// Per-vertex data the renderer draws strands with: tangents and camera-facing ribbons.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include <weft/HairStrands.h>

namespace weft {

/// Unit tangent per point: the central difference p[i+1] - p[i-1] inside a strand, one-sided
/// at its ends. Where that vanishes (coincident points) the strand's tip - root direction is
/// used, and (0, 1, 0) when that vanishes too (a single-point strand).
std::vector<glm::vec3> strandTangents(const HairStrands& strands);

/// Camera-facing ribbons: two vertices per point, p -/+ s * w / 2 with
/// s = normalize(t x (eye - p)) and w = widthScale * thickness (the default thickness without
/// a thickness array). When t is parallel to eye - p, s = normalize(t x Y) (X if t is along Y).
/// Vertex 2i is the - side of point i, 2i + 1 the + side.
std::vector<glm::vec3> strandRibbons(const HairStrands& strands, const glm::vec3& eye,
                                     float widthScale);
/// Two counter-clockwise triangles per segment over strandRibbons()' vertices.
std::vector<uint32_t> ribbonIndices(const HairStrands& strands);

} // namespace weft
