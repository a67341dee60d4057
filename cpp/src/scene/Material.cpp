// Material: the checks a material passes before a scene takes it.
#include <weft/Error.h>
#include <weft/Material.h>

#include <cmath>
#include <string>

#include "core/Validate.h"

namespace weft {

void Material::validate() const {
    requireNonNegative(ka, "Material.ka");
    requireNonNegative(kd, "Material.kd");
    requireNonNegative(ks, "Material.ks");
    requireNonNegative(baseColor, "Material.base_color");
    requirePositive(shininess, "Material.shininess");
    requireFinite(alphaCutoff, "Material.alpha_cutoff");
    if (alphaCutoff < 0.0f || alphaCutoff > 1.0f)
        throw InvalidArgument("Material.alpha_cutoff must be in [0, 1]");
    if (ambientMap && ambientMap->srgb())
        throw InvalidArgument(
            "Material.ambient_map must be a linear texture (Texture(..., srgb=False))");
    if (normalMap && normalMap->srgb())
        throw InvalidArgument(
            "Material.normal_map must be a linear texture (Texture(..., srgb=False))");
    if (ambientMapIsRadiance && !ambientMap)
        throw InvalidArgument("Material.ambient_map_is_radiance needs an ambient map");
    requireFinite(shininessMax, "Material.shininess_max");
    requirePositive(normalScale, "Material.normal_scale");
    if (shininessMax != 0.0f) {
        if (!specularMap)
            throw InvalidArgument("Material.shininess_max (exponent in the specular map's alpha) "
                                  "needs a specular map");
        if (shininessMax < shininess)
            throw InvalidArgument("Material.shininess_max must be 0 or >= shininess");
    }
    requireNonNegative(reflectivity, "Material.reflectivity");
    if (glm::any(glm::greaterThan(reflectivity, glm::vec3(1.0f))))
        throw InvalidArgument("Material.reflectivity (Fresnel F0) must be in [0, 1]");
    requireFinite(environmentDiffuse, "Material.environment_diffuse");
    if (environmentDiffuse < 0.0f)
        throw InvalidArgument("Material.environment_diffuse must be >= 0");
    if (dynamicReflection && !glm::any(glm::greaterThan(reflectivity, glm::vec3(0.0f))))
        throw InvalidArgument("Material.dynamic_reflection needs a reflectivity > 0");
    if (glossInAlpha && alphaCutoff > 0.0f)
        throw InvalidArgument(
            "Material.gloss_in_alpha uses the texture's alpha as gloss: it cannot "
            "also be an alpha cutoff");
    if (phantom && dynamicReflection)
        throw InvalidArgument("Material.phantom: a phantom shows only shadows, it cannot carry the "
                              "dynamic reflection");
}

} // namespace weft
