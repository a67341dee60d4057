#pragma once
// A mesh whose vertices move between frames (a simulated cloth): what the scene and the renderer
// read of it, so that neither depends on the simulator and a new deformable kind needs no edit
// of either.
#include <cstdint>

#include <glm/glm.hpp>

#include <weft/Mesh.h>

namespace weft {

class DeformableMesh {
public:
    virtual ~DeformableMesh() = default;
    /// Changes whenever surface() may return something else; the renderer re-uploads only then.
    virtual uint64_t meshVersion() const = 0;
    /// The current surface in world space (triangles may be missing, e.g. torn or holed cloth).
    virtual Mesh surface() const = 0;
    /// World-space bounds of the current vertices (min > max when there are none).
    virtual void surfaceBounds(glm::vec3& lo, glm::vec3& hi) const = 0;
};

} // namespace weft
