#pragma once
// The sRGB transfer function (IEC 61966-2-1): an encoded value in [0, 1] to linear light, as the
// GPU's sRGB formats decode it when a texture is sampled.

#include <cmath>

namespace weft {

inline float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

} // namespace weft
