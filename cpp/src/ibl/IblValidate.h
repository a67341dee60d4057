#pragma once
// Argument checks shared by the IBL tools (all throw InvalidArgument).
#include <weft/CubeMap.h>
#include <weft/IblConvert.h>

#include "core/Validate.h"

namespace weft {

/// Positive sizes up to 65536 per side.
void requireImageSize(int width, int height, const char* what);
/// Non-null pixels, valid sizes, finite values.
void requireRgb(RgbView image, const char* what);
/// Non-empty, finite and non-negative radiance.
void requireCube(const CubeMap& cube, const char* what);
/// 1 <= n <= maxValue.
void requireCount(int n, int maxValue, const char* what);
/// Refuses jobs of more than 4e10 elementary steps (minutes of CPU) instead of hanging.
void requireAffordable(double steps, const char* what);
/// The arguments of a GGX prefilter chain (CPU and GPU): a valid cube, size and sample counts,
/// levels in [1, log2(size) + 1], an affordable job.
void requireGgxArguments(const CubeMap& radiance, int size, int levels, int samples);
/// The arguments of the exact irradiance convolution (CPU and GPU): a valid cube, output and
/// source sizes in [1, 1024], an affordable job (36 size^2 sourceSize^2 steps).
void requireExactIrradianceArguments(const CubeMap& radiance, int size, int sourceSize);

} // namespace weft
