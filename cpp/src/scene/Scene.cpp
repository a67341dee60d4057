#include <weft/Scene.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/Validate.h"

namespace weft {

namespace {
void checkId(uint32_t id, size_t count, const char* what) {
    if (id >= count)
        throw InvalidArgument(std::string(what) + " id " + std::to_string(id) +
                              " does not exist (" + std::to_string(count) + " in the scene)");
}
} // namespace

uint32_t Scene::addMesh(MeshPtr mesh, const Material& material, const glm::mat4& transform,
                        bool castShadows) {
    if (!mesh) throw InvalidArgument("Scene.add_mesh: mesh is null");
    mesh->validate();
    material.validate();
    requireInvertible(transform, "mesh transform");
    mInstances.push_back({std::move(mesh), nullptr, material, transform, castShadows});
    ++mVersion;
    return uint32_t(mInstances.size() - 1);
}

uint32_t Scene::addCloth(std::shared_ptr<const DeformableMesh> cloth, const Material& material,
                         bool castShadows) {
    if (!cloth) throw InvalidArgument("Scene.add_cloth: cloth is null");
    material.validate();
    Material m = material;
    m.twoSided = true;
    mInstances.push_back({nullptr, std::move(cloth), m, glm::mat4(1.0f), castShadows});
    ++mVersion;
    return uint32_t(mInstances.size() - 1);
}

void Scene::setTransform(uint32_t id, const glm::mat4& transform) {
    checkId(id, mInstances.size(), "mesh");
    if (mInstances[id].deformable)
        throw InvalidArgument("a cloth's particles are in world space; it has no transform");
    requireInvertible(transform, "mesh transform");
    mInstances[id].transform = transform;
    ++mVersion;
}

void Scene::setMaterial(uint32_t id, const Material& material) {
    checkId(id, mInstances.size(), "mesh");
    material.validate();
    mInstances[id].material = material;
    if (mInstances[id].deformable) mInstances[id].material.twoSided = true;
    ++mVersion;
}

uint32_t Scene::addLight(const Light& light) {
    validateLight(light);
    mLights.push_back(light);
    ++mVersion;
    return uint32_t(mLights.size() - 1);
}

void Scene::setLight(uint32_t id, const Light& light) {
    checkId(id, mLights.size(), "light");
    validateLight(light);
    mLights[id] = light;
    ++mVersion;
}

void Scene::setAmbient(const glm::vec3& ambient) {
    requireNonNegative(ambient, "Scene.ambient");
    mAmbient = ambient;
    ++mVersion;
}

void Scene::setBackgroundImage(TexturePtr image) {
    mBackgroundImage = std::move(image);
    ++mVersion;
}

void Scene::setBackground(const glm::vec3& background) {
    requireNonNegative(background, "Scene.background");
    mBackground = background;
    ++mVersion;
}

void EnvironmentLighting::validate() const {
    if (!environment) throw InvalidArgument("Scene.set_environment: no environment given");
    environment->radiance().requireFinite("environment radiance", true);
    requireFinite(intensity, "environment intensity");
    if (intensity < 0.0f) throw InvalidArgument("environment intensity must be >= 0");
    if (specularSize < 4 || specularSize > 1024)
        throw InvalidArgument("environment specular_size must be in [4, 1024]");
    int maxLevels = 1;
    while ((specularSize >> maxLevels) >= 1 && maxLevels < 16) ++maxLevels;
    if (specularLevels < 2 || specularLevels > maxLevels)
        throw InvalidArgument("environment specular_levels must be in [2, " +
                              std::to_string(maxLevels) + "] for specular_size " +
                              std::to_string(specularSize));
    if (specularSamples < 1 || specularSamples > 4096)
        throw InvalidArgument("environment specular_samples must be in [1, 4096]");
    if (domeLights < 0 || domeLights > 64 || domeLights % 8 != 0)
        throw InvalidArgument("environment dome_lights must be 0, 8, 16, ..., 64 (got " +
                              std::to_string(domeLights) + ")");
    if (domeMapSize < 16 || domeMapSize > 4096)
        throw InvalidArgument("environment dome_map_size must be in [16, 4096]");
    if (domeRefresh < 0) throw InvalidArgument("environment dome_refresh must be >= 0 (0: all)");
    requireFinite(domeBlur, "environment dome_blur");
    if (domeBlur < 0.0f || domeBlur > 64.0f)
        throw InvalidArgument("environment dome_blur must be in [0, 64] pixels");
    requireFinite(backgroundBlur, "environment background_blur");
    if (backgroundBlur < 0.0f || backgroundBlur > 1.0f)
        throw InvalidArgument("environment background_blur must be in [0, 1] (roughness)");
    requireFinite(domeBlurDepthTolerance, "environment dome_blur_depth_tolerance");
    if (domeBlurDepthTolerance <= 0.0f)
        throw InvalidArgument("environment dome_blur_depth_tolerance must be > 0");
    if (lookup != Lookup::Cube && lookup != Lookup::SphereMap)
        throw InvalidArgument("environment lookup must be cube or sphere_map");
    if (sphereMapSize < 8 || sphereMapSize > 2048)
        throw InvalidArgument("environment sphere_map_size must be in [8, 2048]");
    if (lookup == Lookup::SphereMap && (sphereMapSize >> (specularLevels - 1)) < 1)
        throw InvalidArgument("environment sphere_map_size must hold specular_levels mip levels");
}

void Scene::setEnvironment(const EnvironmentLighting& environment) {
    environment.validate();
    mEnvironment = environment;
    ++mVersion;
}

void Scene::clearEnvironment() {
    mEnvironment = EnvironmentLighting{};
    ++mVersion;
}

namespace {
// Grows [lo, hi] by the eight corners of [olo, ohi] under `transform`.
void addBox(glm::vec3& lo, glm::vec3& hi, const glm::vec3& olo, const glm::vec3& ohi,
            const glm::mat4& transform) {
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 c((i & 1) ? ohi.x : olo.x, (i & 2) ? ohi.y : olo.y,
                          (i & 4) ? ohi.z : olo.z);
        const glm::vec3 w = glm::vec3(transform * glm::vec4(c, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
}
} // namespace

void Scene::instanceBounds(size_t index, glm::vec3& lo, glm::vec3& hi) const {
    if (index >= mInstances.size())
        throw InvalidArgument("instance " + std::to_string(index) +
                              " out of range (the scene has " + std::to_string(mInstances.size()) +
                              ")");
    const MeshInstance& inst = mInstances[index];
    lo = glm::vec3(1e30f);
    hi = glm::vec3(-1e30f);
    if (inst.deformable) { // its vertices are in world space
        inst.deformable->surfaceBounds(lo, hi);
        return;
    }
    glm::vec3 mlo, mhi;
    inst.mesh->bounds(mlo, mhi);
    addBox(lo, hi, mlo, mhi, inst.transform);
}

void Scene::bounds(glm::vec3& lo, glm::vec3& hi, bool castersOnly) const {
    lo = glm::vec3(1e30f);
    hi = glm::vec3(-1e30f);
    for (size_t i = 0; i < mInstances.size(); ++i) {
        if (castersOnly && !mInstances[i].castShadows) continue;
        glm::vec3 ilo, ihi;
        instanceBounds(i, ilo, ihi);
        lo = glm::min(lo, ilo);
        hi = glm::max(hi, ihi);
    }
    for (const HairInstance& h : mHairs)
        if (!castersOnly || h.castShadows) addBox(lo, hi, h.lo, h.hi, h.transform);
}

} // namespace weft
