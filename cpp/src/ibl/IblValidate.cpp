// Argument checks shared by the IBL tools.
#include "IblValidate.h"

#include <cmath>
#include <string>

#include <weft/Error.h>

namespace weft {

void requireImageSize(int width, int height, const char* what) {
    if (width < 1 || height < 1 || width > 65536 || height > 65536)
        throw InvalidArgument(std::string(what) + " size must be in [1, 65536], got " +
                              std::to_string(width) + " x " + std::to_string(height));
}

void requireRgb(RgbView image, const char* what) {
    requireImageSize(image.width, image.height, what);
    if (!image.pixels) throw InvalidArgument(std::string(what) + " has no pixels");
    const size_t n = size_t(image.width) * image.height * 3;
    for (size_t k = 0; k < n; ++k)
        if (!std::isfinite(image.pixels[k]))
            throw InvalidArgument(std::string(what) + " must be finite (found NaN/inf)");
}

void requireCube(const CubeMap& cube, const char* what) {
    if (cube.empty()) throw InvalidArgument(std::string(what) + " is empty");
    cube.requireFinite(what, true);
}

void requireCount(int n, int maxValue, const char* what) {
    if (n < 1 || n > maxValue)
        throw InvalidArgument(std::string(what) + " must be in [1, " + std::to_string(maxValue) +
                              "], got " + std::to_string(n));
}

void requireAffordable(double steps, const char* what) {
    if (steps > 4e10)
        throw InvalidArgument(std::string(what) + ": about " + std::to_string(steps) +
                              " steps is too expensive; reduce the sizes or sample counts");
}

void requireGgxArguments(const CubeMap& radiance, int size, int levels, int samples) {
    requireCube(radiance, "radiance cube map");
    requireCount(size, 4096, "output size");
    requireCount(samples, 1 << 20, "sample count");
    int maxLevels = 1;
    while ((size >> maxLevels) >= 1) ++maxLevels;
    if (levels < 1 || levels > maxLevels)
        throw InvalidArgument("levels must be in [1, " + std::to_string(maxLevels) + "] for size " +
                              std::to_string(size));
    requireAffordable(8.0 * size * size * samples * 16.0, "GGX prefilter");
}

void requireExactIrradianceArguments(const CubeMap& radiance, int size, int sourceSize) {
    requireCube(radiance, "radiance cube map");
    requireCount(size, 1024, "output size");
    requireCount(sourceSize, 1024, "source size");
    requireAffordable(36.0 * size * size * sourceSize * sourceSize, "exact irradiance");
}

} // namespace weft
