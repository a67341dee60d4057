"""Issue 17 item 7: self-collision that does not tunnel, and that respects collider margins.

A cloth folded in two (a 1 cm crease, the layers 2 cm apart) is dropped 20 cm onto a ground
plane at 2 substeps. When the bottom layer stops on the ground the top one still moves ~1.2 T
per substep, and a repulsion that only looks at the positions after the substep pushed it on
through (85% of the top layer ended under the bottom, ~450 crossing triangles; none at 8
substeps). The truths here share nothing with the solver: which layer is above the other at
each point, and a NumPy triangle-triangle intersection count over the rendered mesh.
"""

from __future__ import annotations

from typing import Tuple

import numpy as np
import pytest
import weft
from weft.reference.cloth import ClothReference, PlaneShape

DT = 1.0 / 60.0
NX, NY, SIZE = 32, 64, (0.5, 1.0)
THICKNESS = 0.005  # the collider default
T = 0.9 * min(SIZE[0] / (NX - 1), SIZE[1] / (NY - 1))  # the default self thickness


def folded(nx: int, ny: int, size: Tuple[float, float], y0: float, radius: float
           ) -> Tuple[np.ndarray, np.ndarray]:
    """The grid folded in two across v: the rows up to the middle lie flat at height y0, a
    semicircular crease of the given radius turns the rest back over them, 2 radius higher.
    Returns positions and a mask of the top layer (the rows past the crease's apex)."""
    s = size[1] / (ny - 1)
    flat = (size[1] - np.pi * radius) / 2
    t = np.arange(ny) * s
    z, y = np.empty(ny), np.empty(ny)
    bottom, top = t < flat, t >= flat + np.pi * radius
    crease = ~bottom & ~top
    z[bottom], y[bottom] = t[bottom], y0
    angle = (t[crease] - flat) / radius
    z[crease] = flat + radius * np.sin(angle)
    y[crease] = y0 + radius * (1 - np.cos(angle))
    z[top], y[top] = flat - (t[top] - flat - np.pi * radius), y0 + 2 * radius
    x = np.zeros((ny, nx, 3))
    x[:, :, 0] = (np.linspace(0, size[0], nx) - size[0] / 2)[None, :]
    x[:, :, 1] = y[:, None]
    x[:, :, 2] = (z - flat / 2)[:, None]
    return x.reshape(-1, 3), np.repeat(t >= flat + np.pi * radius / 2, nx)


def segments_cross_triangles(p0, p1, a, b, c) -> np.ndarray:
    """Whether segment p0-p1 crosses triangle abc, row by row (Moller-Trumbore)."""
    d, e1, e2 = p1 - p0, b - a, c - a
    h = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, h)
    ok = np.abs(det) > 1e-14
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = p0 - a
    u = np.einsum("ij,ij->i", s, h) * inv
    q = np.cross(s, e1)
    v = np.einsum("ij,ij->i", d, q) * inv
    t = np.einsum("ij,ij->i", e2, q) * inv
    return ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= 0) & (t <= 1)


def self_intersections(x: np.ndarray, tris: np.ndarray) -> int:
    """Pairs of triangles sharing no vertex that intersect (an edge of one crosses the other)."""
    tris = np.asarray(tris, dtype=np.int64)
    v = x[tris]
    lo, hi = v.min(axis=1), v.max(axis=1)
    pairs = []
    for i0 in range(0, len(tris), 512):  # bounding boxes first, in blocks
        overlap = np.all((lo[i0:i0 + 512, None] <= hi[None]) & (hi[i0:i0 + 512, None] >= lo[None]),
                         axis=-1)
        i, j = np.nonzero(overlap)
        i = i + i0
        pairs.append(np.stack([i[j > i], j[j > i]], 1))
    pr = np.concatenate(pairs)
    shared = (tris[pr[:, 0]][:, :, None] == tris[pr[:, 1]][:, None, :]).any(axis=(1, 2))
    pr = pr[~shared]
    a, b = v[pr[:, 0]], v[pr[:, 1]]
    hit = np.zeros(len(pr), dtype=bool)
    for k in range(3):
        hit |= segments_cross_triangles(a[:, k], a[:, (k + 1) % 3], b[:, 0], b[:, 1], b[:, 2])
        hit |= segments_cross_triangles(b[:, k], b[:, (k + 1) % 3], a[:, 0], a[:, 1], a[:, 2])
    return int(hit.sum())


def below_bottom(x: np.ndarray, top: np.ndarray) -> float:
    """Fraction of the top layer's particles not above the bottom layer particle nearest to
    them in plan (x, z); on the ground the two layers should lie about T apart."""
    xt, xb = x[top], x[~top]
    d2 = ((xt[:, None, [0, 2]] - xb[None, :, [0, 2]]) ** 2).sum(axis=-1)
    return float(np.mean(xt[:, 1] <= xb[d2.argmin(axis=1), 1]))


def test_self_intersection_counter_sees_crossing_sheets() -> None:
    """The counter's own check: two unit squares (2 triangles each) crossing at right angles
    intersect; moved apart, or sharing a vertex only, they do not."""
    x = np.array([[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1],
                  [0.5, -0.5, 0.2], [0.5, 0.5, 0.2], [0.5, 0.5, 0.8], [0.5, -0.5, 0.8]], float)
    tris = np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]])
    assert self_intersections(x, tris) >= 2
    apart = x.copy()
    apart[4:, 0] += 2.0
    assert self_intersections(apart, tris) == 0
    assert self_intersections(x, np.array([[0, 1, 2], [2, 4, 5]])) == 0  # shared vertex only


def drop_fold(substeps: int, iterations: int, collider=None, steps: int = 60):
    cloth = weft.Cloth(NX, NY, size=SIZE, origin=(-0.25, 1.0, 0.0), self_collision=True,
                       substeps=substeps, iterations=iterations, threads=1)
    x, top = folded(NX, NY, SIZE, 0.2 + THICKNESS, 0.01)
    cloth.set_positions(x)
    cloth.add_collider(collider or weft.Collider.plane((0, 0, 0), (0, 1, 0)))
    lowest = np.inf
    for _ in range(steps):
        cloth.step(DT)
        lowest = min(lowest, float(np.min(np.asarray(cloth.positions)[:, 1])))
    return cloth, top, lowest


@pytest.mark.parametrize("iterations", [1, 2])
def test_fold_dropped_20cm_at_2_substeps_does_not_tunnel(iterations: int) -> None:
    cloth, top, _ = drop_fold(2, iterations)
    x = np.asarray(cloth.positions, dtype=np.float64)
    assert np.all(np.isfinite(x))
    assert below_bottom(x, top) == 0.0
    assert self_intersections(x, cloth.mesh()["indices"]) == 0
    # and the layers rest apart: the top layer lies on the bottom one, within T of it (its
    # particles settle into the gaps between the bottom's, >= T from each) but well off it
    flat = top & (np.arange(NX * NY) // NX > NY // 2 + 4)
    gap = np.median(x[flat, 1]) - THICKNESS
    assert 0.4 * T < gap <= 1.01 * T


def test_self_collision_respects_the_ground_margin() -> None:
    """Self-collision used to push the bottom layer into the plane's thickness (down to
    1.5 mm of 5 mm): after every step now every particle is at least the thickness above."""
    _, _, lowest = drop_fold(2, 1)
    assert lowest >= THICKNESS * (1 - 1e-4)


def test_self_collision_respects_a_sphere_margin() -> None:
    centre, radius = np.array([0.0, -0.25, 0.0]), 0.3
    cloth, _, _ = drop_fold(2, 1, weft.Collider.sphere(tuple(centre), radius), steps=40)
    d = np.linalg.norm(np.asarray(cloth.positions, dtype=np.float64) - centre, axis=1)
    assert d.min() >= radius + THICKNESS * (1 - 1e-3)


def test_numpy_reference_runs_the_same_self_collision() -> None:
    """The NumPy cloth (float64, brute force over all pairs) follows weft's self-collision on
    a small fold dropped onto the ground, through the contact."""
    nx, ny, size = 6, 12, (0.25, 0.5)
    x, _ = folded(nx, ny, size, 0.05 + THICKNESS, 0.02)
    kw = dict(size=size, origin=(-0.125, 1.0, 0.0), self_collision=True, substeps=2)
    cloth = weft.Cloth(nx, ny, threads=1, **kw)
    ref = ClothReference(nx, ny, **kw)
    cloth.set_positions(x)
    ref.set_positions(x)
    cloth.add_collider(weft.Collider.plane((0, 0, 0), (0, 1, 0)))
    ref.add_collider(PlaneShape((0, 0, 0), (0, 1, 0)))
    for _ in range(12):
        cloth.step(DT)
        ref.step(DT)
    got = np.asarray(cloth.positions, dtype=np.float64)
    assert got[:, 1].min() == pytest.approx(THICKNESS)  # it has landed
    np.testing.assert_allclose(got, ref.positions, atol=2e-4)
