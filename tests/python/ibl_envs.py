"""Analytic test environments for the IBL tests: radiance as a function of direction, put on a
cube map at the reference texel directions (optionally supersampled)."""

from __future__ import annotations

from typing import Callable, Sequence

import numpy as np
from weft.reference import ibl as ref

Env = Callable[[np.ndarray], np.ndarray]  # (N, 3) unit directions -> (N, 3) radiance


def to_faces(env: Env, size: int, supersample: int = 1) -> np.ndarray:
    """Cube faces (6, S, S, 3) float32: the mean of env over ss x ss points per texel."""
    n = size * supersample
    d = ref.texel_directions(n).reshape(-1, 3)
    vals = env(d).reshape(6, size, supersample, size, supersample, 3)
    return vals.mean(axis=(2, 4)).astype(np.float32)


def constant(level: Sequence[float] = (0.7, 0.5, 0.3)) -> Env:
    return lambda d: np.broadcast_to(np.asarray(level, np.float64), d.shape).copy()


def sky_gradient() -> Env:
    """Bright blue-white zenith, darker horizon, brown ground."""
    def env(d: np.ndarray) -> np.ndarray:
        up = np.clip(d[:, 1], -1, 1)[:, None]
        sky = np.array([0.4, 0.6, 1.0]) * (0.5 + 0.8 * np.maximum(up, 0)) + 0.2 * d[:, :1]
        ground = np.array([0.25, 0.2, 0.15]) * (1.0 + 0.3 * d[:, 2:3])
        return np.where(up > 0, sky, ground) * 0.5 + 0.5 * (sky * ground) ** 0.5 + 0.05

    return env


def sun_disc(direction: Sequence[float], radius: float, radiance: float,
             sky: Env, colour: Sequence[float] = (1.0, 0.95, 0.85)) -> Env:
    s = np.asarray(direction, np.float64)
    s /= np.linalg.norm(s)
    cos_r = np.cos(radius)

    def env(d: np.ndarray) -> np.ndarray:
        inside = (d @ s) >= cos_r
        return sky(d) + inside[:, None] * radiance * np.asarray(colour)

    return env


def sun_power(radius: float, radiance: float, colour: Sequence[float] = (1.0, 0.95, 0.85)):
    """Integrated radiance of a disc of angular radius `radius`: L * 2 pi (1 - cos r)."""
    return radiance * 2.0 * np.pi * (1.0 - np.cos(radius)) * np.asarray(colour)


def random_smooth(seed: int, lobes: int = 5) -> Env:
    """Sum of a few broad exponential lobes (positive, smooth)."""
    rng = np.random.default_rng(seed)
    axes = rng.normal(size=(lobes, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    sharp = rng.uniform(0.5, 3.0, lobes)
    colours = rng.uniform(0.1, 1.0, (lobes, 3))

    def env(d: np.ndarray) -> np.ndarray:
        w = np.exp(sharp[None, :] * ((d @ axes.T) - 1.0))
        return 0.05 + w @ colours

    return env


def seam_violations(faces: np.ndarray, factor: float = 3.0, floor: float = 1e-4) -> int:
    """Counts edge texel pairs (a on one face, b its neighbour across the edge) with
    |a - b| > factor x the local gradient + floor x the mean, where the local gradient is the
    largest step between the next texels into either face (a -> a1 -> a2, b -> b1)."""
    faces = np.asarray(faces, np.float64)
    s = faces.shape[1]
    lum = faces @ np.array([0.2126, 0.7152, 0.0722])
    scale = floor * max(float(np.mean(np.abs(lum))), 1e-12)
    bad = 0
    for f in range(6):
        for (di, dj, along) in ((1, 0, "col"), (-1, 0, "col"), (0, 1, "row"), (0, -1, "row")):
            for k in range(s):
                i = (s - 1 if di > 0 else 0) if along == "col" else k
                j = k if along == "col" else (s - 1 if dj > 0 else 0)
                a = lum[f, j, i]
                a1 = lum[f, j - dj, i - di] if s > 1 else a
                a2 = lum[f, j - 2 * dj, i - 2 * di] if s > 2 else a1
                b, b1 = (_across(lum, f, i, j, di, dj, step) for step in (1, 2))
                grad = max(abs(a - a1), abs(a1 - a2), abs(b - b1))
                if abs(a - b) > factor * grad + scale:
                    bad += 1
    return bad


def _across(lum: np.ndarray, f: int, i: int, j: int, di: int, dj: int, step: int) -> float:
    """The texel `step` texels across the edge next to edge texel (i, j) of face f, at the same
    position along the edge (adjacent faces' edge texels line up)."""
    s = lum.shape[1]
    u = 2.0 * (i + 0.5) / s - 1.0 if di == 0 else float(di) * (1.0 + 1e-6)
    v = 2.0 * (j + 0.5) / s - 1.0 if dj == 0 else float(dj) * (1.0 + 1e-6)
    ax = ref.FACE_AXES[f]
    face, uu, vv = ref.direction_to_face((ax[0] + u * ax[1] + v * ax[2])[None, :])
    ii = int(np.clip(np.floor((uu[0] + 1) * 0.5 * s), 0, s - 1))
    jj = int(np.clip(np.floor((vv[0] + 1) * 0.5 * s), 0, s - 1))
    # step further into the neighbour: away from whichever of its coordinates is on the edge
    if abs(abs(uu[0]) - 1.0) < abs(abs(vv[0]) - 1.0):
        ii -= int(np.sign(uu[0])) * (step - 1)
    else:
        jj -= int(np.sign(vv[0])) * (step - 1)
    return float(lum[face[0], jj, ii])


def mirror_ball_directions(size: int) -> np.ndarray:
    """World direction seen at each pixel of a 360-degree mirror ball looking down -Z (row 0 at
    the top, y up): normal N on the ball, reflected eye ray R = 2 (N.A) N - A, A = (0, 0, 1)."""
    c = 2.0 * (np.arange(size) + 0.5) / size - 1.0
    x, y = np.meshgrid(c, -c, indexing="xy")
    z = np.sqrt(np.maximum(1.0 - x * x - y * y, 0.0))
    n = np.stack([x, y, z], -1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    return 2.0 * n[..., 2:3] * n - np.array([0.0, 0.0, 1.0])

