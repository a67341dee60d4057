#include "app/DemoSkyDome.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <glm/gtc/constants.hpp>

namespace weft::app {

namespace {

float linearToSrgb(float c) {
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

} // namespace

void paintSkyDome(Material& dome, const std::function<glm::vec3(const glm::vec3&)>& radiance,
                  int width, int height) {
    std::vector<glm::vec3> texels(size_t(width) * size_t(height));
    float peak = 0.0f;
    for (int y = 0; y < height; ++y) {
        const float polar = glm::pi<float>() * (float(y) + 0.5f) / float(height);
        for (int x = 0; x < width; ++x) {
            const float azimuth = glm::two_pi<float>() * (float(x) + 0.5f) / float(width);
            const glm::vec3 dir(std::sin(polar) * std::sin(azimuth), std::cos(polar),
                                std::sin(polar) * std::cos(azimuth));
            const glm::vec3 c = glm::max(radiance(dir), glm::vec3(0.0f));
            texels[size_t(y) * size_t(width) + size_t(x)] = c;
            peak = std::max(peak, std::max(c.x, std::max(c.y, c.z)));
        }
    }
    peak = std::max(peak, 1e-12f);
    ImageU8 img(width, height, 4);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec3 c = texels[size_t(y) * size_t(width) + size_t(x)] / peak;
            uint8_t* p = img.at(x, y);
            for (int k = 0; k < 3; ++k)
                p[k] = uint8_t(std::lround(255.0f * std::clamp(linearToSrgb(c[k]), 0.0f, 1.0f)));
            p[3] = 255;
        }
    // Ambient maps must be linear, and 8 linear bits band in a dark sky: the radiance goes into
    // the sRGB base texture T instead, under a white ambient map (the term is I_A K_A T).
    ImageU8 white(1, 1, 4);
    for (int k = 0; k < 4; ++k) white.at(0, 0)[k] = 255;
    dome.texture = std::make_shared<Texture>(std::move(img), true, false);
    dome.ambientMap = std::make_shared<Texture>(std::move(white), false, false);
    dome.ambientMapIsRadiance = false;
    dome.ka = glm::vec3(peak);
    dome.kd = dome.ks = glm::vec3(0.0f);
    dome.baseColor = glm::vec3(1.0f);
}

} // namespace weft::app
