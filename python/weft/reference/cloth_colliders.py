"""NumPy reference of the cloth's collider shapes (SPEC §2.2): signed distances (negative
inside) and outward normals of spheres (eq. 3.7), planes, boxes, capsules and height fields,
the shape records :class:`weft.reference.cloth.ClothReference` projects out of, and the wind
setting; plus the small array helpers both modules use. Float64, independent of weft."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Sequence, Tuple, Union

import numpy as np

ArrayLike = Union[np.ndarray, Sequence[float], float]

_EPS = 1e-12


def _vec(value: ArrayLike, n: int, name: str) -> np.ndarray:
    arr = np.asarray(value, dtype=np.float64).reshape(-1)
    if arr.shape != (n,):
        raise ValueError(f"{name} must have {n} components, got shape {np.shape(value)}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite, got {arr}")
    return arr


def _points(value: ArrayLike, name: str = "points") -> np.ndarray:
    arr = np.asarray(value, dtype=np.float64)
    if arr.ndim == 1 and arr.shape[0] == 3:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"{name} must be (M, 3), got shape {arr.shape}")
    return arr


def _normalize(v: np.ndarray) -> np.ndarray:
    length = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.where(length > _EPS, v / np.where(length > _EPS, length, 1.0), 0.0)


# --------------------------------------------------------------------------------------------
# Collider shapes: signed distance (negative inside) and outward normal
# --------------------------------------------------------------------------------------------

def sphere_distance(points: ArrayLike, center: ArrayLike, radius: float
                    ) -> Tuple[np.ndarray, np.ndarray]:
    """Sphere: ``s = |p - M| - r``, ``n = (p - M)/|p - M|`` (eq. 3.7 projects to
    ``M + (r + thickness) n``)."""
    p = _points(points)
    rel = p - _vec(center, 3, "center")
    return np.linalg.norm(rel, axis=1) - float(radius), _normalize(rel)


def plane_distance(points: ArrayLike, point: ArrayLike, normal: ArrayLike
                   ) -> Tuple[np.ndarray, np.ndarray]:
    """Plane through ``point`` with normal ``n`` (normalised): ``s = (p - point) . n``."""
    p = _points(points)
    n = _normalize(_vec(normal, 3, "normal"))
    return (p - _vec(point, 3, "point")) @ n, np.broadcast_to(n, p.shape).copy()


def box_distance(points: ArrayLike, center: ArrayLike, half_extents: ArrayLike,
                 rotation: Optional[ArrayLike] = None) -> Tuple[np.ndarray, np.ndarray]:
    """Oriented box: ``q = R^T (p - c)`` in box space (R maps box axes to world, its columns
    are the box axes), ``d = |q| - h``; outside ``s = |max(d, 0)|`` with the normal towards
    the nearest surface point, inside ``s = max_k d_k`` (< 0) with the normal of that face."""
    p = _points(points)
    c = _vec(center, 3, "center")
    h = _vec(half_extents, 3, "half_extents")
    r = np.eye(3) if rotation is None else np.asarray(rotation, dtype=np.float64).reshape(3, 3)
    q = (p - c) @ r  # = R^T (p - c) per row
    d = np.abs(q) - h
    outside = np.maximum(d, 0.0)
    out_len = np.linalg.norm(outside, axis=1)
    inner = d.max(axis=1)
    s = np.where(out_len > 0.0, out_len, inner)
    n_out = np.sign(q) * outside / np.where(out_len > 0.0, out_len, 1.0)[:, None]
    axis = np.argmax(d, axis=1)
    n_in = np.zeros_like(q)
    n_in[np.arange(len(q)), axis] = np.where(q[np.arange(len(q)), axis] >= 0.0, 1.0, -1.0)
    n_local = np.where((out_len > 0.0)[:, None], n_out, n_in)
    return s, n_local @ r.T


def capsule_distance(points: ArrayLike, a: ArrayLike, b: ArrayLike, radius: float
                     ) -> Tuple[np.ndarray, np.ndarray]:
    """Capsule around segment ab: ``s = |p - c| - r`` with c the closest point of the segment,
    ``n = (p - c)/|p - c|``."""
    p = _points(points)
    a3, b3 = _vec(a, 3, "a"), _vec(b, 3, "b")
    ab = b3 - a3
    denom = float(ab @ ab)
    t = np.clip(((p - a3) @ ab) / denom, 0.0, 1.0) if denom > 0.0 else np.zeros(len(p))
    rel = p - (a3 + t[:, None] * ab)
    return np.linalg.norm(rel, axis=1) - float(radius), _normalize(rel)


def height_field_distance(points: ArrayLike, heights: ArrayLike, origin: ArrayLike,
                          size: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
    """Height-field terrain: heights (rows, cols), rows along z, cols along x, spanning
    ``[o.x, o.x + size_x] x [o.z, o.z + size_z]`` at surface height ``H = o.y + h`` (bilinear,
    clamped at the borders). The normal is that of the bilinear surface,
    ``normalize(-dH/dx, 1, -dH/dz)``, and the distance is to its tangent plane,
    ``s = (y - H) n_y`` (exact for a planar field; the push ``(thickness - s) n`` then lands on
    ``H + thickness`` measured along the normal)."""
    p = _points(points)
    hf = np.asarray(heights, dtype=np.float64)
    if hf.ndim != 2 or hf.shape[0] < 2 or hf.shape[1] < 2:
        raise ValueError(f"heights must be (rows >= 2, cols >= 2), got {hf.shape}")
    o = _vec(origin, 3, "origin")
    sz = _vec(size, 2, "size")
    rows, cols = hf.shape
    fx = np.clip((p[:, 0] - o[0]) / sz[0], 0.0, 1.0) * (cols - 1)
    fz = np.clip((p[:, 2] - o[2]) / sz[1], 0.0, 1.0) * (rows - 1)
    c0 = np.minimum(np.floor(fx).astype(np.int64), cols - 2)
    r0 = np.minimum(np.floor(fz).astype(np.int64), rows - 2)
    tx, tz = fx - c0, fz - r0
    h00, h01 = hf[r0, c0], hf[r0, c0 + 1]
    h10, h11 = hf[r0 + 1, c0], hf[r0 + 1, c0 + 1]
    h = (1 - tz) * ((1 - tx) * h00 + tx * h01) + tz * ((1 - tx) * h10 + tx * h11)
    dhdx = ((1 - tz) * (h01 - h00) + tz * (h11 - h10)) * (cols - 1) / sz[0]
    dhdz = ((1 - tx) * (h10 - h00) + tx * (h11 - h01)) * (rows - 1) / sz[1]
    n = _normalize(np.stack([-dhdx, np.ones_like(h), -dhdz], axis=1))
    return (p[:, 1] - (o[1] + h)) * n[:, 1], n


@dataclass
class SphereShape:
    """Sphere collider (eq. 3.7)."""
    center: ArrayLike
    radius: float
    friction: float = 0.0

    def distance(self, points: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
        return sphere_distance(points, self.center, self.radius)


@dataclass
class PlaneShape:
    """Plane collider through ``point`` with outward ``normal``."""
    point: ArrayLike
    normal: ArrayLike
    friction: float = 0.0

    def distance(self, points: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
        return plane_distance(points, self.point, self.normal)


@dataclass
class BoxShape:
    """Oriented box collider (``rotation`` maps box axes to world)."""
    center: ArrayLike
    half_extents: ArrayLike
    rotation: Optional[ArrayLike] = None
    friction: float = 0.0

    def distance(self, points: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
        return box_distance(points, self.center, self.half_extents, self.rotation)


@dataclass
class CapsuleShape:
    """Capsule collider around segment ab."""
    a: ArrayLike
    b: ArrayLike
    radius: float
    friction: float = 0.0

    def distance(self, points: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
        return capsule_distance(points, self.a, self.b, self.radius)


@dataclass
class HeightFieldShape:
    """Height-field terrain collider (rows along z, cols along x)."""
    heights: ArrayLike
    origin: ArrayLike
    size: ArrayLike = (1.0, 1.0)
    friction: float = 0.0

    def distance(self, points: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
        return height_field_distance(points, self.heights, self.origin, self.size)


@dataclass
class WindSetting:
    """Global wind (eq. 3.5): direction ``r`` (normalised on use) and strength ``s``."""
    direction: ArrayLike = (1.0, 0.0, 0.0)
    strength: float = 0.0
