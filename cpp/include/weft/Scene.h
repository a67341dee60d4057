#pragma once
// What the renderer draws: mesh instances with materials and transforms, lights, ambient.
#include <cstdint>
#include <memory>
#include <vector>
#include <weft/Error.h>

#include <glm/glm.hpp>

#include <weft/Camera.h>
#include <weft/DeformableMesh.h>
#include <weft/Environment.h>
#include <weft/HairMaterial.h>
#include <weft/HairStrands.h>
#include <weft/Light.h>
#include <weft/Material.h>
#include <weft/Mesh.h>

namespace weft {

using MeshPtr = std::shared_ptr<const Mesh>;

struct MeshInstance {
    MeshPtr mesh;                                     // null for a deformable instance
    std::shared_ptr<const DeformableMesh> deformable; // e.g. a Cloth: drawn as it is now (world)
    Material material;
    glm::mat4 transform{1.0f}; // object -> world (identity for cloth)
    bool castShadows = true;
};

using HairStrandsPtr = std::shared_ptr<const HairStrands>;

/// Hair or fur drawn as strands (SPEC §5). The strands are immutable once added: the renderer
/// uploads them once, keyed by the object.
struct HairInstance {
    HairStrandsPtr strands;
    HairMaterial material;
    glm::mat4 transform{1.0f}; // object -> world
    bool castShadows = true;
    glm::vec3 lo{0.0f}, hi{0.0f}; // object-space bounds of the points
};

/// Image-based lighting of a scene (SPEC §4.4): the environment's radiance is world space. The
/// renderer bakes SH9 irradiance (diffuse) and a GGX-prefiltered chain (specular) from it, again
/// only when the environment's content version or the chain parameters change.
struct EnvironmentLighting {
    std::shared_ptr<Environment> environment; // null: no environment
    float intensity = 1.0f;   // scales the radiance, >= 0 (changing it bakes nothing)
    int specularSize = 64;    // texels per face of the specular chain's level 0
    int specularLevels = 6;   // mips: perceptual roughness 0 .. 1, at most log2(size) + 1
    int specularSamples = 64; // GGX importance samples per texel
    /// Dome of shadow lights (SPEC §4.5): 0, or a multiple of 8 up to 64 directional lights from
    /// Environment::shadowDome, each with a `domeMapSize` shadow map; the diffuse light becomes
    /// eq. 2.23 D = E(n) - sum of occluded T_i max(0, n.V_i).
    int domeLights = 0;
    int domeMapSize = 256;
    /// Dome maps re-rendered per frame while the casters move (round robin); 0 = all.
    int domeRefresh = 0;
    /// Radius in pixels of the blur of the dome's shadows (SPEC §4.5: the accumulated shadow
    /// image is blurred and darkens the diffuse light only); 0 = per pixel, unblurred. Bilateral:
    /// depths differing by more than `domeBlurDepthTolerance` (relative) do not mix.
    float domeBlur = 0.0f;
    float domeBlurDepthTolerance = 0.05f;
    /// Cube: world-space cube-map lookups (irradiance at N, glossy chain at R). SphereMap: the
    /// seed's eye-space path (SPEC §4.4) for a capture taken from the viewer's camera: the
    /// environment is read as eye space, baked into sphere maps of `sphereMapSize` (irradiance
    /// and a glossy mip chain) and looked up at normalize(d_eye + (0, 0, 1)).
    enum class Lookup { Cube, SphereMap };
    Lookup lookup = Lookup::Cube;
    int sphereMapSize = 128;
    /// Draw the environment behind the scene (cube lookups; a background image wins): its
    /// radiance times `intensity`, sharp at `backgroundBlur` 0, else the glossy chain at that
    /// roughness (0..1). Reflections and the dynamic probe see it too.
    bool background = false;
    float backgroundBlur = 0.0f;

    /// Throws InvalidArgument for a missing/non-finite/negative environment or bad parameters.
    void validate() const;
};

class Scene {
public:
    /// Adds an instance and returns its id. The mesh and material are validated here.
    uint32_t addMesh(MeshPtr mesh, const Material& material = {},
                     const glm::mat4& transform = glm::mat4(1.0f), bool castShadows = true);
    /// Adds a deformable mesh (a simulated Cloth), drawn two-sided from its state at render time
    /// (the renderer uploads its surface only when meshVersion() changed). Returns its instance id.
    uint32_t addCloth(std::shared_ptr<const DeformableMesh> cloth, const Material& material = {},
                      bool castShadows = true);
    void setTransform(uint32_t id, const glm::mat4& transform);
    void setMaterial(uint32_t id, const Material& material);
    /// Adds a hair instance (strands and material validated here) and returns its hair id.
    uint32_t addHair(HairStrandsPtr strands, const HairMaterial& material = {},
                     const glm::mat4& transform = glm::mat4(1.0f), bool castShadows = true);
    void setHairTransform(uint32_t id, const glm::mat4& transform);
    void setHairMaterial(uint32_t id, const HairMaterial& material);
    const std::vector<HairInstance>& hairs() const { return mHairs; }
    /// Adds a directional, point or spot light (validated) and returns its id.
    uint32_t addLight(const Light& light);
    void setLight(uint32_t id, const Light& light);

    const std::vector<MeshInstance>& instances() const { return mInstances; }
    const std::vector<Light>& lights() const { return mLights; }

    void setAmbient(const glm::vec3& ambient);       // I_A
    void setBackground(const glm::vec3& background); // linear colour behind everything
    /// An image behind everything instead of the colour (a camera frame for AR compositing with
    /// phantom materials), stretched over the output; null clears it.
    void setBackgroundImage(TexturePtr image);
    const TexturePtr& backgroundImage() const { return mBackgroundImage; }
    const glm::vec3& ambient() const { return mAmbient; }
    const glm::vec3& background() const { return mBackground; }

    /// Lights the scene with an environment (validated); materials opt in with `reflectivity`
    /// and `environmentDiffuse`.
    void setEnvironment(const EnvironmentLighting& environment);
    void clearEnvironment();
    const EnvironmentLighting& environment() const { return mEnvironment; }

    /// World-space bounds of all mesh and hair instances (min > max when the scene is empty);
    /// with `castersOnly`, of those that cast shadows (what shadow maps must enclose).
    void bounds(glm::vec3& lo, glm::vec3& hi, bool castersOnly = false) const;
    /// World-space bounds of mesh instance `index` (a cloth's: of its particles, holes left out).
    void instanceBounds(size_t index, glm::vec3& lo, glm::vec3& hi) const;
    /// Increases whenever anything in the scene changes; the renderer reuses work by it.
    uint64_t version() const { return mVersion; }

private:
    std::vector<MeshInstance> mInstances;
    std::vector<HairInstance> mHairs;
    std::vector<Light> mLights;
    glm::vec3 mAmbient{0.1f};
    glm::vec3 mBackground{0.0f};
    TexturePtr mBackgroundImage;
    EnvironmentLighting mEnvironment;
    uint64_t mVersion = 1;
};

/// The default scene of the demo and the benchmarks: a textured ground plane, a sphere and a
/// box lit by a shadow-casting sun, and a camera looking at them.
void makeDefaultScene(Scene& scene, Camera& camera);

} // namespace weft
