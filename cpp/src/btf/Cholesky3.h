#pragma once
// Cholesky factorisation of a symmetric 3x3 matrix with a relative pivot check.

namespace weft {

struct Cholesky3 {
    double l[3][3] = {};
    /// False when a pivot falls below `relTol` times the largest diagonal entry (singular or
    /// indefinite matrix).
    bool factor(const double a[3][3], double relTol);
    /// x = A⁻¹ b with the stored factor.
    void solve(const double b[3], double x[3]) const;
};

} // namespace weft
