#pragma once
// Cast-shadow classification of one texel's samples against a fit (SPEC §3.5 robustness),
// shared by the Blinn-Phong and Lafortune fits. A cast shadow removes the diffuse and specular
// light and leaves the constant term, so a sample is taken as shadowed when it lies below
// base + diffuse / 2 (half the diffuse light; channel sums) and below the prediction by more
// than 4 robust standard deviations of the texel's residuals under steep light (and 2% of the
// prediction): noise and model error stay in.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace weft {

/// Robust standard deviation of the residuals seen - lit of the used samples (used[s] > 0)
/// under steep light (l_z >= 0.85: θ_l <= 31°, which cast shadows rarely reach; all used
/// samples when fewer than 5 are that steep): median absolute residual / 0.6745.
inline double steepResidualSigma(size_t count, const double* lit, const double* seen,
                                 const float* lz, const float* used) {
    static thread_local std::vector<double> store; // no allocation per texel
    std::vector<double>& res = store;
    res.clear();
    for (size_t s = 0; s < count; ++s)
        if (used[s] > 0.0f && lz[s] >= 0.85f) res.push_back(std::fabs(seen[s] - lit[s]));
    if (res.size() < 5)
        for (size_t s = 0; s < count; ++s)
            if (used[s] > 0.0f) res.push_back(std::fabs(seen[s] - lit[s]));
    if (res.empty()) return 0.0;
    const size_t n = res.size(), k = n / 2;
    if (n > 32) {
        std::nth_element(res.begin(), res.begin() + long(k), res.end());
        return res[k] / 0.6745;
    }
    // The k-th smallest by rank (the values below it, and equal ones before it): the element
    // nth_element would put at k, in loops the compiler vectorises (half the time of
    // nth_element for the ~20 steep samples of a texel; it was 4% of a shadowed fit)
    const double* v = res.data();
    for (size_t i = 0; i < n; ++i) {
        const double x = v[i];
        long less = 0, equal = 0;
        for (size_t j = 0; j < n; ++j) less += v[j] < x;
        for (size_t j = 0; j < i; ++j) equal += v[j] == x;
        if (size_t(less + equal) == k) return x / 0.6745;
    }
    return 0.0; // not reached: the ranks are a permutation of 0..n-1
}

/// Per sample s < count: lit[s] the fit's light-dependent part, diffuse[s] its diffuse part,
/// seen[s] the observed value minus `base` (the constant term), lz[s] the light's z, used[s] > 0
/// for a sample the fit used. Writes weights (1 used, 0 left out; all 1 when fewer than
/// `minUsed` would remain) and returns the number left out; `misfit` counts the samples off the
/// prediction by more than 3 σ either way (a fit pulled by shadows may hide them from the first
/// test). σ is steepResidualSigma, at most `sigmaCap`: a fit pulled far from the data (by
/// shadowed samples it still uses, or by a highlight that a model without one cannot follow)
/// misses every sample by more than the noise, and a σ measured on it would hide the shadows
/// that pulled it.
inline int classifyCastShadows(size_t count, const double* lit, const double* diffuse,
                               const double* seen, double base, const float* lz, const float* used,
                               int minUsed, float* weights, int& misfit,
                               double sigmaCap = HUGE_VAL) {
    const double sigma = std::min(steepResidualSigma(count, lit, seen, lz, used), sigmaCap);
    int left = 0;
    misfit = 0;
    for (size_t s = 0; s < count; ++s) {
        const double margin = std::max(4.0 * sigma, 0.02 * (lit[s] + base));
        const bool below = lit[s] - seen[s] > margin;
        // half the diffuse light, not of the whole prediction: a highlight that overshoots a
        // sample must not make it look shadowed (it would then be left out and never corrected)
        const bool dark = below && seen[s] < 0.5 * diffuse[s];
        weights[s] = dark ? 0.0f : 1.0f;
        left += dark ? 1 : 0;
        misfit += std::fabs(lit[s] - seen[s]) > 0.75 * margin ? 1 : 0;
    }
    if (int(count) - left < minUsed) { // too few left to fit the unknowns well: use them all
        std::fill(weights, weights + count, 1.0f);
        return 0;
    }
    return left;
}

} // namespace weft
