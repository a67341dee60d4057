"""Lights from an environment (SPEC §4.5): threshold + connected components (C++), and median
cut (Debevec 2005, "A median cut algorithm for light probe sampling") on the equirectangular
image of the cube map."""

from __future__ import annotations

from dataclasses import dataclass
from typing import List, Tuple

import numpy as np

from weft._core import CubeMap, InvalidArgument, cube_to_equirect
from weft._core import extract_lights as _extract_lights

_LUMA = np.array([0.2126, 0.7152, 0.0722])


@dataclass(frozen=True)
class EnvLight:
    """A light found in an environment."""

    direction: Tuple[float, float, float]  #: unit vector towards the light (world)
    colour: Tuple[float, float, float]     #: radiance integrated over its solid angle (RGB)
    solid_angle: float  #: sr (threshold method: power / peak radiance; median cut: the region's)
    texels: int = 0                        #: cube texels (threshold method) or pixels (median cut)

    @property
    def power(self) -> float:
        """Luminance of ``colour``."""
        return float(np.dot(_LUMA, self.colour))


def extract_lights(radiance, downsample: int = 32, threshold: float = 0.0,
                   relative_threshold: float = 8.0, max_lights: int = 16) -> List[EnvLight]:
    """Bright regions: luminance max-filtered down to ``downsample``^2 per face, thresholded
    (``threshold``, or ``relative_threshold`` x the mean luminance when ``threshold`` <= 0),
    grouped into connected components across cube edges; strongest first."""
    found = _extract_lights(radiance, downsample=downsample, threshold=threshold,
                            relative_threshold=relative_threshold, max_lights=max_lights)
    return [EnvLight(tuple(d["direction"]), tuple(d["colour"]), float(d["solid_angle"]),
                     int(d["texels"])) for d in found]


def split_lights(radiance, downsample: int = 32, threshold: float = 0.0,
                 relative_threshold: float = 8.0,
                 max_lights: int = 16) -> Tuple[List[EnvLight], CubeMap]:
    """The lights of :func:`extract_lights` and the environment without them: their texels are
    filled (push-pull) from the surrounding sky. SH9 of the residual plus the lights as
    directional lights represents a sun-dominated HDR environment far better than SH9 alone."""
    from weft._core import fill_unseen

    cube = radiance if isinstance(radiance, CubeMap) else CubeMap(np.asarray(radiance, np.float32))
    found, labels = _extract_lights(cube, downsample=downsample, threshold=threshold,
                                    relative_threshold=relative_threshold,
                                    max_lights=max_lights, labels=True)
    lights = [EnvLight(tuple(d["direction"]), tuple(d["colour"]), float(d["solid_angle"]),
                       int(d["texels"])) for d in found]
    sky = labels < 0
    residual = fill_unseen(cube, sky) if not sky.all() else cube.copy()
    return lights, residual


def median_cut(radiance, count: int = 16, width: int = 0) -> List[EnvLight]:
    """Median cut: the equirectangular image (``width`` x ``width / 2``, default 8 x cube size) is
    split ``log2(count)`` times (single pixels stay whole), each region along its longer side
    (measured on the sphere) where its solid-angle weighted luminance is halved; each region
    becomes a light at its luminance centroid carrying the region's integrated radiance.
    ``count`` must be a power of two."""
    if count < 1 or count > 4096 or count & (count - 1):
        raise InvalidArgument("median cut light count must be a power of two in [1, 4096], "
                              f"got {count}")
    cube = radiance if isinstance(radiance, CubeMap) else CubeMap(np.asarray(radiance, np.float32))
    width = width or 8 * cube.size
    if width < 2:
        raise InvalidArgument("equirectangular width must be >= 2")
    height = max(1, width // 2)
    img = np.asarray(cube_to_equirect(cube, width, height), np.float64)
    theta = np.pi * (np.arange(height) + 0.5) / height
    phi = 2.0 * np.pi * ((np.arange(width) + 0.5) / width - 0.5)
    omega = (2.0 * np.pi / width) * (np.pi / height) * np.sin(theta)[:, None] * np.ones(width)
    energy = (img @ _LUMA) * omega
    st, ct = np.sin(theta)[:, None], np.cos(theta)[:, None]
    dirs = np.stack([st * np.sin(phi), ct * np.ones(width), -st * np.cos(phi)], axis=-1)
    regions = [(0, height, 0, width)]
    for _ in range(count.bit_length() - 1):
        regions = [part for region in regions for part in _split(energy, theta, *region)]
    lights = []
    for (r0, r1, c0, c1) in regions:
        e = energy[r0:r1, c0:c1]
        w = omega[r0:r1, c0:c1]
        colour = (img[r0:r1, c0:c1] * w[..., None]).sum(axis=(0, 1))
        centroid = (dirs[r0:r1, c0:c1] * (e if e.sum() > 0 else w)[..., None]).sum(axis=(0, 1))
        n = np.linalg.norm(centroid)
        d = centroid / n if n > 0 else dirs[(r0 + r1) // 2, (c0 + c1) // 2]
        lights.append(EnvLight(tuple(float(v) for v in d), tuple(float(v) for v in colour),
                               float(w.sum()), int((r1 - r0) * (c1 - c0))))
    lights.sort(key=lambda l: -l.power)
    return lights


def _split(energy: np.ndarray, theta: np.ndarray, r0: int, r1: int, c0: int, c1: int):
    """Splits a region in two along its longer side at the energy median."""
    h, w = r1 - r0, c1 - c0
    if h * w < 2:
        return [(r0, r1, c0, c1)]  # a single pixel stays whole (fewer lights than asked)
    rows, cols = energy.shape
    # angular size: a column spans 2 pi / W x sin(theta), a row pi / H
    width_on_sphere = w * np.sin(theta[(r0 + r1) // 2]) * (2.0 * rows / cols)
    horizontal_cut = (h >= 2 and (width_on_sphere <= h or w < 2))
    e = energy[r0:r1, c0:c1]
    profile = e.sum(axis=1) if horizontal_cut else e.sum(axis=0)
    cum = np.cumsum(profile)
    k = int(np.searchsorted(cum, 0.5 * cum[-1])) + 1 if cum[-1] > 0 else len(profile) // 2
    k = min(max(k, 1), len(profile) - 1)
    if horizontal_cut:
        return [(r0, r0 + k, c0, c1), (r0 + k, r1, c0, c1)]
    return [(r0, r1, c0, c0 + k), (r0, r1, c0 + k, c1)]
