// Scene: hair instances (SPEC §5).
#include <weft/Scene.h>

#include <string>

#include "core/Validate.h"

namespace weft {

namespace {
void checkHairId(uint32_t id, size_t count) {
    if (id >= count)
        throw InvalidArgument("hair id " + std::to_string(id) + " does not exist (" +
                              std::to_string(count) + " in the scene)");
}
} // namespace

uint32_t Scene::addHair(HairStrandsPtr strands, const HairMaterial& material,
                        const glm::mat4& transform, bool castShadows) {
    if (!strands) throw InvalidArgument("Scene.add_hair: strands is null");
    strands->validate();
    material.validate();
    requireInvertible(transform, "hair transform");
    HairInstance h{std::move(strands), material, transform, castShadows};
    h.lo = glm::vec3(1e30f);
    h.hi = glm::vec3(-1e30f);
    for (const glm::vec3& p : h.strands->points) {
        h.lo = glm::min(h.lo, p);
        h.hi = glm::max(h.hi, p);
    }
    mHairs.push_back(std::move(h));
    ++mVersion;
    return uint32_t(mHairs.size() - 1);
}

void Scene::setHairTransform(uint32_t id, const glm::mat4& transform) {
    checkHairId(id, mHairs.size());
    requireInvertible(transform, "hair transform");
    mHairs[id].transform = transform;
    ++mVersion;
}

void Scene::setHairMaterial(uint32_t id, const HairMaterial& material) {
    checkHairId(id, mHairs.size());
    material.validate();
    mHairs[id].material = material;
    ++mVersion;
}

} // namespace weft
