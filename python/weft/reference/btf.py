"""NumPy references for the BTF linear fit (SPEC §3.2, eq. 4.22), used as test oracles and as
the benchmark's "what a user would write" peer.

Per texel the unknowns are x = (n_x, n_y, n_z, a_r, a_g, a_b) and every sample s, channel c gives
the equation t_c (l_s . n) + t_c a_c = p_sc.
"""

from __future__ import annotations

import numpy as np


def design_matrix(lights: np.ndarray, texture: np.ndarray) -> np.ndarray:
    """The (3 S, 6) matrix of one texel: rows (t_c l_s, t_c e_c) ordered sample-major."""
    lights = np.asarray(lights, np.float64)
    t = np.asarray(texture, np.float64)
    s = lights.shape[0]
    a = np.zeros((s, 3, 6))
    for c in range(3):
        a[:, c, :3] = t[c] * lights
        a[:, c, 3 + c] = t[c]
    return a.reshape(3 * s, 6)


def lstsq_texels(values: np.ndarray, lights: np.ndarray, texture: np.ndarray) -> np.ndarray:
    """float64 ``np.linalg.lstsq`` per texel. values (S, 3, H, W), texture (H, W, 3);
    returns (H, W, 6) = (n, a)."""
    values = np.asarray(values, np.float64)
    s, _, h, w = values.shape
    out = np.zeros((h, w, 6))
    for y in range(h):
        for x in range(w):
            a = design_matrix(lights, texture[y, x])
            b = values[:, :, y, x].reshape(3 * s)
            out[y, x] = np.linalg.lstsq(a, b, rcond=None)[0]
    return out


def batched_normal_equations(values: np.ndarray, lights: np.ndarray) -> np.ndarray:
    """The straightforward batched NumPy fit: T = mean, per-texel design matrices, AᵀA and Aᵀb
    by einsum, ``np.linalg.solve`` over all texels. Returns (H, W, 6) = (n, a)."""
    values = np.asarray(values, np.float32)
    s, _, h, w = values.shape
    p = values.reshape(s, 3, h * w).transpose(2, 0, 1)          # (N, S, 3)
    t = p.mean(axis=1)                                           # (N, 3)
    lights = np.asarray(lights, np.float32)
    a = np.zeros((h * w, s, 3, 6), np.float32)
    a[..., :3] = t[:, None, :, None] * lights[None, :, None, :]
    for c in range(3):
        a[:, :, c, 3 + c] = t[:, None, c]
    a = a.reshape(h * w, 3 * s, 6)
    ata = np.einsum("nki,nkj->nij", a, a)
    atb = np.einsum("nki,nk->ni", a, p.reshape(h * w, 3 * s))
    x = np.linalg.solve(ata.astype(np.float64), atb.astype(np.float64)[..., None])[..., 0]
    return x.reshape(h, w, 6)
