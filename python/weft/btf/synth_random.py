"""Random ground-truth materials for synthetic BTFs (issue 12: "independent data").

The presets are five fixed materials, so fits tuned to them could pass every check and fail on a
real fabric. :func:`random_truth` draws a whole material from a seed instead: a tiling height
field made of several random components (value-noise octaves, oriented ridges, a weave, wrapped
bumps), scaled so that a random share of the surface is tilted steeply; two random albedo colours
mixed by a random pattern; a random ambient colour; a grey-ish specular map with k_s drawn in
[0.02, 0.3] and one exponent drawn log-uniformly in [5, 500]; the highlight around the fitted
normal or around n_s = (0, 0, 1) (seed eq. 4.30), drawn when not given. Every sample of the
material stays below 0.95 so that 8-bit files do not clip the truth.
"""

from __future__ import annotations

from typing import Optional, Tuple

import numpy as np

import weft
from weft.btf import synth
from weft.btf.material import BtfMaterial

K_S_RANGE = (0.02, 0.3)   # below ~0.02 the lobe is under the 0.004 noise: no exponent to recover
EXPONENT_RANGE = (5.0, 500.0)
TILT_DEG_RANGE = (15.0, 40.0)  # 90th percentile of the normals' tilt
PEAK = 0.95                # brightest possible sample (θ_l = 0, highlight)


def _value_noise(rng: np.random.Generator, size: int, cells: int) -> np.ndarray:
    """synth's tileable value noise with the cell count kept in [2, size]."""
    return synth._value_noise(rng, size, int(min(max(cells, 2), size)))


def _fbm(rng: np.random.Generator, size: int) -> np.ndarray:
    base = int(rng.integers(2, max(3, size // 6) + 1))
    octaves = int(rng.integers(2, 5))
    gain = rng.uniform(0.35, 0.65)
    return sum(_value_noise(rng, size, base * 2 ** k) * gain ** k for k in range(octaves))


def _ridges(rng: np.random.Generator, size: int) -> np.ndarray:
    """|sin|^p ridges along a random integer wave vector (so the field tiles)."""
    top = max(2, size // 6)
    k = np.zeros(2)
    while not k.any():
        k = rng.integers(-top, top + 1, size=2)
    y, x = np.mgrid[0:size, 0:size] / size
    return np.abs(np.sin(np.pi * (k[0] * x + k[1] * y) + rng.uniform(0, np.pi))) ** \
        rng.uniform(0.5, 2.0)


def _weave(rng: np.random.Generator, size: int) -> np.ndarray:
    """Plain weave: threads along x and y alternately on top."""
    k = int(rng.integers(2, max(3, size // 6) + 1))
    y, x = np.mgrid[0:size, 0:size] * (np.pi * k / size)
    su, sv = np.sin(x), np.sin(y)
    on_top = np.sign(su * sv)
    return np.maximum(np.abs(su) * (0.5 + 0.5 * on_top), np.abs(sv) * (0.5 - 0.5 * on_top))


def _bumps(rng: np.random.Generator, size: int) -> np.ndarray:
    """Gaussian bumps at random places with random radii, wrapped around the edges."""
    y, x = np.mgrid[0:size, 0:size].astype(np.float64)
    out = np.zeros((size, size))
    for _ in range(int(rng.integers(5, 41))):
        cx, cy = rng.uniform(0, size, 2)
        r = rng.uniform(1.5, max(2.0, size / 8))
        dx = np.abs(x - cx)
        dy = np.abs(y - cy)
        d2 = np.minimum(dx, size - dx) ** 2 + np.minimum(dy, size - dy) ** 2
        out += rng.uniform(0.3, 1.0) * np.exp(-d2 / (2 * r * r))
    return out


_COMPONENTS = (_fbm, _ridges, _weave, _bumps)


def _unit(a: np.ndarray) -> np.ndarray:
    return (a - a.min()) / max(float(np.ptp(a)), 1e-12)


def random_height(rng: np.random.Generator, size: int) -> np.ndarray:
    """A tiling height field (texels) of 2-3 random components, its 90th-percentile tilt drawn
    in :data:`TILT_DEG_RANGE`."""
    picks = rng.choice(len(_COMPONENTS), size=int(rng.integers(2, 4)), replace=False)
    h = sum(rng.uniform(0.3, 1.0) * _unit(_COMPONENTS[int(i)](rng, size)) for i in picks)
    h = _unit(h)
    gy, gx = np.gradient(h)
    slope = float(np.percentile(np.hypot(gx, gy), 90))
    tilt = np.radians(rng.uniform(*TILT_DEG_RANGE))
    return (h * (np.tan(tilt) / max(slope, 1e-9))).astype(np.float32)


def _normals(height: np.ndarray) -> np.ndarray:
    """Unit normals of a tiling height field: x right, y up (rows grow down), as the presets."""
    dx = (np.roll(height, -1, axis=1) - np.roll(height, 1, axis=1)) * 0.5
    dy = -(np.roll(height, -1, axis=0) - np.roll(height, 1, axis=0)) * 0.5
    n = np.stack([-dx, -dy, np.ones_like(height)], axis=-1).astype(np.float64)
    return n / np.linalg.norm(n, axis=-1, keepdims=True)


def random_truth(seed: int, size: int = 64, *, specular: bool = True,
                 flat_specular_normal: Optional[bool] = None) -> Tuple[BtfMaterial, np.ndarray]:
    """(material, height field in texels) drawn from ``seed``; the same seed gives the same
    material. ``flat_specular_normal`` None: drawn too."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise weft.InvalidArgument(f"seed must be a non-negative integer, got {seed!r}")
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or \
            not 4 <= size <= 4096:
        raise weft.InvalidArgument(f"size must be an integer in 4..4096, got {size!r}")
    size = int(size)
    rng = np.random.default_rng(np.random.SeedSequence([int(seed), 12]))
    height = random_height(rng, size)
    h01 = _unit(height.astype(np.float64))
    colours = rng.uniform(0.05, 0.7, size=(2, 3))
    mix_kind = int(rng.integers(0, 3))
    if mix_kind == 0:    # colour follows the relief (threads vs gaps)
        mix = np.clip((h01 - rng.uniform(0.3, 0.7)) * rng.uniform(3, 20) + 0.5, 0, 1)
    elif mix_kind == 1:  # an independent pattern
        mix = _unit(_fbm(rng, size)) > rng.uniform(0.35, 0.65)
    else:
        mix = _unit(_ridges(rng, size))
    mix = np.asarray(mix, np.float64)[..., None]
    albedo = colours[0] * (1 - mix) + colours[1] * mix
    albedo *= 0.85 + 0.3 * _value_noise(rng, size, max(size // 4, 2))[..., None]
    ambient = rng.uniform(0.02, 0.25, 3) * (0.8 + 0.4 * h01[..., None])
    k_s = rng.uniform(*K_S_RANGE) if specular else 0.0
    tint = rng.uniform(0.85, 1.0, 3)
    spec = k_s * tint * (0.7 + 0.3 * _value_noise(rng, size, max(size // 8, 2))[..., None])
    exponent = float(np.exp(rng.uniform(*np.log(EXPONENT_RANGE))))
    flat = bool(rng.random() < 0.5) if flat_specular_normal is None else bool(flat_specular_normal)
    # keep the brightest sample (albedo (ambient + 1) + k_s) below PEAK: 8-bit files would clip
    peak = float(np.max(albedo * (1 + ambient) + spec))
    if peak > PEAK:
        albedo *= (PEAK - float(spec.max())) / float(np.max(albedo * (1 + ambient)))
    material = BtfMaterial(normal=_normals(height), albedo=albedo, ambient=ambient,
                           specular=spec if specular else None, exponent=exponent,
                           flat_specular_normal=flat, clamp_diffuse=True)
    return material, height
