#include <weft/HairMaterial.h>

#include <cmath>
#include <string>

#include <glm/gtc/constants.hpp>

#include <weft/Error.h>

namespace weft {

namespace {

void requireColor(const glm::vec3& c, const char* what) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(c[i]) || c[i] < 0.0f)
            throw InvalidArgument(std::string("hair material: ") + what +
                                  " must be finite and >= 0");
}

void requireRange(float v, float lo, float hi, bool openLow, const char* what) {
    const bool ok = std::isfinite(v) && (openLow ? v > lo : v >= lo) && v <= hi;
    if (!ok)
        throw InvalidArgument(std::string("hair material: ") + what + " must be in " +
                              (openLow ? "(" : "[") + std::to_string(lo) + ", " +
                              std::to_string(hi) + "], got " + std::to_string(v));
}

} // namespace

void HairMaterial::validate() const {
    if (int(model) < 0 || int(model) > 2) throw InvalidArgument("hair material: unknown model");
    requireColor(diffuse, "diffuse");
    requireColor(specular, "specular");
    requireRange(shininess, 0.0f, 10000.0f, true, "shininess");
    const float quarter = glm::quarter_pi<float>(), halfPi = glm::half_pi<float>();
    for (int i = 0; i < 3; ++i) {
        requireRange(shift[i], -quarter, quarter, false, "shift");
        requireRange(width[i], 0.0f, halfPi, true, "width");
    }
    requireRange(eta, 1.0f, 3.0f, true, "eta");
    requireColor(absorption, "absorption");
    requireRange(causticWidth, 0.0f, 1e3f, true, "caustic width");
    requireColor(colorR, "colour R");
    requireColor(colorTT, "colour TT");
    requireColor(colorTRT, "colour TRT");
    requireColor(intensity, "intensity");
    requireRange(ttAzimuthalWidth, 0.0f, glm::pi<float>(), true, "TT azimuthal width");
    requireRange(glintIntensity, 0.0f, 1e3f, false, "glint intensity");
    requireRange(glintWidth, 0.0f, glm::pi<float>(), true, "glint width");
    requireRange(glintAngleMin, 0.0f, glm::pi<float>(), false, "glint angle min");
    requireRange(glintAngleMax, glintAngleMin, glm::pi<float>(), false, "glint angle max");
}

} // namespace weft
