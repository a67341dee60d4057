"""Weighted blended order-independent transparency (SPEC §5.4, McGuire & Bavoil 2013) and the
exact depth-sorted "over" compositing it approximates, in NumPy (float64).

Fragments carry premultiplied colour ``C_i = alpha_i c_i``, coverage ``alpha_i`` and depth;
``z`` is the view-space depth (positive metres), ``z_ndc`` the depth-buffer value in [0, 1].
Composite (eq. 25 of the seed)::

    C_f = sum(C_i w_i) / sum(alpha_i w_i) * (1 - prod(1 - alpha_i)) + C_0 prod(1 - alpha_i)
"""

from __future__ import annotations

from typing import Callable, Dict

import numpy as np


def weight_eq7(z: np.ndarray, alpha: np.ndarray, z_ndc: np.ndarray = None) -> np.ndarray:
    z = np.abs(z)
    return alpha * np.clip(10.0 / (1e-5 + (z / 5.0) ** 2 + (z / 200.0) ** 6), 1e-2, 3e3)


def weight_eq8(z: np.ndarray, alpha: np.ndarray, z_ndc: np.ndarray = None) -> np.ndarray:
    z = np.abs(z)
    return alpha * np.clip(10.0 / (1e-5 + (z / 10.0) ** 3 + (z / 200.0) ** 6), 1e-2, 3e3)


def weight_eq9(z: np.ndarray, alpha: np.ndarray, z_ndc: np.ndarray = None) -> np.ndarray:
    z = np.abs(z)
    return alpha * np.clip(0.03 / (1e-5 + (z / 200.0) ** 4), 1e-2, 3e3)


def weight_eq10(z: np.ndarray, alpha: np.ndarray, z_ndc: np.ndarray) -> np.ndarray:
    return alpha * np.maximum(1e-2, 3e3 * (1.0 - z_ndc) ** 3)


WEIGHTS: Dict[str, Callable[..., np.ndarray]] = {
    "eq7": weight_eq7, "eq8": weight_eq8, "eq9": weight_eq9, "eq10": weight_eq10,
    # the renderer's names of the same weights (Renderer.hair_oit_weight)
    "near_quadratic": weight_eq7, "near_cubic": weight_eq8, "far_quartic": weight_eq9,
    "ndc_cubic": weight_eq10}


def wboit_composite(color: np.ndarray, alpha: np.ndarray, z: np.ndarray, z_ndc: np.ndarray,
                    background: np.ndarray, weight: str = "eq7") -> np.ndarray:
    """Composite of fragment stacks: color (..., n, 3) straight (not premultiplied) colour,
    alpha/z/z_ndc (..., n), background (..., 3). Returns (..., 3)."""
    w = WEIGHTS[weight](z, alpha, z_ndc)
    pre = color * alpha[..., None]
    accum_rgb = np.sum(pre * w[..., None], axis=-2)
    accum_a = np.sum(alpha * w, axis=-1)
    reveal = np.prod(1.0 - alpha, axis=-1)
    avg = accum_rgb / np.maximum(accum_a, 1e-30)[..., None]
    return avg * (1.0 - reveal)[..., None] + background * reveal[..., None]


def sorted_over(color: np.ndarray, alpha: np.ndarray, z: np.ndarray,
                background: np.ndarray) -> np.ndarray:
    """Exact back-to-front "over" compositing of the same stacks."""
    order = np.argsort(-np.abs(z), axis=-1)  # farthest first
    c = np.take_along_axis(color, order[..., None], axis=-2)
    a = np.take_along_axis(alpha, order, axis=-1)
    out = np.array(background, dtype=np.float64, copy=True)
    for i in range(a.shape[-1]):
        out = a[..., i, None] * c[..., i, :] + (1.0 - a[..., i, None]) * out
    return out



def random_stack_errors(stacks: int = 2000, layers: int = 8, seed: int = 0):
    """Mean and max |WBOIT - sorted over| per weight on random stacks (8 layers, alpha in
    [0.05, 0.6], z in [0.5, 20] m, z_ndc = z / 25)."""
    rng = np.random.default_rng(seed)
    c = rng.random((stacks, layers, 3))
    a = rng.uniform(0.05, 0.6, (stacks, layers))
    z = rng.uniform(0.5, 20.0, (stacks, layers))
    bg = rng.random((stacks, 3))
    exact = sorted_over(c, a, z, bg)
    out = {}
    for name in WEIGHTS:
        got = wboit_composite(c, a, z, z / 25.0, bg, name)
        out[name] = (float(np.mean(np.abs(got - exact))), float(np.max(np.abs(got - exact))))
    return out


__all__ = ["WEIGHTS", "random_stack_errors", "sorted_over", "wboit_composite", "weight_eq7",
           "weight_eq8", "weight_eq9", "weight_eq10"]
