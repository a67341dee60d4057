"""The cloth's grid in NumPy (part of :mod:`weft.reference.cloth`, re-exported there): rest
positions, the 12(+4)-neighbour constraint pattern, vertex normals (eq. 3.6), triangles, hole
masks from images and strain. Nothing here calls weft's compiled code."""

from __future__ import annotations

from typing import Any, List, Optional, Tuple

import numpy as np

from weft.reference.cloth_colliders import ArrayLike, _normalize, _vec

#: Constraint family codes, as ``weft.Cloth.constraints()["family"]`` reports them.
STRETCH, SHEAR, BEND = 0, 1, 2


def grid_positions(nx: int, ny: int, size: ArrayLike = (1.0, 1.0),
                   origin: ArrayLike = (-0.5, 1.0, -0.5), axis_u: ArrayLike = (1.0, 0.0, 0.0),
                   axis_v: ArrayLike = (0.0, 0.0, 1.0)) -> np.ndarray:
    """Initial (= rest) positions (nx*ny, 3), index ``j * nx + i`` (SPEC §2.1)::

        x(i, j) = origin + u size_u i/(nx-1) + v size_v j/(ny-1)   (a term is 0 for nx or ny 1)

    with ``u``, ``v`` the normalised axes."""
    s = _vec(size, 2, "size")
    o = _vec(origin, 3, "origin")
    u = _normalize(_vec(axis_u, 3, "axis_u"))
    v = _normalize(_vec(axis_v, 3, "axis_v"))
    fu = np.arange(nx, dtype=np.float64) / (nx - 1) if nx > 1 else np.zeros(1)
    fv = np.arange(ny, dtype=np.float64) / (ny - 1) if ny > 1 else np.zeros(1)
    x = (o[None, None, :] + (s[0] * fu)[None, :, None] * u[None, None, :]
         + (s[1] * fv)[:, None, None] * v[None, None, :])
    return x.reshape(nx * ny, 3)


def constraint_pattern(nx: int, ny: int, bend_distance: int = 2, extra_axial: bool = False
                       ) -> List[Tuple[int, np.ndarray, np.ndarray]]:
    """The neighbour pattern (SPEC §2.1, seed fig. 3.4/3.8) as conflict-free batches.

    Offsets (dx, dy) in this order: (1,0), (0,1) stretch; (1,1), (1,-1) shear; (k,k), (k,-k)
    bend; with ``extra_axial`` also (k,0), (0,k) bend. Each offset gives two batches, parity 0
    then 1, where ``parity = (i // |dx|) % 2`` (or ``(j // |dy|) % 2`` when dx = 0); a
    constraint joins particle (i, j) to (i+dx, j+dy). No two constraints of a batch share a
    particle. Returns ``[(family, a, b), ...]`` (empty batches left out), a and b int64 arrays
    in row-major order of (j, i).
    """
    k = int(bend_distance)
    offsets = [(1, 0, STRETCH), (0, 1, STRETCH), (1, 1, SHEAR), (1, -1, SHEAR),
               (k, k, BEND), (k, -k, BEND)]
    if extra_axial:
        offsets += [(k, 0, BEND), (0, k, BEND)]
    jj, ii = np.meshgrid(np.arange(ny), np.arange(nx), indexing="ij")
    ii, jj = ii.reshape(-1), jj.reshape(-1)
    batches: List[Tuple[int, np.ndarray, np.ndarray]] = []
    for dx, dy, fam in offsets:
        i2, j2 = ii + dx, jj + dy
        inside = (i2 >= 0) & (i2 < nx) & (j2 >= 0) & (j2 < ny)
        colour = (ii // abs(dx)) % 2 if dx != 0 else (jj // abs(dy)) % 2
        for parity in (0, 1):
            sel = inside & (colour == parity)
            if not np.any(sel):
                continue
            a = (jj[sel] * nx + ii[sel]).astype(np.int64)
            b = (j2[sel] * nx + i2[sel]).astype(np.int64)
            batches.append((fam, a, b))
    return batches


def grid_normals(x: np.ndarray, nx: int, ny: int,
                 previous: Optional[np.ndarray] = None) -> np.ndarray:
    """Per-particle normals (eq. 3.6 on the grid): ``normalize((x[i,j+1] - x[i,j-1]) x
    (x[i+1,j] - x[i-1,j]))`` with one-sided differences at the borders. Where the cross
    product vanishes the normal is taken from ``previous`` (zero without it). +Y for the
    default horizontal cloth (u = +X, v = +Z)."""
    g = np.asarray(x, dtype=np.float64).reshape(ny, nx, 3)

    def diff(axis: int) -> np.ndarray:
        n = g.shape[axis]
        if n < 2:
            return np.zeros_like(g)
        take = lambda s: np.take(g, s, axis=axis)  # noqa: E731
        d = np.empty_like(g)
        sl = [slice(None)] * 3
        sl[axis] = slice(1, n - 1)
        d[tuple(sl)] = take(np.arange(2, n)) - take(np.arange(0, n - 2))
        sl[axis] = slice(0, 1)
        d[tuple(sl)] = take([1]) - take([0])
        sl[axis] = slice(n - 1, n)
        d[tuple(sl)] = take([n - 1]) - take([n - 2])
        return d

    du = diff(1)  # along i
    dv = diff(0)  # along j
    c = np.cross(dv, du).reshape(nx * ny, 3)
    length = np.linalg.norm(c, axis=1)
    ok = length > 1e-20
    out = np.zeros_like(c) if previous is None else np.array(previous, dtype=np.float64)
    out[ok] = c[ok] / length[ok, None]
    return out


def grid_triangles(nx: int, ny: int, edge_active: Optional[Any] = None,
                   hole: Optional[np.ndarray] = None) -> np.ndarray:
    """Triangle indices (M, 3) uint32 of the mesh output (SPEC §2.2 holes and tears): quad
    (i, j) gives (p00, p11, p10) and (p00, p01, p11); a triangle is kept only if no vertex is a
    hole and ``edge_active(a, b)`` (a callable on index arrays, default all True) holds for its
    three edges."""
    if nx < 2 or ny < 2:
        return np.zeros((0, 3), dtype=np.uint32)
    jj, ii = np.meshgrid(np.arange(ny - 1), np.arange(nx - 1), indexing="ij")
    p00 = (jj * nx + ii).reshape(-1)
    p10, p01, p11 = p00 + 1, p00 + nx, p00 + nx + 1
    tris = np.stack([np.stack([p00, p11, p10], 1), np.stack([p00, p01, p11], 1)], 1)
    tris = tris.reshape(-1, 3)
    keep = np.ones(len(tris), dtype=bool)
    if hole is not None:
        keep &= ~np.asarray(hole, dtype=bool).reshape(-1)[tris].any(axis=1)
    if edge_active is not None:
        for e0, e1 in ((0, 1), (1, 2), (2, 0)):
            keep &= np.asarray(edge_active(tris[:, e0], tris[:, e1]), dtype=bool)
    return tris[keep].astype(np.uint32)


def hole_mask_from_image(image: np.ndarray, nx: int, ny: int) -> np.ndarray:
    """Hole mask (ny, nx) from a uint8 image (H, W) or (H, W, C) of any size (SPEC §2.2: a
    mask texture): particle (i, j) samples the nearest texel at its UV, column
    ``min(floor(u W), W - 1)``, row ``min(floor(v H), H - 1)`` (row 0 at v = 0), and is a hole
    where that texel (its alpha with 4 channels, else its first channel) is below 128."""
    img = np.asarray(image)
    if img.ndim == 2:
        img = img[:, :, None]
    if img.ndim != 3 or img.shape[0] < 1 or img.shape[1] < 1 or not 1 <= img.shape[2] <= 4:
        raise ValueError(f"hole image must be (H, W) or (H, W, C <= 4), got {np.shape(image)}")
    h, w, c = img.shape
    u = np.arange(nx) / (nx - 1) if nx > 1 else np.zeros(1)
    v = np.arange(ny) / (ny - 1) if ny > 1 else np.zeros(1)
    cols = np.minimum((u * w).astype(np.int64), w - 1)
    rows = np.minimum((v * h).astype(np.int64), h - 1)
    channel = 3 if c == 4 else 0
    return img[rows[:, None], cols[None, :], channel] < 128


def strain(positions: np.ndarray, a: np.ndarray, b: np.ndarray, rest: np.ndarray,
           active: Optional[np.ndarray] = None) -> Tuple[float, float]:
    """Mean and max relative strain ``|len - rest| / rest`` over the active constraints
    (SPEC §2.6 (a)); (0, 0) when none is active."""
    x = np.asarray(positions, dtype=np.float64)
    a, b = np.asarray(a), np.asarray(b)
    rest = np.asarray(rest, dtype=np.float64)
    if active is not None:
        sel = np.asarray(active, dtype=bool)
        a, b, rest = a[sel], b[sel], rest[sel]
    if len(a) == 0:
        return 0.0, 0.0
    s = np.abs(np.linalg.norm(x[b] - x[a], axis=1) - rest) / rest
    return float(s.mean()), float(s.max())


def constraints_on_surface(nx: int, tris: np.ndarray, a: np.ndarray, b: np.ndarray
                           ) -> np.ndarray:
    """Whether each constraint (a, b) runs on the surface of the triangles ``tris`` (M, 3)
    (issue 17: a constraint lives while the faces it runs through are there; nothing spans a
    hole or a tear). Geometric, in grid coordinates (i, j): points along the segment (the ends,
    the lattice points and the midpoints between them) must each lie in some closed triangle.
    """
    a = np.asarray(a, dtype=np.int64)
    b = np.asarray(b, dtype=np.int64)
    tris = np.asarray(tris, dtype=np.int64).reshape(-1, 3)
    out = np.zeros(len(a), dtype=bool)
    if len(tris) == 0:
        return out
    corner = np.stack([tris % nx, tris // nx], axis=-1).astype(np.float64)  # (M, 3, 2)
    # a triangle covers the points of its unit quad: index triangles by their quad
    quad = np.minimum.reduce(corner, axis=1).astype(np.int64)  # (M, 2) lower-left corner
    by_quad: dict = {}
    for m, (qi, qj) in enumerate(quad.tolist()):
        by_quad.setdefault((qi, qj), []).append(m)

    def covered(p: np.ndarray) -> bool:
        for qi in (int(np.floor(p[0])) - 1, int(np.floor(p[0]))):
            for qj in (int(np.floor(p[1])) - 1, int(np.floor(p[1]))):
                for m in by_quad.get((qi, qj), ()):
                    t = corner[m]
                    d = [(t[(e + 1) % 3][0] - t[e][0]) * (p[1] - t[e][1])
                         - (t[(e + 1) % 3][1] - t[e][1]) * (p[0] - t[e][0]) for e in range(3)]
                    if min(d) >= -1e-9 or max(d) <= 1e-9:
                        return True
        return False

    for c, (pa, pb) in enumerate(zip(a.tolist(), b.tolist())):
        p0 = np.array([pa % nx, pa // nx], dtype=np.float64)
        p1 = np.array([pb % nx, pb // nx], dtype=np.float64)
        steps = 2 * int(np.max(np.abs(p1 - p0)))
        out[c] = all(covered(p0 + (p1 - p0) * s / steps) for s in range(steps + 1))
    return out
