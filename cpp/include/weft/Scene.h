#pragma once
// What the renderer draws: mesh instances with materials and transforms, lights, ambient.
#include <weft/Error.h>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include <weft/Cloth.h>
#include <weft/Light.h>
#include <weft/Material.h>
#include <weft/Camera.h>
#include <weft/Mesh.h>

namespace weft {

using MeshPtr = std::shared_ptr<const Mesh>;

struct MeshInstance {
    MeshPtr mesh;                       // null for a cloth instance
    std::shared_ptr<const Cloth> cloth; // drawn from its current state (positions are world)
    Material material;
    glm::mat4 transform{1.0f}; // object -> world (identity for cloth)
    bool castShadows = true;
};

class Scene {
public:
    /// Adds an instance and returns its id. The mesh and material are validated here.
    uint32_t addMesh(MeshPtr mesh, const Material& material = {},
                     const glm::mat4& transform = glm::mat4(1.0f), bool castShadows = true);
    /// Adds a simulated cloth, drawn two-sided from its state at render time (the renderer
    /// uploads its mesh only when Cloth::meshVersion() changed). Returns its instance id.
    uint32_t addCloth(std::shared_ptr<const Cloth> cloth, const Material& material = {},
                      bool castShadows = true);
    void setTransform(uint32_t id, const glm::mat4& transform);
    void setMaterial(uint32_t id, const Material& material);
    /// Adds a directional, point or spot light (validated) and returns its id.
    uint32_t addLight(const Light& light);
    void setLight(uint32_t id, const Light& light);

    const std::vector<MeshInstance>& instances() const { return mInstances; }
    const std::vector<Light>& lights() const { return mLights; }

    void setAmbient(const glm::vec3& ambient);      // I_A
    void setBackground(const glm::vec3& background); // linear colour behind everything
    const glm::vec3& ambient() const { return mAmbient; }
    const glm::vec3& background() const { return mBackground; }

    /// World-space bounds of all instances (min > max when the scene is empty).
    void bounds(glm::vec3& lo, glm::vec3& hi) const;
    /// Increases whenever anything in the scene changes; the renderer reuses work by it.
    uint64_t version() const { return mVersion; }

private:
    std::vector<MeshInstance> mInstances;
    std::vector<Light> mLights;
    glm::vec3 mAmbient{0.1f};
    glm::vec3 mBackground{0.0f};
    uint64_t mVersion = 1;
};

/// The default scene of the demo and the benchmarks: a textured ground plane, a sphere and a
/// box lit by a shadow-casting sun, and a camera looking at them.
void makeDefaultScene(Scene& scene, Camera& camera);

} // namespace weft
