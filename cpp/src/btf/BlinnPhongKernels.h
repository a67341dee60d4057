#pragma once
// The per-sample SIMD kernels of the built-in Blinn-Phong fit (BlinnPhongKernels.cpp): the cost
// pass (basis d, g and their Gram / projection sums), the derivative pass for Kaufman's JᵀJ,
// and a vector log; each picks the AVX2 + FMA copy at run time on x86-64 where it exists.
#include "btf/BlinnPhongTexel.h"

namespace weft {

struct CostInput {
    const BlinnPhongGeometry* geo;
    const float* p[3]; // planes
    const float* w;    // sample weights
    float n[3], e;
    float *d, *g, *lg; // out, per padded sample
    /// false: no highlight column (g = log = 0, no log or exp per sample)
    bool specular = true;
};
struct CostSums {
    double sd, sg, sdd, sdg, sgg, sdp[3], sgp[3];
};

struct DerivInput {
    const BlinnPhongGeometry* geo;
    const float* p[3];
    const float* w;
    const float *d, *g, *lg;
    float n[3], dn[2][3], e, x[3][3];
};
// D = (∂d_u, ∂d_v, ∂g_u, ∂g_v, ∂g_η): DᵀD, (d, 1, g)ᵀD, r_cᵀD with r_c = p_c - Φ x_c.
struct DerivSums {
    double dd[5][5], phiD[3][5], rD[3][5];
};

/// d, g, log(n_s·h) per padded sample and their sums (in.d, in.g, in.lg are written).
void blinnPhongCost(const CostInput& in, CostSums& out);
/// The derivative sums of DerivSums for the current θ and linear coefficients.
void blinnPhongDeriv(const DerivInput& in, DerivSums& out);
/// out[s] = log(x[s]) for x > 0, else 0; n a multiple of the lane count.
void blinnPhongLog(const float* x, float* out, int n);

} // namespace weft
