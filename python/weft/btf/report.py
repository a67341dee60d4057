"""Figures and the Markdown report of a BTF fit (SPEC §3.4): difference images, per-pixel polar
plots (seed fig. 4.16), a histogram of per-sample errors and the seed's tables 4.1-4.3 for any
dataset. Figures are rasterised with NumPy and written through weft.save_png, so no plotting
package is needed.
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Sequence, Tuple

import numpy as np

import weft

POLAR_SIZE = 129


def to_u8(img: np.ndarray) -> np.ndarray:
    return np.clip(np.rint(np.asarray(img) * 255.0), 0, 255).astype(np.uint8)


def difference_image(measured: np.ndarray, recon: np.ndarray, gain: float = 4.0) -> np.ndarray:
    """|measured - recon| x gain on neutral grey's scale, (H, W, 3) uint8; inputs (3, H, W)."""
    return to_u8(np.abs(measured - recon).transpose(1, 2, 0) * gain)


def polar_plot(values: np.ndarray, angles: np.ndarray, size: int = POLAR_SIZE) -> np.ndarray:
    """A disk image of one texel's colour over light directions: radius = θ_l (edge 90°),
    angle = φ_l; each pixel takes the nearest sample. ``values`` (S, 3), ``angles`` (S, 2)."""
    y, x = np.mgrid[0:size, 0:size].astype(np.float64)
    cx = (size - 1) / 2.0
    u, v = (x - cx) / cx, (cx - y) / cx
    r = np.hypot(u, v)
    theta = np.radians(np.minimum(r, 1.0) * 90.0)
    phi = np.arctan2(v, u)
    d = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], -1)
    t, p = np.radians(angles[:, 0]), np.radians(angles[:, 1])
    dirs = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], -1)
    nearest = np.argmax(d.reshape(-1, 3) @ dirs.T, axis=1).reshape(size, size)
    img = values[nearest]
    img[(r > np.radians(82.5) / np.radians(90.0))] = 0.5
    return to_u8(img)


def histogram_image(errors: np.ndarray, bins: int = 20, height: int = 100) -> Tuple[np.ndarray,
                                                                                  List[Any]]:
    """A bar chart (uint8 image) of per-sample deviations (%) and its (low, high, count) bins."""
    counts, edges = np.histogram(errors, bins=bins)
    width = 8
    img = np.full((height, bins * width, 3), 255, np.uint8)
    top = max(int(counts.max()), 1)
    for i, c in enumerate(counts):
        h = int(round(c / top * (height - 2)))
        img[height - h:, i * width + 1:(i + 1) * width - 1] = (60, 90, 160)
    rows = [(float(edges[i]), float(edges[i + 1]), int(counts[i])) for i in range(bins)]
    return img, rows


def seed_tables(results: Dict[str, Dict[str, Any]]) -> str:
    """The seed's tables 4.1-4.3 for this dataset: deviation (%) per θ_l group and in total for
    each model, with the specular exponent where there is one."""
    names = list(results)
    groups = list(next(iter(results.values()))["deviation"]["groups"])
    header = ["θ_l group"] + names
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for g in groups:
        cells = [f"{results[n]['deviation']['groups'][g]:.4f}" for n in names]
        lines.append(f"| {g}° | " + " | ".join(cells) + " |")
    lines.append("| **total** | " + " | ".join(
        f"**{results[n]['deviation']['total']:.4f}**" for n in names) + " |")
    lines.append("| exponent n | " + " | ".join(
        str(results[n].get("exponent", "–")) for n in names) + " |")
    return "\n".join(lines)


def write_figures(out_dir: str, samples: Any, name: str, recon: np.ndarray,
                  texels: Sequence[Tuple[int, int]]) -> Dict[str, List[str]]:
    """Difference images of the first sample of every θ_l group and polar plots
    (measurement | reconstruction) of the given (x, y) texels, frontal view samples."""
    os.makedirs(out_dir, exist_ok=True)
    angles = np.asarray(samples.angles)
    values = samples.values
    files: Dict[str, List[str]] = {"difference": [], "polar": []}
    for t in np.unique(angles[:, 0]):
        s = int(np.flatnonzero(angles[:, 0] == t)[0])
        path = os.path.join(out_dir, f"{name}_diff_tl{int(t):03d}.png")
        weft.save_png(path, difference_image(values[s], recon[s]))
        files["difference"].append(os.path.basename(path))
    frontal = (angles[:, 2] == angles[0, 2]) & (angles[:, 3] == angles[0, 3])
    for x, y in texels:
        meas = values[frontal][:, :, y, x]
        rec = recon[frontal][:, :, y, x]
        scale = max(float(meas.max()), 1e-6)
        pair = np.concatenate([polar_plot(meas / scale, angles[frontal][:, :2]),
                               np.full((POLAR_SIZE, 4, 3), 255, np.uint8),
                               polar_plot(rec / scale, angles[frontal][:, :2])], axis=1)
        path = os.path.join(out_dir, f"{name}_polar_{x}_{y}.png")
        weft.save_png(path, pair)
        files["polar"].append(os.path.basename(path))
    return files
