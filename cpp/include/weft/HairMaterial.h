#pragma once
// Hair shading models and their parameters (SPEC §5.2): Kajiya-Kay, Marschner et al. 2003 and
// Sadeghi et al. 2010. The models themselves are written in glsl/common/hair_shading.glsl.
#include <glm/glm.hpp>

namespace weft {

enum class HairModel { KajiyaKay = 0, Marschner = 1, Sadeghi = 2 };

/// Every model adds the diffuse term diffuse * sin(t, l). Angles in radians.
struct HairMaterial {
    HairModel model = HairModel::Sadeghi;
    glm::vec3 diffuse{0.0f};

    // Kajiya-Kay: specular * max(0, cos(theta_i + theta_o))^shininess.
    glm::vec3 specular{0.3f};
    float shininess = 80.0f;

    // Marschner and Sadeghi: longitudinal shift alpha_p and width beta_p of R, TT, TRT.
    glm::vec3 shift{-0.0872665f, 0.0436332f, 0.1308997f}; // -5, 2.5, 7.5 degrees
    glm::vec3 width{0.122173f, 0.0610865f, 0.244346f};    // 7, 3.5, 14 degrees

    // Marschner: refractive index, absorption sigma_a per fibre radius (RGB), and the width
    // eps of the caustic regularisation 1 / x -> x / (x^2 + eps^2), x = |2 dphi/dh|.
    float eta = 1.55f;
    glm::vec3 absorption{0.2f, 0.35f, 0.6f};
    float causticWidth = 0.2f;

    // Sadeghi: colour C_p and intensity I_p per lobe, TT azimuthal width xi_TT, glints
    // (relative intensity I_g, azimuthal width xi_g, per-strand half-angle in [min, max]).
    glm::vec3 colorR{1.0f};
    glm::vec3 colorTT{0.9f, 0.6f, 0.3f};
    glm::vec3 colorTRT{0.8f, 0.5f, 0.25f};
    glm::vec3 intensity{1.0f, 1.0f, 1.0f};
    float ttAzimuthalWidth = 0.174533f; // 10 degrees
    float glintIntensity = 0.5f;
    float glintWidth = 0.0872665f;   // 5 degrees
    float glintAngleMin = 0.523599f; // 30 degrees
    float glintAngleMax = 0.785398f; // 45 degrees

    /// Throws InvalidArgument for non-finite values, negative colours/intensities/absorption,
    /// shininess outside (0, 10000], |shift| > pi/4, widths outside (0, pi/2], eta outside
    /// (1, 3], causticWidth <= 0, glint angles outside [0, pi] or min > max.
    void validate() const;
};

} // namespace weft
