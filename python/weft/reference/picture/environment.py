"""Environments for the picture references: a synthetic HDR sky (NumPy, no files) as a weft cube
map, and weft's cube map as the equirectangular bitmap Mitsuba's ``envmap`` reads.

Mitsuba's envmap (measured by test_picture_reference.py with ``Emitter.eval``): the radiance
arriving from world direction d is the bitmap at ``u = atan2(d.x, -d.z) / 2 pi`` (mod 1),
``v = acos(d.y) / pi`` (rows from the zenith down), so with Y up in both, the equirect is filled
in world space and its ``to_world`` is the identity. Each bitmap pixel is the mean of the cube
sampled as a GPU samples it (seamless bilinear, weft.reference.ibl_shading's convention; the
texture is the input both renderers are given, the light transport is what is compared) in
``supersample``^2 directions spread over the pixel, so a small bright sun keeps its power.
Nearest texels drew the horizon's texel steps into the truth, which weft's filtered background
does not have (FLIP 0.01-0.02 of every sky scene's whole image was that).
"""

from __future__ import annotations

from typing import Optional, Sequence

import numpy as np

from weft.reference import ibl as ref_ibl
from weft.reference.ibl_shading import sample_face_bilinear

#: The sun of the reference skies: direction towards it (unit), angular radius (radians) and
#: the radiance of its disc, so bright that it dominates the sky's light (as the real one).
SUN_DIRECTION = tuple(np.array([0.55, 0.62, 0.36]) / np.linalg.norm([0.55, 0.62, 0.36]))
SUN_RADIUS = np.radians(2.5)
SUN_RADIANCE = 250.0


def equirect_directions(width: int, height: int, supersample: int = 1) -> np.ndarray:
    """World directions of an equirect bitmap's sample points, (H, W, ss*ss, 3): Mitsuba's
    mapping u = atan2(x, -z) / 2 pi, v = acos(y) / pi inverted."""
    s = int(supersample)
    offs = (np.arange(s) + 0.5) / s
    u = ((np.arange(width)[:, None] + offs[None, :]) / width).reshape(-1)      # W*s
    v = ((np.arange(height)[:, None] + offs[None, :]) / height).reshape(-1)    # H*s
    phi = 2.0 * np.pi * u
    theta = np.pi * v
    st, ct = np.sin(theta)[:, None], np.cos(theta)[:, None]
    d = np.stack([st * np.sin(phi)[None, :], np.broadcast_to(ct, (len(v), len(u))),
                  -st * np.cos(phi)[None, :]], axis=-1)  # (H*s, W*s, 3)
    d = d.reshape(height, s, width, s, 3).transpose(0, 2, 1, 3, 4)
    return d.reshape(height, width, s * s, 3)


def cube_to_equirect(faces: np.ndarray, width: Optional[int] = None,
                     supersample: int = 2) -> np.ndarray:
    """Equirect bitmap (H, W, 3) float32 of cube faces (6, S, S, 3) for Mitsuba's envmap; W
    defaults to 16 S (a quarter cube texel per pixel at the horizon: the bitmap and Mitsuba's
    bilinear lookup of it add no visible blur of their own; at 4 S they softened the horizon's
    kink by 3-4% against weft's bilinear cube), H = W / 2."""
    faces = np.asarray(faces, np.float64)
    width = int(width or 16 * faces.shape[1])
    height = width // 2
    d = equirect_directions(width, height, supersample)
    vals = sample_face_bilinear(faces, d.reshape(-1, 3)).reshape(height, width, -1, 3)
    return vals.mean(axis=2).astype(np.float32)


def sky_radiance(d: np.ndarray, sun: bool = False, sun_direction: Sequence[float] = SUN_DIRECTION,
                 sun_radius: float = SUN_RADIUS, sun_radiance: float = SUN_RADIANCE) -> np.ndarray:
    """A synthetic clear sky, radiance at unit directions (N, 3) -> (N, 3): blue zenith
    brightening to a hazy horizon, a brighter circumsolar region, a dim brown ground below the
    horizon; with ``sun`` a disc of ``sun_radiance`` (sharp shadows, the GGX prefilter's test)."""
    d = np.asarray(d, np.float64)
    y = d[:, 1]
    s = np.asarray(sun_direction, np.float64)
    s = s / np.linalg.norm(s)
    up = np.clip(y, 0.0, 1.0)[:, None]
    zenith = np.array([0.25, 0.45, 0.95])
    horizon = np.array([0.85, 0.9, 1.0])
    t = (1.0 - up) ** 3
    sky = zenith * (1.0 - t) + horizon * t
    glow = np.exp(6.0 * ((d @ s) - 1.0))[:, None] * np.array([1.2, 1.0, 0.7])
    sky = sky + glow
    ground = np.array([0.22, 0.18, 0.14]) * (0.6 + 0.4 * np.exp(8.0 * np.minimum(y, 0.0)))[:, None]
    # a soft 2-degree blend across the horizon keeps the cube texels there smooth
    w = np.clip(0.5 + y / (2.0 * np.radians(2.0)), 0.0, 1.0)[:, None]
    out = sky * w + ground * (1.0 - w)
    if sun:
        out = out + ((d @ s) >= np.cos(sun_radius))[:, None] * sun_radiance * np.array(
            [1.0, 0.95, 0.85])
    return out


def sky_faces(size: int = 64, sun: bool = False, supersample: int = 4) -> np.ndarray:
    """The reference sky as cube faces (6, S, S, 3) float32 (each texel the mean of
    ``supersample``^2 directions in it)."""
    n = int(size) * int(supersample)
    d = ref_ibl.texel_directions(n).reshape(-1, 3)
    vals = sky_radiance(d, sun=sun).reshape(6, size, supersample, size, supersample, 3)
    return vals.mean(axis=(2, 4)).astype(np.float32)
