"""NumPy reference ("oracle") for weft's IBL tools, float64, written from the equations and never
calling weft.

- Cube-map convention (Vulkan spec, "Cube Map Face Selection"): the major axis picks the face;
  face coordinates (sc, tc) divided by |major| give u, v in [-1, 1]; texel (row j, column i) has
  u = 2 (i + 0.5) / S - 1, v = 2 (j + 0.5) / S - 1.
- Texel solid angles by midpoint quadrature of dA / (1 + u^2 + v^2)^(3/2) (not the closed form).
- SH9 with constants written as square roots (Ramamoorthi & Hanrahan 2001), irradiance
  E(n) = sum A_l L_lm Y_lm(n) with A = (pi, 2 pi / 3, pi / 4), and E(n) = integral of
  L max(0, n.w) dw by brute force.
- Sphere-map lookup (SPEC §4.2), equirectangular lookup, ray-sphere visibility and the
  visibility-weighted irradiance of a ground point, the split-sum DFG by plain quadrature.
"""

from __future__ import annotations

from typing import Tuple

import numpy as np

#: (major axis, s axis, t axis) per face +X, -X, +Y, -Y, +Z, -Z: dir = ma + u s + v t.
FACE_AXES = np.array([
    [[1, 0, 0], [0, 0, -1], [0, -1, 0]],
    [[-1, 0, 0], [0, 0, 1], [0, -1, 0]],
    [[0, 1, 0], [1, 0, 0], [0, 0, 1]],
    [[0, -1, 0], [1, 0, 0], [0, 0, -1]],
    [[0, 0, 1], [1, 0, 0], [0, -1, 0]],
    [[0, 0, -1], [-1, 0, 0], [0, -1, 0]],
], dtype=np.float64)


def face_uv(size: int) -> Tuple[np.ndarray, np.ndarray]:
    """u (columns) and v (rows) of the texel centres of a face, each (S, S)."""
    c = 2.0 * (np.arange(size) + 0.5) / size - 1.0
    return np.meshgrid(c, c, indexing="xy")


def texel_directions(size: int) -> np.ndarray:
    """Unit directions of all texel centres, (6, S, S, 3)."""
    u, v = face_uv(size)
    d = (FACE_AXES[:, 0, None, None, :] + u[None, ..., None] * FACE_AXES[:, 1, None, None, :]
         + v[None, ..., None] * FACE_AXES[:, 2, None, None, :])
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def direction_to_face(d: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Face index, u, v of directions (N, 3) by the major-axis rule."""
    d = np.asarray(d, np.float64)
    a = np.abs(d)
    face = np.where((a[:, 0] >= a[:, 1]) & (a[:, 0] >= a[:, 2]), np.where(d[:, 0] > 0, 0, 1),
                    np.where(a[:, 1] >= a[:, 2], np.where(d[:, 1] > 0, 2, 3),
                             np.where(d[:, 2] > 0, 4, 5)))
    axes = FACE_AXES[face]
    ma = np.einsum("nk,nk->n", d, axes[:, 0])
    u = np.einsum("nk,nk->n", d, axes[:, 1]) / ma
    v = np.einsum("nk,nk->n", d, axes[:, 2]) / ma
    return face, u, v


def texel_solid_angles(size: int, sub: int = 8) -> np.ndarray:
    """Solid angle of each texel of a face (S, S) by sub x sub midpoint quadrature."""
    n = size * sub
    c = 2.0 * (np.arange(n) + 0.5) / n - 1.0
    u, v = np.meshgrid(c, c, indexing="xy")
    dw = (2.0 / n) ** 2 / (1.0 + u * u + v * v) ** 1.5
    return dw.reshape(size, sub, size, sub).sum(axis=(1, 3))


def sh9_basis(d: np.ndarray) -> np.ndarray:
    """Real SH basis (..., 9) in weft's order: Y00, Y1-1 (y), Y10 (z), Y11 (x), Y2-2 (xy),
    Y2-1 (yz), Y20, Y21 (xz), Y22 (x^2 - y^2)."""
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    c0 = 0.5 / np.sqrt(np.pi)
    c1 = np.sqrt(3.0 / (4.0 * np.pi))
    c2 = np.sqrt(15.0 / (4.0 * np.pi))
    c20 = np.sqrt(5.0 / (16.0 * np.pi))
    c22 = np.sqrt(15.0 / (16.0 * np.pi))
    return np.stack([np.full_like(x, c0), c1 * y, c1 * z, c1 * x, c2 * x * y, c2 * y * z,
                     c20 * (3.0 * z * z - 1.0), c2 * x * z, c22 * (x * x - y * y)], axis=-1)


def _texels(faces: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    faces = np.asarray(faces, np.float64)
    s = faces.shape[1]
    d = texel_directions(s).reshape(-1, 3)
    w = np.broadcast_to(texel_solid_angles(s, sub=max(8, 128 // s)), (6, s, s)).reshape(-1)
    return d, w, faces.reshape(-1, 3)


def reduce_faces(faces: np.ndarray, factor: int) -> np.ndarray:
    """Solid-angle weighted factor x factor averages of the texels, (6, S/f, S/f, 3)."""
    faces = np.asarray(faces, np.float64)
    s = faces.shape[1]
    w = texel_solid_angles(s, sub=max(2, 64 // s))[None, ..., None]
    num = (faces * w).reshape(6, s // factor, factor, s // factor, factor, 3).sum(axis=(2, 4))
    den = np.broadcast_to(w, (6, s, s, 1)).reshape(6, s // factor, factor, s // factor, factor,
                                                    1).sum(axis=(2, 4))
    return num / den


def project_sh9(faces: np.ndarray) -> np.ndarray:
    """SH9 radiance coefficients (9, 3)."""
    d, w, c = _texels(faces)
    return np.einsum("nk,n,nc->kc", sh9_basis(d), w, c)


def sh_irradiance(coeffs: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """E(n) from SH9 coefficients, (N, 3)."""
    a = np.array([np.pi] + [2.0 * np.pi / 3.0] * 3 + [np.pi / 4.0] * 5)
    return sh9_basis(np.asarray(normals, np.float64)) @ (a[:, None] * coeffs)


def irradiance(faces: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """E(n) = sum of L max(0, n.w) dw over all texels, (N, 3)."""
    d, w, c = _texels(faces)
    cos = np.maximum(np.asarray(normals, np.float64) @ d.T, 0.0)
    return cos @ (c * w[:, None])


def phong(faces: np.ndarray, shininess: float, dirs: np.ndarray) -> np.ndarray:
    """Normalised Phong-lobe average of the radiance around each direction, (N, 3)."""
    d, w, c = _texels(faces)
    lobe = np.maximum(np.asarray(dirs, np.float64) @ d.T, 0.0) ** shininess * w
    return (lobe @ c) / lobe.sum(axis=1, keepdims=True)


def ggx_prefilter(faces: np.ndarray, roughness: float, dirs: np.ndarray) -> np.ndarray:
    """Split-sum prefiltered radiance with N = V = R: integral of L(l) D(h) (n.l) dl over the
    same integral of D(h) (n.l), h = normalize(l + n), GGX D with alpha = roughness^2, (N, 3)."""
    d, w, c = _texels(faces)
    n = np.asarray(dirs, np.float64)
    alpha2 = max(roughness * roughness, 1e-3) ** 2
    nl = n @ d.T
    nh2 = np.maximum(0.5 * (1.0 + nl), 0.0)  # (n.h)^2 for h = normalize(l + n)
    dd = alpha2 / (np.pi * (nh2 * (alpha2 - 1.0) + 1.0) ** 2)
    weight = np.where(nl > 0, dd * nl, 0.0) * w
    return (weight @ c) / weight.sum(axis=1, keepdims=True)


def sphere_map_coords(dirs: np.ndarray, world_to_sphere: np.ndarray, wrap: float) -> np.ndarray:
    """SPEC §4.2: disc coordinates (x, y) (y up) where a world direction is read, (N, 2)."""
    v = np.asarray(dirs, np.float64) @ np.asarray(world_to_sphere, np.float64)[:3, :3].T
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    h = v + np.array([0.0, 0.0, wrap])
    h /= np.linalg.norm(h, axis=1, keepdims=True)
    back = h[:, 2] < 0
    h[back, 2] = 0.0
    h[back] /= np.linalg.norm(h[back], axis=1, keepdims=True)
    return h[:, :2]


def equirect_coords(dirs: np.ndarray) -> np.ndarray:
    """(u, v) in [0, 1]: u = 0.5 + atan2(x, -z) / 2 pi, v = acos(y) / pi, (N, 2)."""
    d = np.asarray(dirs, np.float64)
    return np.stack([0.5 + np.arctan2(d[:, 0], -d[:, 2]) / (2.0 * np.pi),
                     np.arccos(np.clip(d[:, 1], -1.0, 1.0)) / np.pi], axis=1)


def ray_hits_sphere(origin: np.ndarray, dirs: np.ndarray, centre: np.ndarray,
                    radius: float) -> np.ndarray:
    """Whether rays origin + t d (t > 0, unit d) hit the sphere, (N,) bool."""
    oc = np.asarray(origin, np.float64) - np.asarray(centre, np.float64)
    b = np.asarray(dirs, np.float64) @ oc
    c = oc @ oc - radius * radius
    disc = b * b - c
    t_far = -b + np.sqrt(np.maximum(disc, 0.0))
    return (disc > 0.0) & (t_far > 0.0)


def visible_irradiance(faces: np.ndarray, point: np.ndarray, normal: np.ndarray,
                       centre: np.ndarray, radius: float, sub: int = 1) -> np.ndarray:
    """Integral of L V cos over the hemisphere around ``normal`` at ``point``, V = not blocked by
    the sphere; texels split into sub x sub visibility rays. (3,)"""
    faces = np.asarray(faces, np.float64)
    s = faces.shape[1]
    n = s * sub
    d = texel_directions(n).reshape(-1, 3)
    w = np.broadcast_to(texel_solid_angles(n), (6, n, n)).reshape(-1)
    c = np.repeat(np.repeat(faces, sub, axis=1), sub, axis=2).reshape(-1, 3)
    cos = np.maximum(d @ np.asarray(normal, np.float64), 0.0)
    vis = ~ray_hits_sphere(point, d, centre, radius)
    return (cos * vis * w) @ c


def dfg(n_dot_v: float, roughness: float, n: int = 400) -> Tuple[float, float]:
    """Split-sum DFG terms (scale, bias) by midpoint quadrature over the hemisphere of l:
    integral of f_spec / F * (n.l) with GGX D, Smith-Schlick G (k = alpha / 2)."""
    alpha = roughness * roughness
    k = alpha / 2.0
    v = np.array([np.sqrt(1.0 - n_dot_v ** 2), 0.0, n_dot_v])
    mu = (np.arange(n) + 0.5) / n  # cos(theta_l)
    phi = 2.0 * np.pi * (np.arange(2 * n) + 0.5) / (2 * n)
    m, p = np.meshgrid(mu, phi, indexing="ij")
    st = np.sqrt(1.0 - m * m)
    l = np.stack([st * np.cos(p), st * np.sin(p), m], axis=-1)
    h = l + v
    h /= np.linalg.norm(h, axis=-1, keepdims=True)
    nh, vh, nl = h[..., 2], h @ v, m
    d = alpha ** 2 / (np.pi * (nh * nh * (alpha ** 2 - 1.0) + 1.0) ** 2)
    g = (n_dot_v / (n_dot_v * (1 - k) + k)) * (nl / (nl * (1 - k) + k))
    f = d * g / (4.0 * n_dot_v * nl) * nl
    fc = (1.0 - vh) ** 5
    dw = (1.0 / n) * (2.0 * np.pi / (2 * n))
    return float(((1.0 - fc) * f).sum() * dw), float((fc * f).sum() * dw)


def srgb_to_linear(x: np.ndarray) -> np.ndarray:
    """sRGB decode of values in [0, 1]."""
    x = np.asarray(x, np.float64)
    return np.where(x <= 0.04045, x / 12.92, ((x + 0.055) / 1.055) ** 2.4)
