#include "render/HairShadingGpu.h"

namespace weft {

namespace hair {

HairShadingGpu packHairShading(const HairMaterial& m) {
    m.validate();
    HairShadingGpu g{};
    g.model[0] = int32_t(m.model);
    g.diffuse = glm::vec4(m.diffuse, 0.0f);
    g.specular = glm::vec4(m.specular, m.shininess);
    g.colorR = glm::vec4(m.colorR, m.intensity.x);
    g.colorTT = glm::vec4(m.colorTT, m.intensity.y);
    g.colorTRT = glm::vec4(m.colorTRT, m.intensity.z);
    g.shift = glm::vec4(m.shift, m.eta);
    g.width = glm::vec4(m.width, m.ttAzimuthalWidth);
    g.glint = glm::vec4(m.glintIntensity, m.glintWidth, m.glintAngleMin, m.glintAngleMax);
    g.absorption = glm::vec4(m.absorption, m.causticWidth);
    return g;
}

} // namespace hair

} // namespace weft
