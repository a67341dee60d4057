// BtfSamples storage and the Bonn direction set.
#include <weft/BtfSamples.h>
#include <weft/Error.h>

#include <cmath>

namespace weft {

glm::vec3 btfDirection(float thetaDeg, float phiDeg) {
    const double t = double(thetaDeg) * M_PI / 180.0, p = double(phiDeg) * M_PI / 180.0;
    return glm::vec3(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)),
                     float(std::cos(t)));
}

const std::vector<glm::vec2>& btfStandardDirections() {
    static const std::vector<glm::vec2> directions = [] {
        const int rings[6][2] = {{0, 1}, {15, 6}, {30, 12}, {45, 18}, {60, 20}, {75, 24}};
        std::vector<glm::vec2> out;
        for (const auto& ring : rings)
            for (int k = 0; k < ring[1]; ++k)
                out.emplace_back(float(ring[0]), float(360 / ring[1] * k));
        return out;
    }();
    return directions;
}

BtfSamples::BtfSamples(int width, int height, std::vector<BtfAngles> angles)
    : mWidth(width), mHeight(height), mAngles(std::move(angles)) {
    if (width <= 0 || height <= 0 || width > 65536 || height > 65536)
        throw InvalidArgument("BTF size must be 1..65536 texels per side, got " +
                              std::to_string(width) + "x" + std::to_string(height));
    if (mAngles.empty()) throw InvalidArgument("a BTF needs at least one sample");
    for (const BtfAngles& a : mAngles) {
        const float v[4] = {a.thetaLight, a.phiLight, a.thetaView, a.phiView};
        for (float x : v)
            if (!std::isfinite(x)) throw InvalidArgument("BTF angles must be finite");
        if (a.thetaLight < 0 || a.thetaLight >= 90 || a.thetaView < 0 || a.thetaView >= 90)
            throw InvalidArgument("BTF polar angles must lie in [0, 90) degrees, got light " +
                                  std::to_string(a.thetaLight) + ", view " +
                                  std::to_string(a.thetaView));
        mLights.push_back(btfDirection(a.thetaLight, a.phiLight));
        mViews.push_back(btfDirection(a.thetaView, a.phiView));
    }
    mValues.assign(texels() * 3 * mAngles.size(), 0.0f);
}

void BtfSamples::requireFinite() const {
    for (size_t i = 0; i < mValues.size(); ++i)
        if (!std::isfinite(mValues[i]))
            throw InvalidArgument("BTF sample " + std::to_string(i / (3 * texels())) +
                                  " holds a NaN or infinite value");
}

} // namespace weft
