"""One exponent for a material whose texels agree: empirical-Bayes pooling of the per-texel
Blinn-Phong exponents (``fit_blinn_phong(exponent="pooled")``).

A per-texel fit pins each texel's exponent only as well as the few samples under its lobe allow:
on 8-bit data with 0.004 noise its median error is 2-7%, on JPEG q90 11-31% (BENCHMARKS.md, btf),
even where the whole material has one exponent, as the seed's fit assumes (SPEC §3.3: one n
searched over 1..1024). Pooling decides from the data how much of the texels' spread is real.
Each texel's η = ln e is modelled as η_i = μ + δ_i + ε_i with the material's spread
δ_i ~ N(0, τ²) and the estimation error ε_i ~ N(0, s_i²), s_i² from the fit's own Gauss-Newton
covariance (σ_i² (JᵀJ)⁻¹ at the fitted parameters, σ_i² from the texel's residuals). μ and τ² are
estimated by the method of moments (DerSimonian & Laird 1986, "Meta-analysis in clinical
trials"), and each texel keeps the posterior mean μ + τ² / (τ² + s_i²) (η_i - μ) (James-Stein
shrinkage; Efron & Morris 1975). Where the texels' spread is what their errors explain, τ = 0
and every texel takes μ (one exponent, far more precise than any texel's); where the material's
exponents differ by more than that (threads of two fibres), τ is large and each texel keeps
nearly its own. Texels without a highlight (k = 0) have no exponent to estimate: they take μ.

The covariance ignores errors that are correlated across a texel's samples (JPEG compresses
the same content alike in all 81 images), so on JPEG s_i comes out too small (by 1.0-2.8x on the
benchmark's datasets, against the truth). :func:`error_scale` measures that factor from the data
alone: neighbouring texels mostly share the material's exponent (threads and regions span
several texels), so their differences η_i - η_j measure the estimation error, N(0, s_i² + s_j²)
times the factor squared; the median over all neighbour pairs leaves out the pairs that straddle
a region's edge. It matched the truth's factor within 0.05 on every dataset checked whose
exponent is uniform (1.00 on PNG), and where the exponent varies between neighbours it comes out
larger, which τ then absorbs (BENCHMARKS.md, btf). Only factors above 1 are applied: errors
correlated between neighbours (JPEG's 8 x 8 blocks) make the differences too small, not too
large.
"""

from __future__ import annotations

from typing import Any, Dict, Optional, Tuple

import numpy as np

from weft.btf.material import BtfMaterial

#: BT.601 luma weights (the fit's ``luminance_normals`` model)
LUMA = np.array([0.299, 0.587, 0.114])
#: the median of the χ² distribution with one degree of freedom
CHI2_1_MEDIAN = 0.454936


def _frame(n: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Two unit tangents orthogonal to each unit normal (H, W, 3)."""
    helper = np.where(np.abs(n[..., :1]) < 0.9, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0])
    t1 = np.cross(n, helper)
    t1 /= np.linalg.norm(t1, axis=-1, keepdims=True)
    return t1, np.cross(n, t1)


def eta_variance(samples: Any, material: BtfMaterial, luminance: bool = False,
                 shadowed: Optional[np.ndarray] = None) -> np.ndarray:
    """(H, W) variance of each texel's fitted η = ln e (inf where the texel has no highlight or
    too few samples): σ² [(JᵀJ)⁻¹]_ηη of the texel's least-squares problem at the fitted
    parameters (the normal's two tilts, per channel ρ, ρa and k, and η; one channel, the luma,
    with ``luminance``), σ² = its squared residuals over the degrees of freedom. ``shadowed``:
    (S, H, W) samples left out (cast shadows)."""
    values = np.asarray(samples.values, np.float64)
    lights = np.asarray(samples.light_dirs, np.float64)
    views = np.asarray(samples.view_dirs, np.float64)
    halves = lights + views
    halves /= np.linalg.norm(halves, axis=1, keepdims=True)
    flat = bool(material.flat_specular_normal)
    h, w = material.shape
    out = np.full((h, w), np.inf)
    normal = np.asarray(material.normal, np.float64)
    rho = np.asarray(material.albedo, np.float64)
    const = rho * np.asarray(material.ambient, np.float64)
    k = np.zeros((h, w, 3)) if material.specular is None else \
        np.asarray(material.specular, np.float64)
    e = (np.asarray(material.exponent_map, np.float64) if material.exponent_map is not None
         else np.full((h, w), float(material.exponent)))
    if luminance:
        values = np.einsum("c,schw->shw", LUMA, values)[:, None]
        rho, const, k = (a @ LUMA for a in (rho, const, k))
        rho, const, k = rho[..., None], const[..., None], k[..., None]
    channels = values.shape[1]
    params = 3 * channels + 3
    # rows per chunk: the Jacobians of a chunk within ~64 MB of doubles
    rows = max(1, min(h, 8_000_000 // (w * values.shape[0] * channels * params)))
    for r0 in range(0, h, rows):
        sl = slice(r0, min(h, r0 + rows))
        n = normal[sl]
        t1, t2 = _frame(n)
        nl = np.einsum("hwc,sc->shw", n, lights)
        lit = nl > 0
        nh = (np.broadcast_to(halves[:, 2, None, None], nl.shape) if flat
              else np.einsum("hwc,sc->shw", n, halves))
        nh = np.clip(nh, 1e-12, None)
        ee = e[sl][None]
        g = lit * nh ** ee                                    # the lobe's shape (S, h, w)
        d = np.maximum(nl, 0.0)
        dd = [lit * np.einsum("hwc,sc->shw", t, lights) for t in (t1, t2)]
        dg = [np.zeros_like(g) if flat else
              g * ee / nh * np.einsum("hwc,sc->shw", t, halves) for t in (t1, t2)]
        dg_eta = g * ee * np.log(nh)
        used = np.ones_like(d) if shadowed is None else (~np.asarray(shadowed)[:, sl]) * 1.0
        s_count = used.sum(0)
        jac = np.zeros(d.shape + (channels, params))      # (S, h, w, C, P)
        sse = np.zeros(d.shape[1:])
        for c in range(channels):
            m_c, b_c, k_c = rho[sl][..., c], const[sl][..., c], k[sl][..., c]
            jac[..., c, 3 * c] = d
            jac[..., c, 3 * c + 1] = 1.0
            jac[..., c, 3 * c + 2] = g
            for j in range(2):
                jac[..., c, 3 * channels + j] = m_c * dd[j] + k_c * dg[j]
            jac[..., c, 3 * channels + 2] = k_c * dg_eta
            resid = values[:, c, sl] - (m_c * d + b_c + k_c * g)
            sse += (used * resid ** 2).sum(0)
        jac *= used[..., None, None]
        # JᵀJ per texel as one batched product: (texels, S C, P)ᵀ (texels, S C, P)
        flat_jac = np.moveaxis(jac, 0, 2).reshape(sse.size, -1, params)
        jtj = np.matmul(np.swapaxes(flat_jac, 1, 2), flat_jac).reshape(sse.shape + (params,
                                                                                   params))
        dof = s_count * channels - params
        sigma2 = sse / np.maximum(dof, 1)
        # every column scaled to unit norm before inverting (η's is tiny where k is near 0)
        scale = np.sqrt(np.clip(np.einsum("...ii->...i", jtj), 1e-300, None))
        inv = np.linalg.pinv(jtj / scale[..., :, None] / scale[..., None, :])
        var = sigma2 * inv[..., -1, -1] / scale[..., -1] ** 2
        ok = (np.max(k[sl], axis=-1) > 0) & (dof > 0) & np.isfinite(var) & (var > 0) & \
            (np.abs(jtj[..., -1, -1]) > 1e-20)
        out[sl] = np.where(ok, var, np.inf)
    return out


def error_scale(eta: np.ndarray, variance: np.ndarray) -> float:
    """The factor (>= 1) by which the (H, W) variances understate the errors of the (H, W)
    estimates η, from the 4-neighbour differences: median of (η_i - η_j)² / (s_i² + s_j²) over
    the pairs where both are finite, over the median of χ²(1) (0.4549); 1 without pairs."""
    eta = np.asarray(eta, np.float64)
    variance = np.asarray(variance, np.float64)
    ok = np.isfinite(eta) & np.isfinite(variance) & (variance > 0)
    ratios = []
    for a, b in (((slice(None), slice(1, None)), (slice(None), slice(None, -1))),
                 ((slice(1, None), slice(None)), (slice(None, -1), slice(None)))):
        both = ok[a] & ok[b]
        ratios.append(((eta[a] - eta[b]) ** 2 / (variance[a] + variance[b]))[both])
    pairs = np.concatenate(ratios)
    if pairs.size == 0:
        return 1.0
    return max(1.0, float(np.median(pairs)) / CHI2_1_MEDIAN)


def pool(eta: np.ndarray, variance: np.ndarray,
         iterations: int = 100) -> Tuple[np.ndarray, Dict[str, float]]:
    """Posterior means of η_i (the module's model) and {"mean": μ, "spread": τ, "texels"}:
    μ and τ² by DerSimonian-Laird moments iterated to a fixed point (Paule-Mandel); texels with
    infinite variance take μ. Raises ValueError when no texel has a finite variance."""
    eta = np.asarray(eta, np.float64)
    variance = np.asarray(variance, np.float64)
    ok = np.isfinite(eta) & np.isfinite(variance) & (variance > 0)
    if not np.any(ok):
        raise ValueError("no texel with a fitted highlight to pool")
    x, v = eta[ok], variance[ok]
    tau2 = 0.0
    mu = float(np.average(x, weights=1.0 / v))
    for _ in range(iterations):
        wts = 1.0 / (v + tau2)
        mu = float(np.sum(wts * x) / np.sum(wts))
        nxt = max(0.0, float(np.sum(wts * ((x - mu) ** 2 - v)) / np.sum(wts)))
        if abs(nxt - tau2) <= 1e-10 * max(1.0, tau2):
            tau2 = nxt
            break
        tau2 = nxt
    post = np.full(eta.shape, mu)
    post[ok] = mu + tau2 / (tau2 + v) * (x - mu)
    return post, {"mean": float(np.exp(mu)), "spread": float(np.sqrt(tau2)),
                  "texels": int(np.count_nonzero(ok))}
