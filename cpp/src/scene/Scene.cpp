#include <weft/Scene.h>

#include <string>

#include "core/Validate.h"

namespace weft {

void Material::validate() const {
    requireNonNegative(ka, "Material.ka");
    requireNonNegative(kd, "Material.kd");
    requireNonNegative(ks, "Material.ks");
    requireNonNegative(baseColor, "Material.base_color");
    requirePositive(shininess, "Material.shininess");
}

void DirectionalLight::validate() const {
    requireFinite(direction, "DirectionalLight.direction");
    if (glm::length(direction) < 1e-12f)
        throw InvalidArgument("DirectionalLight.direction must not be zero");
    requireNonNegative(color, "DirectionalLight.color");
    requireFinite(intensity, "DirectionalLight.intensity");
    if (intensity < 0) throw InvalidArgument("DirectionalLight.intensity must not be negative");
}

namespace {
void checkId(uint32_t id, size_t count, const char* what) {
    if (id >= count)
        throw InvalidArgument(std::string(what) + " id " + std::to_string(id) + " does not exist (" +
                              std::to_string(count) + " in the scene)");
}
} // namespace

uint32_t Scene::addMesh(MeshPtr mesh, const Material& material, const glm::mat4& transform,
                        bool castShadows) {
    if (!mesh) throw InvalidArgument("Scene.add_mesh: mesh is null");
    mesh->validate();
    material.validate();
    requireInvertible(transform, "mesh transform");
    mInstances.push_back({std::move(mesh), material, transform, castShadows});
    ++mVersion;
    return uint32_t(mInstances.size() - 1);
}

void Scene::setTransform(uint32_t id, const glm::mat4& transform) {
    checkId(id, mInstances.size(), "mesh");
    requireInvertible(transform, "mesh transform");
    mInstances[id].transform = transform;
    ++mVersion;
}

void Scene::setMaterial(uint32_t id, const Material& material) {
    checkId(id, mInstances.size(), "mesh");
    material.validate();
    mInstances[id].material = material;
    ++mVersion;
}

uint32_t Scene::addLight(const DirectionalLight& light) {
    light.validate();
    mLights.push_back(light);
    ++mVersion;
    return uint32_t(mLights.size() - 1);
}

void Scene::setLight(uint32_t id, const DirectionalLight& light) {
    checkId(id, mLights.size(), "light");
    light.validate();
    mLights[id] = light;
    ++mVersion;
}

void Scene::setAmbient(const glm::vec3& ambient) {
    requireNonNegative(ambient, "Scene.ambient");
    mAmbient = ambient;
    ++mVersion;
}

void Scene::setBackground(const glm::vec3& background) {
    requireNonNegative(background, "Scene.background");
    mBackground = background;
    ++mVersion;
}

void Scene::bounds(glm::vec3& lo, glm::vec3& hi) const {
    lo = glm::vec3(1e30f);
    hi = glm::vec3(-1e30f);
    for (const MeshInstance& inst : mInstances) {
        glm::vec3 mlo, mhi;
        inst.mesh->bounds(mlo, mhi);
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 c((i & 1) ? mhi.x : mlo.x, (i & 2) ? mhi.y : mlo.y,
                              (i & 4) ? mhi.z : mlo.z);
            const glm::vec3 w = glm::vec3(inst.transform * glm::vec4(c, 1.0f));
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    }
}

} // namespace weft
