"""Blinn-Phong refinement against what JPEG files store (issue 12: JPEG q90 data).

A JPEG keeps, per 8 x 8 block of each colour component, the DCT coefficients F of the 8-bit
image (JFIF YCbCr, levels shifted by -128) quantised as c = round(F / q). The decoded image is
the cells' centres c q; its error is the quantised AC content inside each block, the same
across the 81 images of a texel (similar content compresses alike), so per-texel fits to
decoded values do not average it out. What the file does say is that F lay in the cell
[(c - 1/2) q, (c + 1/2) q]. Here the model's luma, taken through the block DCT, is fitted to
those cells: the dead-zone cost sum_j dist(F_j, cell_j)^2, plus ``tie`` times the squared
distance to the cells' centres so that the solution inside the feasible set is the one
nearest the decoded data. The DCT couples the 64 texels of a block, so every block is one
Gauss-Newton / Levenberg-Marquardt problem over its texels' luma parameters (normal u, v;
m_Y, b_Y, k_Y; log e), solved with a dense batched Cholesky (384 unknowns per block).

The colours (chroma, stored at half resolution) are then fitted per texel to the decoded RGB
at the refined normal and exponent, and their luma replaced by the refined one.
Samples the visibility pass would leave out (much darker than the model: cast shadows) enter
the block DCT with their decoded values and no derivative, so they neither pull nor count.
"""

from __future__ import annotations

from typing import Any, Dict, Optional, Tuple

import numpy as np

from weft.btf.material import BtfMaterial

# JFIF (ITU-T T.871) full-range YCbCr from 8-bit RGB
_YCC = np.array([[0.299, 0.587, 0.114],
                 [-0.168736, -0.331264, 0.5],
                 [0.5, -0.418688, -0.081312]])
_RGB = np.linalg.inv(_YCC)


def dct_matrix() -> np.ndarray:
    """The orthonormal 8-point DCT-II (JPEG's, T.81 A.3.3): row u, column x."""
    k = np.arange(8)
    c = np.sqrt(2 / 8) * np.cos((2 * k[None, :] + 1) * k[:, None] * np.pi / 16)
    c[0] /= np.sqrt(2)
    return c


def _log_phi_lower(z: np.ndarray) -> np.ndarray:
    """log Φ(z) for z <= 0, Φ the standard normal CDF, accurate far into the tail:
    Φ(z) = erfc(-z / √2) / 2 with erfc from the Chebyshev fit of Numerical Recipes (2nd ed.,
    §6.2, erfcc; relative error < 1.2e-7), taken in logs so that nothing underflows."""
    x = -z / np.sqrt(2.0)
    t = 1.0 / (1.0 + 0.5 * x)
    poly = -1.26551223 + t * (1.00002368 + t * (0.37409196 + t * (0.09678418 + t * (
        -0.18628806 + t * (0.27886807 + t * (-1.13520398 + t * (1.48851587 + t * (
            -0.82215223 + t * 0.17087277))))))))
    return np.log(0.5 * t) - x * x + poly


def cell_nll(f: np.ndarray, lo: np.ndarray, hi: np.ndarray, sigma: float
             ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """-log P(lo <= F + noise <= hi) for Gaussian noise of deviation ``sigma`` (the encoder saw
    the noisy image and quantised it into the cell), and its first and second derivatives in F.
    Inside a wide cell it is flat, outside it grows as the squared distance / 2 sigma^2; a
    narrow cell (q of the order of sigma) acts like a Gaussian around its centre."""
    a, b = (hi - f) / sigma, (lo - f) / sigma          # a > b
    # orient so that both bounds sit in the lower tail, where log Φ is accurate
    flip = a + b > 0
    hi_z = np.where(flip, -b, a)
    lo_z = np.where(flip, -a, b)
    la = _log_phi_lower(np.minimum(hi_z, 0.0))
    la = np.where(hi_z > 0, np.log1p(-np.exp(_log_phi_lower(-np.maximum(hi_z, 0.0)))), la)
    lb = _log_phi_lower(np.minimum(lo_z, 0.0))
    logp = la + np.log1p(-np.exp(np.minimum(lb - la, -1e-12)))
    lphi = lambda z: -0.5 * z * z - 0.5 * np.log(2 * np.pi)
    ra, rb = np.exp(lphi(a) - logp), np.exp(lphi(b) - logp)   # φ(a) / P, φ(b) / P
    d1 = (ra - rb) / sigma
    d2 = d1 * d1 + (a * ra - b * rb) / (sigma * sigma)
    return -logp, d1, np.maximum(d2, 0.0)


def luma_cells(samples: Any) -> Optional[Dict[str, np.ndarray]]:
    """The luma cells of JPEG samples: ``coef`` c and ``quant`` q as (S, by, bx, 64) floats
    (natural order, row-major u, v), or None when the samples carry no cells or their blocks do
    not tile the image (sizes not a multiple of 8)."""
    cells = getattr(samples, "jpeg_cells", None)
    if cells is None:
        return None
    comp = cells["components"][0]
    coef = np.asarray(comp["coefficients"], np.float64)
    s, by, bx = coef.shape[:3]
    if by * 8 != samples.height or bx * 8 != samples.width:
        return None
    quant = np.asarray(comp["quant"], np.float64).reshape(s, 1, 1, 64)
    return {"coef": coef.reshape(s, by, bx, 64), "quant": np.broadcast_to(quant, (s, by, bx, 64))}


def _blocks(a: np.ndarray) -> np.ndarray:
    """(..., H, W) -> (..., by, bx, 64) texels of each 8 x 8 block, row-major."""
    *lead, h, w = a.shape
    b = a.reshape(*lead, h // 8, 8, w // 8, 8)
    b = np.moveaxis(b, -3, -2)
    return b.reshape(*lead, h // 8, w // 8, 64)


class _LumaModel:
    """Y (8-bit units) of the Blinn-Phong model per texel and sample, and its derivatives
    with respect to (u, v, m_Y, b_Y, k_Y, log e)."""

    def __init__(self, lights: np.ndarray, views: np.ndarray, flat: bool):
        self.l = lights                                  # (S, 3)
        h = lights + views
        self.h = h / np.linalg.norm(h, axis=1, keepdims=True)
        self.flat = flat

    def eval(self, p: np.ndarray, jac: bool) -> Tuple[np.ndarray, Optional[np.ndarray]]:
        """p (N, 6) -> Y (N, S), dY/dp (N, S, 6)."""
        u, v, m, b, k, le = (p[:, i] for i in range(6))
        r = np.sqrt(u * u + v * v + 1)
        n = np.stack([u, v, np.ones_like(u)], 1) / r[:, None]
        d = n @ self.l.T                                  # (N, S)
        lit = d > 0
        e = np.exp(le)
        c = (n @ self.h.T) if not self.flat else np.broadcast_to(self.h[:, 2], d.shape)
        c = np.clip(c, 1e-12, 1.0)
        logc = np.log(c)
        spec = np.where(lit, np.exp(e[:, None] * logc), 0.0)
        diff = np.maximum(d, 0)
        y = 255.0 * (m[:, None] * diff + b[:, None] + k[:, None] * spec)
        if not jac:
            return y, None
        g = np.empty(d.shape + (6,))
        # dn/du = (e_x - n n_x) / r, dn/dv = (e_y - n n_y) / r
        dn_du = (np.array([1.0, 0, 0])[None, :] - n * n[:, :1]) / r[:, None]
        dn_dv = (np.array([0, 1.0, 0])[None, :] - n * n[:, 1:2]) / r[:, None]
        dd_du, dd_dv = dn_du @ self.l.T, dn_dv @ self.l.T
        g[..., 0] = m[:, None] * np.where(lit, dd_du, 0)
        g[..., 1] = m[:, None] * np.where(lit, dd_dv, 0)
        if not self.flat:
            ds = np.where(lit, e[:, None] * spec / c, 0.0)  # dS/dc
            g[..., 0] += k[:, None] * ds * (dn_du @ self.h.T)
            g[..., 1] += k[:, None] * ds * (dn_dv @ self.h.T)
        g[..., 2] = diff
        g[..., 3] = 1.0
        g[..., 4] = spec
        g[..., 5] = k[:, None] * spec * logc * e[:, None]
        return y, g * 255.0


def _params(material: BtfMaterial, flat: bool) -> np.ndarray:
    n = np.asarray(material.normal, np.float64).reshape(-1, 3)
    w = _YCC[0]
    rho = np.asarray(material.albedo, np.float64).reshape(-1, 3)
    amb = np.asarray(material.ambient, np.float64).reshape(-1, 3)
    spec = np.zeros_like(rho) if material.specular is None else \
        np.asarray(material.specular, np.float64).reshape(-1, 3)
    e = np.full(len(n), float(material.exponent)) if material.exponent_map is None else \
        np.asarray(material.exponent_map, np.float64).reshape(-1)
    nz = np.maximum(n[:, 2], 1e-3)
    return np.stack([n[:, 0] / nz, n[:, 1] / nz, rho @ w, (rho * amb) @ w, spec @ w,
                     np.log(np.maximum(e, 1.0))], 1)


def refine_luma(samples: Any, material: BtfMaterial, cells: Dict[str, np.ndarray], *,
                max_exponent: float, shadowed: Optional[np.ndarray] = None,
                iterations: int = 6, sigma: float = 0.77, prior: float = 1.0,
                cg_iterations: int = 25,
                chunk: int = 256) -> Tuple[np.ndarray, Dict[str, Any]]:
    """Per-texel luma parameters (H*W, 6) minimising the dead-zone cost over each block.
    ``shadowed`` (S, H, W) bool: samples left out."""
    h, w = samples.height, samples.width
    flat = bool(material.flat_specular_normal)
    model = _LumaModel(np.asarray(samples.light_dirs, np.float64),
                       np.asarray(samples.view_dirs, np.float64), flat)
    vals = np.asarray(samples.values, np.float64)                     # (S, 3, H, W)
    ns = len(vals)
    y_data = np.einsum("c,schw->shw", _YCC[0], vals) * 255.0          # decoded luma
    p = _params(material, flat)
    C = dct_matrix()
    B = np.kron(C, C)                                                 # (64, 64): F = B y
    B2 = B * B
    nblocks = (h // 8) * (w // 8)
    tex = _blocks(np.arange(h * w).reshape(h, w)).reshape(-1, 64)     # (blocks, 64)
    coef = cells["coef"].reshape(ns, -1, 64)
    quant = cells["quant"].reshape(ns, -1, 64)
    ydat_b = _blocks(y_data).reshape(ns, -1, 64)
    sh_b = None if shadowed is None else _blocks(shadowed).reshape(ns, -1, 64)
    lmax = float(np.log(max_exponent))
    stats = {"cost_before": 0.0, "cost_after": 0.0}
    for start in range(0, nblocks, chunk):
        blk = np.arange(start, min(start + chunk, nblocks))
        nb = len(blk)
        idx = tex[blk]                                                # (nb, 64)
        c = coef[:, blk].transpose(1, 0, 2)                           # (nb, S, 64)
        qq = quant[:, blk].transpose(1, 0, 2)
        lo, hi = (c - 0.5) * qq, (c + 0.5) * qq
        pvar = 1.0 / (qq * qq / 12.0 + sigma * sigma)
        yd = ydat_b[:, blk].transpose(1, 0, 2)
        keep = None if sh_b is None else ~sh_b[:, blk].transpose(1, 0, 2)

        def evaluate(q: np.ndarray, jac: bool):
            y, g = model.eval(q.reshape(-1, 6), jac)
            y = y.reshape(nb, 64, ns).transpose(0, 2, 1)              # (nb, S, 64)
            if keep is not None:
                y = np.where(keep, y, yd)
            f = (y - 128.0) @ B.T                                     # block DCT
            nll, d1, d2 = cell_nll(f, lo, hi, sigma)
            if prior > 0:   # the decoded value as a measurement of variance q^2/12 + sigma^2
                dv = f - (lo + hi) * 0.5
                nll = nll + prior * dv * dv * 0.5 * pvar
                d1 = d1 + prior * dv * pvar
                d2 = d2 + prior * pvar
            cost = np.sum(nll, (1, 2))
            if not jac:
                return cost, None
            g = g.reshape(nb, 64, ns, 6).transpose(0, 2, 1, 3)        # (nb, S, 64t, 6)
            if keep is not None:
                g = g * keep[..., None]
            act = d2 + 1e-4 / sigma ** 2                              # Hessian weight per f
            ry = d1 @ B                                               # back to texels
            grad = np.einsum("bst,bsti->bti", ry, g)                  # (nb, 64, 6)
            diag = act @ B2                                           # P_s[t, t]
            hd = np.einsum("bst,bsti,bstj->btij", diag, g, g)         # per-texel 6 x 6
            return cost, (grad, g, act, hd)

        def hess_vec(g, act, v):
            y = np.einsum("bsti,bti->bst", g, v)
            z = ((y @ B.T) * act) @ B
            return np.einsum("bst,bsti->bti", z, g)

        q = p[idx.reshape(-1)].reshape(nb, 64, 6)
        lam = np.full(nb, 1e-2)
        cost, (grad, g, act, hd) = evaluate(q, True)
        stats["cost_before"] += float(cost.sum())
        eye6 = np.eye(6)
        for _ in range(iterations):
            # LM: (H + lam diag-blocks(H)) step = -grad, by preconditioned CG per block
            dscale = np.einsum("btii->bti", hd).mean((1, 2))[:, None, None, None]
            damp = lam[:, None, None, None] * hd + 1e-9 * dscale * eye6
            pre = np.linalg.inv(hd + damp + 1e-12 * eye6)
            x = np.zeros_like(grad)
            r = -grad
            z = np.einsum("btij,btj->bti", pre, r)
            d = z.copy()
            rz = np.sum(r * z, (1, 2))
            for _ in range(cg_iterations):
                ad = hess_vec(g, act, d) + np.einsum("btij,btj->bti", damp, d)
                dad = np.sum(d * ad, (1, 2))
                alpha = np.where(dad > 0, rz / np.maximum(dad, 1e-300), 0.0)
                x += alpha[:, None, None] * d
                r -= alpha[:, None, None] * ad
                z = np.einsum("btij,btj->bti", pre, r)
                rz2 = np.sum(r * z, (1, 2))
                beta = np.where(rz > 0, rz2 / np.maximum(rz, 1e-300), 0.0)
                d = z + beta[:, None, None] * d
                rz = rz2
            trial = q + x
            trial[..., 2:5] = np.maximum(trial[..., 2:5], 0.0)
            trial[..., 5] = np.clip(trial[..., 5], 0.0, lmax)
            tc, _ = evaluate(trial, False)
            better = tc < cost
            lam = np.where(better, lam * 0.3, lam * 10.0)
            if better.any():
                q = np.where(better[:, None, None], trial, q)
                cost, (grad, g, act, hd) = evaluate(q, True)
        stats["cost_after"] += float(cost.sum())
        p[idx.reshape(-1)] = q.reshape(-1, 6)
    return p, stats


def colours(samples: Any, p: np.ndarray, flat: bool,
            shadowed: Optional[np.ndarray] = None) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """m, b, k (H*W, 3) at the refined normal and exponent: per texel least squares to the
    decoded RGB over the kept samples, in YCbCr with the luma replaced by the refined one."""
    model = _LumaModel(np.asarray(samples.light_dirs, np.float64),
                       np.asarray(samples.view_dirs, np.float64), flat)
    q = p.copy()
    q[:, 2:5] = 0
    q[:, 2] = 1 / 255.0
    diff, _ = model.eval(q, False)                                    # D (N, S)
    q[:, 2], q[:, 4] = 0, 1 / 255.0
    spec, _ = model.eval(q, False)
    vals = np.asarray(samples.values, np.float64)
    rgb = vals.reshape(len(vals), 3, -1).transpose(2, 0, 1)           # (N, S, 3)
    a = np.stack([diff, np.ones_like(diff), spec], -1)                # (N, S, 3)
    if shadowed is not None:
        wgt = (~shadowed.reshape(len(vals), -1).T).astype(np.float64)
        a = a * wgt[..., None]
        rgb = rgb * wgt[..., None]
    ata = np.einsum("nsi,nsj->nij", a, a) + 1e-9 * np.eye(3)
    atb = np.einsum("nsi,nsc->nic", a, rgb @ _YCC.T)                  # YCbCr targets
    x = np.linalg.solve(ata, atb)                                     # (N, 3 terms, 3 ycc)
    x[:, :, 0] = p[:, 2:5]
    out = np.maximum(x @ _RGB.T, 0.0)                                 # (N, terms, RGB)
    return out[:, 0], out[:, 1], out[:, 2]


def refine(samples: Any, material: BtfMaterial, *, max_exponent: float,
           shadowed: Optional[np.ndarray] = None, iterations: int = 6,
           sigma: float = 0.77, prior: float = 1.0) -> Tuple[BtfMaterial, Dict[str, Any]]:
    """The material refined against the samples' JPEG cells (unchanged, ``refined`` False, when
    there are none or the blocks do not tile the image). ``sigma``: the sensor noise in 8-bit
    luma levels (0.77: noise 0.004 per channel plus the encoder's rounding). ``prior``: weight of
    the decoded value as a measurement of variance q^2/12 + sigma^2 (0: the cells alone, which
    wander along directions they do not constrain). ``shadowed`` (S, H, W): samples left out."""
    cells = luma_cells(samples)
    if cells is None:
        return material, {"refined": False}
    flat = bool(material.flat_specular_normal)
    p, stats = refine_luma(samples, material, cells, max_exponent=max_exponent,
                           shadowed=shadowed, iterations=iterations, sigma=sigma,
                           prior=prior)
    m, b, k = colours(samples, p, flat, shadowed)
    h, w = samples.height, samples.width
    n = np.stack([p[:, 0], p[:, 1], np.ones(len(p))], 1)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    rho = np.maximum(m, 1e-6)
    out = BtfMaterial(normal=n.reshape(h, w, 3), albedo=rho.reshape(h, w, 3),
                      ambient=(b / rho).reshape(h, w, 3), specular=k.reshape(h, w, 3),
                      exponent=float(material.exponent),
                      exponent_map=np.exp(p[:, 5]).reshape(h, w),
                      flat_specular_normal=flat, clamp_diffuse=True)
    stats["refined"] = True
    return out, stats


def shadow_mask(samples: Any, material: BtfMaterial, sigma: float = 0.77) -> np.ndarray:
    """(S, H, W) samples the visibility pass would leave out, on the luma: darker than the
    constant term plus half the lit part of the model by more than 4 sigma."""
    flat = bool(material.flat_specular_normal)
    model = _LumaModel(np.asarray(samples.light_dirs, np.float64),
                       np.asarray(samples.view_dirs, np.float64), flat)
    p = _params(material, flat)
    y, _ = model.eval(p, False)                                       # (N, S)
    base = 255.0 * p[:, 3:4]
    vals = np.asarray(samples.values, np.float64)
    y_data = (np.einsum("c,schw->shw", _YCC[0], vals) * 255.0).reshape(len(vals), -1).T
    dark = y_data < base + 0.5 * (y - base) - 4 * sigma
    return dark.T.reshape(len(vals), samples.height, samples.width)
