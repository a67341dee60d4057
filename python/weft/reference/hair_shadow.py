"""Deep opacity maps (SPEC §5.3, Yuksel & Keyser 2008): the NumPy reference the GPU passes must
reproduce.

Light: orthographic along ``direction``; light space has axes (right, up, direction) and
pixels of size ``extent / resolution`` over the square [-extent/2, extent/2]^2 around ``center``.

1. Fragments (:func:`rasterize_segments`): every strand segment is sampled at
   ``ceil(pixels spanned) + 1`` evenly spaced points (DDA), each a fragment (pixel, depth,
   alpha) - what a line rasteriser produces; a pixel keeps at most one fragment per segment.
2. Depth pass: z0 = the smallest fragment depth per pixel.
3. Layers: boundaries z0 + b_k with b_k = k d (linear) or d (2^k - 1) (log, layer k twice as
   thick as layer k-1); a fragment adds its alpha to its layer and every layer behind it;
   fragments beyond the last boundary go to the last layer. So ``opacity[k]`` = total alpha of
   the pixel's fragments with depth < z0 + b_{k+1} (all fragments for the last layer).
4. Lookup at depth z: occlusion interpolates linearly inside the layer holding z between the
   opacity at its start (that of the layer before, 0 for the first) and ``opacity[k]`` at its
   end (the last layer ends at its nominal boundary and is flat behind it); before z0 it is 0.
   Transmittance = exp(-occlusion).

:func:`exact_occlusion` is the ground truth the layers approximate: the alpha of every fragment
of the pixel nearer than z.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Tuple

import numpy as np


@dataclass
class LightGrid:
    """An orthographic light's pixel grid."""

    direction: Tuple[float, float, float] = (0.0, -1.0, 0.0)
    center: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    extent: float = 1.0
    resolution: int = 64

    def basis(self) -> np.ndarray:
        """Rows right, up, forward (unit, right-handed)."""
        f = np.asarray(self.direction, dtype=np.float64)
        f = f / np.linalg.norm(f)
        helper = np.array([0.0, 0.0, 1.0]) if abs(f[1]) > 0.9 else np.array([0.0, 1.0, 0.0])
        r = np.cross(helper, f)
        r /= np.linalg.norm(r)
        return np.stack([r, np.cross(f, r), f])

    def to_light(self, points: np.ndarray) -> np.ndarray:
        """(N,3) world -> (x pixel, y pixel, depth)."""
        local = (np.asarray(points, np.float64) - np.asarray(self.center)) @ self.basis().T
        scale = self.resolution / self.extent
        return np.stack([(local[:, 0] + self.extent / 2) * scale,
                         (local[:, 1] + self.extent / 2) * scale, local[:, 2]], axis=-1)


def rasterize_segments(points: np.ndarray, offsets: np.ndarray, alpha: np.ndarray,
                       grid: LightGrid) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Fragments of all strand segments: (pixel index, depth, alpha) arrays.
    ``alpha`` is per point; a segment's fragments take the mean of its two ends."""
    q = grid.to_light(points)
    offsets = np.asarray(offsets, dtype=np.int64)
    starts = np.concatenate([np.arange(offsets[s], offsets[s + 1] - 1)
                             for s in range(len(offsets) - 1)])
    a, b = q[starts], q[starts + 1]
    seg_alpha = 0.5 * (alpha[starts] + alpha[starts + 1])
    steps = np.ceil(np.max(np.abs(b[:, :2] - a[:, :2]), axis=1)).astype(np.int64) + 1
    seg = np.repeat(np.arange(len(starts)), steps)
    first = np.repeat(np.cumsum(steps) - steps, steps)
    k = np.arange(seg.size) - first
    t = np.where(steps[seg] > 1, k / np.maximum(steps[seg] - 1, 1), 0.0)
    pos = a[seg] + (b[seg] - a[seg]) * t[:, None]
    px, py = np.floor(pos[:, 0]).astype(np.int64), np.floor(pos[:, 1]).astype(np.int64)
    res = grid.resolution
    inside = (px >= 0) & (px < res) & (py >= 0) & (py < res)
    pixel = py * res + px
    # one fragment per (segment, pixel): keep the first sample that lands in each
    key = seg * (res * res) + pixel
    keep = inside & np.concatenate([[True], key[1:] != key[:-1]])
    return pixel[keep], pos[keep, 2], seg_alpha[seg[keep]]


def layer_bounds(d: float, layers: int, spacing: str = "linear") -> np.ndarray:
    """Offsets b_0..b_layers of the layer boundaries from z0."""
    k = np.arange(layers + 1, dtype=np.float64)
    if spacing == "linear":
        return k * d
    if spacing == "log":
        return d * (2.0 ** k - 1.0)
    raise ValueError(f"spacing must be 'linear' or 'log', got {spacing!r}")


def depth_pass(pixel: np.ndarray, depth: np.ndarray, pixels: int) -> np.ndarray:
    """z0 per pixel (+inf where no fragment)."""
    z0 = np.full(pixels, np.inf)
    np.minimum.at(z0, pixel, depth)
    return z0


def opacity_layers(pixel: np.ndarray, depth: np.ndarray, alpha: np.ndarray, z0: np.ndarray,
                   bounds: np.ndarray) -> np.ndarray:
    """(pixels, layers) accumulated opacity: each fragment counts for its layer and all behind."""
    layers = len(bounds) - 1
    rel = depth - z0[pixel]
    layer = np.clip(np.searchsorted(bounds[1:], rel, side="right"), 0, layers - 1)
    per = np.zeros((z0.size, layers))
    np.add.at(per, (pixel, layer), alpha)
    return np.cumsum(per, axis=1)


def occlusion_at(opacity: np.ndarray, z0: np.ndarray, bounds: np.ndarray, pixel: np.ndarray,
                 depth: np.ndarray) -> np.ndarray:
    """Interpolated occlusion of the opacity layers at (pixel, depth) queries."""
    layers = len(bounds) - 1
    rel = depth - z0[pixel]
    layer = np.clip(np.searchsorted(bounds[1:], rel, side="right"), 0, layers - 1)
    start = bounds[layer]
    size = bounds[layer + 1] - bounds[layer]
    t = np.clip((rel - start) / size, 0.0, 1.0)
    before = np.where(layer > 0, opacity[pixel, np.maximum(layer - 1, 0)], 0.0)
    occ = before + (opacity[pixel, layer] - before) * t
    return np.where(np.isfinite(z0[pixel]) & (rel > 0), occ, 0.0)


def exact_occlusion(pixel: np.ndarray, depth: np.ndarray, alpha: np.ndarray,
                    query_pixel: np.ndarray, query_depth: np.ndarray) -> np.ndarray:
    """Sum of the alpha of the fragments in the query's pixel strictly nearer than its depth."""
    order = np.lexsort((depth, pixel))
    p, d, a = pixel[order], depth[order], alpha[order]
    cum = np.concatenate([[0.0], np.cumsum(a)])
    lo = np.searchsorted(p, query_pixel, side="left")
    hi = np.searchsorted(p, query_pixel, side="right")
    out = np.empty(query_pixel.size)
    for i in range(query_pixel.size):  # queries are few; fragments per pixel sorted by depth
        n = np.searchsorted(d[lo[i]:hi[i]], query_depth[i], side="left")
        out[i] = cum[lo[i] + n] - cum[lo[i]]
    return out


def transmittance(occlusion: np.ndarray) -> np.ndarray:
    return np.exp(-occlusion)



def slab_scene(n_per_row: int, rows: int, thickness: float, seed: int = 0):
    """Straight strands along X filling y in [0, thickness] evenly (stratified), one set per
    light pixel row; the light looks down -Y from y = thickness."""
    rng = np.random.default_rng(seed)
    z = (np.repeat(np.arange(rows), n_per_row) + 0.5) / rows - 0.5
    y = (np.tile(np.arange(n_per_row), rows) + rng.random(rows * n_per_row)) / n_per_row * thickness
    a = np.stack([np.full_like(z, -0.49), y, z], axis=1)
    b = np.stack([np.full_like(z, 0.49), y, z], axis=1)
    points = np.stack([a, b], axis=1).reshape(-1, 3)
    offsets = np.arange(0, len(points) + 1, 2)
    grid = LightGrid(direction=(0, -1, 0), center=(0, thickness, 0), extent=1.0, resolution=rows)
    return points, offsets, grid


def slab_errors(layers: int = 3, spacing: str = "linear", rows: int = 16):
    """Mean |transmittance error| of a uniform slab: (exact vs analytic, DOM vs exact,
    DOM vs 64-layer map, 64-layer map vs analytic) for `layers` layers spaced `spacing`."""
    n, depth_extent, alpha = 40, 0.2, 0.05
    points, offsets, grid = slab_scene(n, rows, depth_extent)
    pix, dep, alp = rasterize_segments(points, offsets, np.full(len(points), alpha), grid)
    z0 = depth_pass(pix, dep, rows * rows)
    covered = np.nonzero(np.isfinite(z0))[0]
    qd = np.linspace(0.02, 0.19, 8)
    qp, qz = np.repeat(covered, qd.size), np.tile(qd, covered.size)
    exact = exact_occlusion(pix, dep, alp, qp, qz)
    k = alpha * n / depth_extent
    analytic = np.exp(-k * qz)

    def dom(count: int, kind: str) -> np.ndarray:
        d = depth_extent / count if kind == "linear" else depth_extent / (2.0 ** count - 1)
        b = layer_bounds(d, count, kind)
        return occlusion_at(opacity_layers(pix, dep, alp, z0, b), z0, b, qp, qz)

    t_exact, t_dom, t_64 = np.exp(-exact), np.exp(-dom(layers, spacing)), np.exp(-dom(64, "linear"))
    return (float(np.mean(np.abs(t_exact - analytic))), float(np.mean(np.abs(t_dom - t_exact))),
            float(np.mean(np.abs(t_dom - t_64))), float(np.mean(np.abs(t_64 - analytic))))


__all__ = ["LightGrid", "depth_pass", "exact_occlusion", "layer_bounds", "occlusion_at",
           "opacity_layers", "rasterize_segments", "slab_errors", "slab_scene", "transmittance"]
