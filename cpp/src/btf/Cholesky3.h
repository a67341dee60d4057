#pragma once
// Cholesky factorisation of a symmetric 3x3 matrix with a relative pivot check. Inline: the
// per-texel fits call solve() many times per iteration.
#include <algorithm>
#include <cmath>

namespace weft {

struct Cholesky3 {
    double l[3][3] = {};
    /// False when a pivot falls below `relTol` times the largest diagonal entry (singular or
    /// indefinite matrix).
    bool factor(const double a[3][3], double relTol) {
        const double scale = std::max({a[0][0], a[1][1], a[2][2]});
        if (!(scale > 0.0) || !std::isfinite(scale)) return false;
        for (int j = 0; j < 3; ++j) {
            double d = a[j][j];
            for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
            if (!(d > relTol * scale)) return false;
            l[j][j] = std::sqrt(d);
            for (int i = j + 1; i < 3; ++i) {
                double v = a[i][j];
                for (int k = 0; k < j; ++k) v -= l[i][k] * l[j][k];
                l[i][j] = v / l[j][j];
            }
        }
        return true;
    }
    /// x = A⁻¹ b with the stored factor.
    void solve(const double b[3], double x[3]) const {
        double y[3];
        for (int i = 0; i < 3; ++i) {
            double v = b[i];
            for (int k = 0; k < i; ++k) v -= l[i][k] * y[k];
            y[i] = v / l[i][i];
        }
        for (int i = 2; i >= 0; --i) {
            double v = y[i];
            for (int k = i + 1; k < 3; ++k) v -= l[k][i] * x[k];
            x[i] = v / l[i][i];
        }
    }
};

} // namespace weft
