#!/usr/bin/env python3
"""A two-point (Le Cam) lower bound on the mean normal error that any estimator makes from
JPEG q90 BTF files, for a grey diffuse material (issue 12's JPEG target; BENCHMARKS.md, btf).

    python scripts/btf_jpeg_bound.py [--seed 4] [--size 64] [--kappa 5] [--beta 0.06]

The material: random seed SEED's normals, luma albedo and luma ambient, made grey (R = G = B),
so that its chroma planes are constant and the same for every perturbation. With
g = 255 rho_Y n per texel, two materials M+ and M- = g +- dg are built, block by block, by a
linear program: maximise the normals' separation subject to
  - every luma DCT coefficient of every sample (81 lights) staying inside the quantisation cell of
    the unperturbed material, at least KAPPA sigma from its edges (sigma = 0.8: the sensor noise
    and the 8-bit rounding of one coefficient);
  - no texel changing which lights it faces (|dg.l| < |g.l| where g.l is small), so that the
    coefficients are linear in dg;
  - |dg| <= BETA |g| per component.
Coupling both materials' files through the same coefficient errors, their cells differ only where
an error crosses a cell edge that lies between the two noise-free values, so the total variation
between the two files' distributions is at most TV = sum P(crossing). For any estimator,
max over M+- of E[mean angle error] >= D / 2 (1 - TV), D the mean angle between the normals of M+
and M- (the angle is a metric). The script also encodes both materials as PNG and JPEG q90 and
fits them with weft's chosen Blinn-Phong fit, and measures how often the encoder's luma
coefficients leave the cell of their noise-free value (the error model the bound rests on).
Needs SciPy (linprog, HiGHS); a 64 x 64 material takes a few minutes.
"""

from __future__ import annotations

import argparse
import tempfile

import numpy as np
from scipy.optimize import linprog
from scipy.special import ndtr
from weft import btf
from weft.btf import BtfMaterial, synth
from weft.btf import fit as btf_fit
from weft.btf import jpeg_cells as jc

SIGMA = 0.8


def grey_material(g: np.ndarray, amb_y: np.ndarray) -> BtfMaterial:
    r = np.linalg.norm(g, axis=-1) / 255.0
    return BtfMaterial(normal=(g / (255.0 * r[..., None])).astype(np.float32),
                       albedo=np.repeat(r[..., None], 3, -1).astype(np.float32),
                       ambient=np.repeat((amb_y / r)[..., None], 3, -1).astype(np.float32),
                       clamp_diffuse=True)


def luma_dct(g: np.ndarray, amb_y: np.ndarray, lights: np.ndarray) -> np.ndarray:
    """Noise-free luma DCT coefficients (S, by, bx, 64) of the diffuse material g."""
    basis = np.kron(jc.dct_matrix(), jc.dct_matrix())
    y = np.maximum(np.einsum("hwc,sc->shw", g, lights), 0) + 255.0 * amb_y[None] - 128.0
    return jc._blocks(y) @ basis.T


def rendered_dct(material: BtfMaterial) -> np.ndarray:
    """The luma DCT coefficients of what the encoder is given without noise: weft's render of
    the material, clipped to [0, 1] and scaled to 8 bits (as btf.write does before rounding)."""
    clean = synth.render_truth(material, np.zeros(material.normal.shape[:2], np.float32),
                               shadows=False)
    values = np.clip(np.asarray(clean.values, np.float64), 0.0, 1.0) * 255.0
    y = np.einsum("c,schw->shw", jc._YCC[0], values) - 128.0
    return jc._blocks(y) @ np.kron(jc.dct_matrix(), jc.dct_matrix()).T


def crossing(fa: np.ndarray, fb: np.ndarray, q: np.ndarray) -> np.ndarray:
    """P(a cell edge lies between fa + e and fb + e), e ~ N(0, SIGMA)."""
    lo, hi = np.minimum(fa, fb), np.maximum(fa, fb)
    base, total = np.floor(lo / q - 0.5) - 6, np.zeros(fa.shape)
    for j in range(14):
        edge = (base + j + 0.5) * q
        total += np.abs(ndtr((edge - lo) / SIGMA) - ndtr((edge - hi) / SIGMA))
    return total


def perturbation(g: np.ndarray, f: np.ndarray, q: np.ndarray, lights: np.ndarray, kappa: float,
                 beta: float, rng: np.random.Generator) -> np.ndarray:
    """dg (H, W, 3) from one linear program per 8 x 8 block (see the module docstring)."""
    size, s = g.shape[0], len(lights)
    basis = np.kron(jc.dct_matrix(), jc.dct_matrix())
    margin = q / 2 - np.abs(f - np.round(f / q) * q)
    allow = np.maximum(margin - kappa * SIGMA, 0.0)                  # (S, by, bx, 64)
    gb = jc._blocks(np.moveaxis(g, -1, 0))                          # (3, by, bx, 64)
    dg = np.zeros((size // 8, size // 8, 64, 3))
    for a in range(size // 8):
        for b in range(size // 8):
            gx = gb[:, a, b, :].T                                   # (64, 3)
            gl = gx @ lights.T                                      # (64, S)
            lit = (gl > 0).T.astype(float)                          # (S, 64)
            rows = np.einsum("kx,sx,sc->skxc", basis, lit, lights).reshape(s * 64, 192)
            limit = allow[:, a, b, :].reshape(-1)
            used = np.abs(rows).sum(1) > 1e-12
            rows, limit = rows[used], limit[used]
            gn = np.linalg.norm(gx, axis=1)
            xi, si = np.nonzero(np.abs(gl) < 3 * beta * gn[:, None])
            keep = np.zeros((len(xi), 192))
            for c in range(3):
                keep[np.arange(len(xi)), 3 * xi + c] = lights[si, c]
            rows = np.vstack([rows, keep])
            limit = np.concatenate([limit, 0.9 * np.abs(gl[xi, si])])
            d = rng.normal(size=(64, 3))
            d -= (d * gx).sum(1, keepdims=True) * gx / gn[:, None] ** 2  # across g: the normal
            d /= np.linalg.norm(d, axis=1, keepdims=True)
            box = np.repeat(beta * gn, 3)
            res = linprog(-(d / gn[:, None]).reshape(-1), A_ub=np.vstack([rows, -rows]),
                          b_ub=np.concatenate([limit, limit]), bounds=list(zip(-box, box)),
                          method="highs")
            if res.status == 0:
                dg[a, b] = res.x.reshape(64, 3)
    return dg.reshape(size // 8, size // 8, 8, 8, 3).transpose(0, 2, 1, 3, 4).reshape(
        size, size, 3)


def fit_error(material: BtfMaterial, fmt: str) -> float:
    samples = synth.render_truth(material, np.zeros(material.normal.shape[:2], np.float32),
                                 shadows=False, noise=0.004, noise_seed=7)
    with tempfile.TemporaryDirectory() as tmp:
        btf.write(tmp, samples, fmt=fmt, quality=90)
        data = btf.load(tmp)
    linear = btf.fit_linear(data)
    seed = btf.fit_specular(data, linear, False).material
    fit = btf.fit_blinn_phong(data, seed, "builtin", luminance_normals=fmt == "jpg")
    return btf_fit.normal_stats(fit.material.normal, material.normal)["mean_deg"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seed", type=int, default=4)
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--kappa", type=float, default=5.0)
    parser.add_argument("--beta", type=float, default=0.06)
    args = parser.parse_args()
    samples, truth = synth.synthesize_random(args.seed, args.size, specular=False, noise=0.004)
    m = truth.material
    albedo = np.asarray(m.albedo, np.float64)
    rho, amb_y = albedo @ jc._YCC[0], (albedo * np.asarray(m.ambient)) @ jc._YCC[0]
    g = 255.0 * rho[..., None] * np.asarray(m.normal, np.float64)
    grey = grey_material(g, amb_y)
    lights = np.asarray(samples.light_dirs, np.float64)
    with tempfile.TemporaryDirectory() as tmp:
        btf.write(tmp, synth.render_truth(grey, np.zeros(g.shape[:2], np.float32),
                                          shadows=False, noise=0.004, noise_seed=3),
                  fmt="jpg", quality=90)
        cells = jc.luma_cells(btf.load(tmp, jpeg_cells=True))
    q = cells["quant"]
    f = luma_dct(g, amb_y, lights)
    rendered = rendered_dct(grey)
    print(f"analytic luma model vs the render: max |dF| {np.abs(f - rendered).max():.2e}")
    margin = q / 2 - np.abs(rendered - np.round(rendered / q) * q)
    left = cells["coef"] != np.round(rendered / q)
    for k in (3, 4, 5):
        sel = margin >= k * SIGMA
        print(f"error model: {int(left[sel].sum())} of {int(sel.sum())} luma coefficients with a "
              f"margin >= {k} sigma left the cell of their noise-free value")
    dg = perturbation(g, f, q, lights, args.kappa, args.beta, np.random.default_rng(1))
    plus, minus = g + dg, g - dg
    tv = float(crossing(rendered_dct(grey_material(plus, amb_y)),
                        rendered_dct(grey_material(minus, amb_y)), q).sum())
    n_p, n_m = (x / np.linalg.norm(x, axis=-1, keepdims=True) for x in (plus, minus))
    angle = np.degrees(np.arccos(np.clip((n_p * n_m).sum(-1), -1.0, 1.0)))
    print(f"seed {args.seed} {args.size}^2 grey, kappa {args.kappa}, beta {args.beta}: D = "
          f"{angle.mean():.3f} deg mean (p95 {np.percentile(angle, 95):.2f}), TV <= {tv:.2e}, "
          f"bound {angle.mean() / 2 * (1 - tv):.3f} deg mean normal error; n_z >= "
          f"{min(n_p[..., 2].min(), n_m[..., 2].min()):.3f}")
    for name, gg in (("M", g), ("M+", plus), ("M-", minus)):
        mat = grey_material(gg, amb_y)
        print(f"chosen Blinn-Phong fit on {name}: PNG {fit_error(mat, 'png'):.3f} deg, "
              f"JPEG q90 {fit_error(mat, 'jpg'):.3f} deg mean")


if __name__ == "__main__":
    main()
