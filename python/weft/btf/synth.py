"""Synthetic BTFs with known ground truth (SPEC §3.1), written in the Bonn layout.

A preset builds procedural maps in NumPy (albedo pattern, height field -> normals, ambient,
specular map and exponent); the compiled renderer evaluates the truth model for every light
(and view) direction, optionally with cast shadows from the height field; sensor noise is added
here, gamma and JPEG quantisation happen when the files are written.
Presets are named after the seed's materials: wool (knitted loops), polyacrylic (fine plain
weave), corduroy (ridges, cast shadows), upholstery (coarse coloured weave), granite (noise).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, Optional, Sequence, Tuple

import numpy as np

import weft
from weft import _core
from weft.btf.material import BtfMaterial


@dataclass(frozen=True)
class Preset:
    pattern: str
    colours: Tuple[Tuple[float, float, float], Tuple[float, float, float]]
    height: float            # height amplitude in texels
    period: float            # pattern period in texels at 256 x 256
    ambient: float
    specular: float
    exponent: float
    shadows: bool


PRESETS: Dict[str, Preset] = {
    "wool": Preset("knit", ((0.62, 0.52, 0.40), (0.45, 0.36, 0.27)), 1.6, 16, 0.12, 0.05, 87,
                   False),
    "polyacrylic": Preset("weave", ((0.30, 0.34, 0.55), (0.20, 0.22, 0.40)), 0.8, 8, 0.10, 0.06,
                          54, False),
    "corduroy": Preset("ridges", ((0.55, 0.35, 0.20), (0.35, 0.20, 0.10)), 3.0, 12, 0.10, 0.05,
                       74, True),
    "upholstery": Preset("weave", ((0.55, 0.15, 0.15), (0.20, 0.35, 0.25)), 1.5, 20, 0.15, 0.10,
                         51, False),
    "granite": Preset("noise", ((0.60, 0.58, 0.55), (0.20, 0.20, 0.22)), 0.6, 32, 0.12, 0.15,
                      128, False),
}


@dataclass
class SynthTruth:
    """Ground truth of a synthetic BTF: the material and its height field (texels)."""

    material: BtfMaterial
    height: np.ndarray
    shadows: bool
    noise: float

    def __repr__(self) -> str:
        return f"<weft.btf.SynthTruth {self.material!r} shadows={self.shadows} noise={self.noise}>"


def _value_noise(rng: np.random.Generator, size: int, cells: int) -> np.ndarray:
    """Tileable value noise in [0, 1]: a random cells x cells grid, smooth-step interpolated."""
    grid = rng.random((cells, cells))
    t = np.arange(size) * cells / size
    i0 = np.floor(t).astype(int) % cells
    i1 = (i0 + 1) % cells
    f = t - np.floor(t)
    f = f * f * (3 - 2 * f)
    rows = grid[i0] * (1 - f)[:, None] + grid[i1] * f[:, None]
    return rows[:, i0] * (1 - f)[None, :] + rows[:, i1] * f[None, :]


def _pattern(p: Preset, size: int, rng: np.random.Generator) -> Tuple[np.ndarray, np.ndarray]:
    """(mix in [0, 1] between the two colours, height in [0, 1]) of a preset."""
    period = max(p.period * size / 256.0, 4.0)
    y, x = np.mgrid[0:size, 0:size].astype(np.float64)
    u, v = 2 * np.pi * x / period, 2 * np.pi * y / period
    if p.pattern == "weave":  # plain weave: warp and weft threads alternate over and under
        warp = np.abs(np.sin(u / 2)) * (0.5 + 0.5 * np.sign(np.sin(v / 2) * np.sin(u / 2)))
        weft_ = np.abs(np.sin(v / 2)) * (0.5 - 0.5 * np.sign(np.sin(v / 2) * np.sin(u / 2)))
        height = np.maximum(warp, weft_)
        mix = (warp > weft_).astype(np.float64)
    elif p.pattern == "knit":  # rows of V-shaped loops
        loop = np.abs(np.sin(u / 2 + 0.8 * np.abs(np.sin(v / 2))))
        height = loop * (0.6 + 0.4 * np.abs(np.sin(v / 2)))
        mix = 1.0 - loop
    elif p.pattern == "ridges":  # corduroy wales along y
        height = np.abs(np.sin(u / 2)) ** 0.7
        mix = 1.0 - height
    else:  # granite-like multi-octave noise
        cells = max(size // int(period), 2)
        height = sum(_value_noise(rng, size, cells * 2 ** k) / 2 ** k for k in range(4)) / 1.875
        speck = _value_noise(rng, size, max(size // 4, 2))
        mix = (speck > 0.6).astype(np.float64) * 0.8 + 0.2 * height
    fibre = _value_noise(rng, size, max(size // 4, 2))
    height = height + 0.15 * fibre
    height = (height - height.min()) / max(np.ptp(height), 1e-9)
    return np.clip(mix, 0, 1), height


def _normals(height: np.ndarray) -> np.ndarray:
    """Unit normals of a tiling height field (texel units): x right, y up (rows grow down)."""
    dx = (np.roll(height, -1, axis=1) - np.roll(height, 1, axis=1)) * 0.5
    dy = -(np.roll(height, -1, axis=0) - np.roll(height, 1, axis=0)) * 0.5
    n = np.stack([-dx, -dy, np.ones_like(height)], axis=-1)
    return n / np.linalg.norm(n, axis=-1, keepdims=True)


def truth_for(preset: str, size: int = 256, seed: int = 0, *, specular: Optional[float] = None,
              shadows: Optional[bool] = None, height_scale: float = 1.0) -> Tuple[BtfMaterial,
                                                                                    np.ndarray,
                                                                                    bool]:
    """The ground-truth material, height field and shadow flag of a preset."""
    if preset not in PRESETS:
        raise weft.InvalidArgument(f"unknown BTF preset {preset!r}; known: {', '.join(PRESETS)}")
    if not (4 <= int(size) <= 4096):
        raise weft.InvalidArgument(f"size must be 4..4096, got {size}")
    if not (np.isfinite(height_scale) and 0 <= height_scale <= 100):
        raise weft.InvalidArgument("height_scale must be in [0, 100]")
    p = PRESETS[preset]
    rng = np.random.default_rng(seed)
    mix, h01 = _pattern(p, int(size), rng)
    height = (h01 * p.height * height_scale * size / 256.0).astype(np.float32)
    c0, c1 = np.array(p.colours[0]), np.array(p.colours[1])
    albedo = c0[None, None, :] * (1 - mix[..., None]) + c1[None, None, :] * mix[..., None]
    albedo *= 0.9 + 0.2 * _value_noise(rng, int(size), max(int(size) // 8, 2))[..., None]
    ambient = np.full(albedo.shape, p.ambient) * (0.8 + 0.4 * h01[..., None])
    k = p.specular if specular is None else float(specular)
    spec = (k * (0.5 + 0.5 * h01))[..., None] * np.ones(3)
    material = BtfMaterial(normal=_normals(height), albedo=albedo, ambient=ambient,
                           specular=spec if k > 0 else None, exponent=p.exponent,
                           flat_specular_normal=False, clamp_diffuse=True)
    return material, height, p.shadows if shadows is None else bool(shadows)


def view_angles(views: int) -> np.ndarray:
    """The first ``views`` of the 81 standard directions as (θ_v, φ_v) degrees."""
    dirs = _core.btf_standard_directions()
    if not 1 <= int(views) <= len(dirs):
        raise weft.InvalidArgument(f"views must be 1..{len(dirs)}, got {views}")
    return dirs[: int(views)]


def sample_angles(views: Sequence[Sequence[float]]) -> np.ndarray:
    """(S, 4) angles: every standard light direction for each view."""
    lights = _core.btf_standard_directions()
    rows = [(tl, pl, tv, pv) for tv, pv in views for tl, pl in lights]
    return np.asarray(rows, dtype=np.float32)


def render_truth(material: BtfMaterial, height: np.ndarray, *, shadows: bool, views: int = 1,
                 noise: float = 0.0, noise_seed: int = 1) -> "weft.BtfSamples":
    """Float samples of ``material`` for ``views`` view directions x 81 lights (cast shadows
    from ``height`` when ``shadows``), with Gaussian noise of std ``noise``."""
    if not (np.isfinite(noise) and 0 <= noise <= 1):
        raise weft.InvalidArgument(f"noise must be in [0, 1], got {noise}")
    angles = sample_angles(view_angles(views))
    samples = _core.btf_render(material.core_maps(), angles, height if shadows else None, True)
    if noise > 0:
        values = samples.values
        values += np.random.default_rng(noise_seed).normal(0.0, noise, values.shape).astype(
            np.float32)
        samples = _core.BtfSamples(values, angles)
    return samples


def synthesize(preset: str, size: int = 256, *, views: int = 1, noise: float = 0.0,
               seed: int = 0, shadows: Optional[bool] = None, specular: Optional[float] = None,
               height_scale: float = 1.0,
               material: Optional[BtfMaterial] = None) -> Tuple["weft.BtfSamples", SynthTruth]:
    """Renders a preset (or a given ``material`` with the preset's height field) to float
    samples for ``views`` view directions x 81 lights, with Gaussian noise of std ``noise``.
    ``preset`` "random" is :func:`synthesize_random` with this ``seed``."""
    if preset == "random":
        if material is not None or height_scale != 1.0:
            raise weft.InvalidArgument("the random preset takes no material or height_scale")
        return synthesize_random(seed, size, views=views, noise=noise,
                                 specular=specular is None or specular > 0,
                                 shadows=bool(shadows))
    if not (np.isfinite(noise) and 0 <= noise <= 1):
        raise weft.InvalidArgument(f"noise must be in [0, 1], got {noise}")
    truth_material, height, cast = truth_for(preset, size, seed, specular=specular,
                                             shadows=shadows, height_scale=height_scale)
    if material is not None:
        truth_material = material
    samples = render_truth(truth_material, height, shadows=cast, views=views, noise=noise,
                           noise_seed=seed + 1)
    return samples, SynthTruth(truth_material, height, cast, float(noise))


def synthesize_random(seed: int, size: int = 64, *, specular: bool = True, shadows: bool = False,
                      noise: float = 0.004, flat_specular_normal: Optional[bool] = None,
                      views: int = 1) -> Tuple["weft.BtfSamples", SynthTruth]:
    """A material drawn at random from ``seed`` (:func:`weft.btf.synth_random.random_truth`),
    rendered like a preset: independent data for checking the fits without tuning to presets."""
    from weft.btf.synth_random import random_truth

    material, height = random_truth(seed, size, specular=specular,
                                    flat_specular_normal=flat_specular_normal)
    samples = render_truth(material, height, shadows=bool(shadows), views=views, noise=noise,
                           noise_seed=np.random.SeedSequence([int(seed), 1]).generate_state(1)[0])
    return samples, SynthTruth(material, height, bool(shadows), float(noise))


def write(path: str, samples: "weft.BtfSamples", *, fmt: str = "jpg", quality: int = 95,
          zip: bool = False, gamma: str = "raw", prefix: str = "") -> None:
    """Writes samples in the Bonn layout (values clipped to [0, 1], 8 bits)."""
    _core.btf_write(path, samples, fmt, int(quality), bool(zip), gamma, prefix)

