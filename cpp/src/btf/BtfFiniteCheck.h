#pragma once
// Guards for fits whose input is finite but whose float32 arithmetic is not: sample values
// beyond ~1e19 square past FLT_MAX, beyond ~1e36 their sums overflow. Such a fit must not
// return NaN/inf maps or pick an exponent from an infinite error curve; it says why instead.
#include <weft/BtfSamples.h>
#include <weft/Error.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace weft {

/// Largest |value| of the samples (only computed to explain a failure).
inline float btfLargestSample(const BtfSamples& samples) {
    float m = 0.0f;
    for (float v : samples.values()) m = std::max(m, std::fabs(v));
    return m;
}

[[noreturn]] inline void throwBtfOverflow(const std::string& fit, const std::string& what,
                                          const BtfSamples& samples) {
    char largest[32];
    std::snprintf(largest, sizeof largest, "%g", double(btfLargestSample(samples)));
    throw InvalidArgument("the " + fit + " produced a non-finite " + what +
                          " (float32 overflow): the samples reach |p| = " + largest +
                          "; scale them to about [0, 1] before fitting");
}

/// Throws InvalidArgument (throwBtfOverflow) when `values` holds NaN or inf.
inline void requireFiniteFit(const std::vector<float>& values, const std::string& fit,
                             const std::string& what, const BtfSamples& samples) {
    for (float v : values)
        if (!std::isfinite(v)) throwBtfOverflow(fit, what, samples);
}

} // namespace weft
