"""NumPy oracle of the renderer's environment lighting (SPEC §1.3 Fresnel reflection, §4.4),
float64, from a frame's ``render_debug`` outputs; never calls weft.

Per covered pixel with world position p, unit shading normal n, texture colour T and the
material's K_D, reflectivity F0, environment-diffuse weight w and shininess s:

- diffuse  = w K_D T E(n) / pi, E from the SH9 radiance coefficients (``ibl.sh_irradiance``);
- specular = F G(R, lod), v = normalize(eye - p), R = 2 (n.v) n - v,
  F = F0 + (1 - F0) (1 - max(n.v, 0))^5 (Schlick), G the prefiltered chain sampled trilinearly
  at lod = roughness(s) (levels - 1) with roughness(s) = (2 / (s + 2))^(1/4);
- both times the environment intensity;
- the seed's decal material (``gloss_alpha`` = the base texture's alpha a): T (a diffuse / T +
  (1 - a) specular), i.e. lighting = lerp(specular, diffuse, a) times T (SPEC §4.4).

The seed's eye-space sphere-map path (``sphere_map_uv``): a world direction d goes to eye space,
m = normalize(d_eye + (0, 0, 1)), texture coordinates (0.5 + 0.5 m.x, 0.5 - 0.5 m.y).
``dome_blur`` is the bilateral blur of the dome's visibility (glsl/render/dome_blur.frag).

The chain is sampled seamlessly: bilinear taps that fall off a face are read from the
neighbouring face's texel across the edge. Vulkan's cube sampling
does the same along edges; at the corners, where three faces meet, the GPU's choice is
implementation-defined, so pixels whose lookup lands within a texel of a corner may differ.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from weft.reference.ibl import FACE_AXES, direction_to_face, sh_irradiance


def environment_roughness(shininess: np.ndarray) -> np.ndarray:
    """Perceptual GGX roughness of a Blinn-Phong exponent: sqrt(alpha), alpha = sqrt(2/(s+2))."""
    return np.clip((2.0 / (np.asarray(shininess, np.float64) + 2.0)) ** 0.25, 0.0, 1.0)


def _texel(level: np.ndarray, face: np.ndarray, i: np.ndarray, j: np.ndarray) -> np.ndarray:
    """Texels (column i, row j) of `face` where i, j may lie one texel outside the face: those are
    read from the neighbouring face's edge texel across that edge, at the same position along
    it (the outside coordinate is moved to just beyond the edge, then the face is looked up)."""
    s = level.shape[1]
    u = np.clip(2.0 * (i + 0.5) / s - 1.0, -1.0 - 1e-6, 1.0 + 1e-6)
    v = np.clip(2.0 * (j + 0.5) / s - 1.0, -1.0 - 1e-6, 1.0 + 1e-6)
    axes = FACE_AXES[face]
    d = axes[:, 0] + u[:, None] * axes[:, 1] + v[:, None] * axes[:, 2]
    f2, u2, v2 = direction_to_face(d)
    i2 = np.clip(np.floor((u2 + 1.0) * 0.5 * s), 0, s - 1).astype(np.int64)
    j2 = np.clip(np.floor((v2 + 1.0) * 0.5 * s), 0, s - 1).astype(np.int64)
    return level[f2, j2, i2]


def sample_face_bilinear(level: np.ndarray, dirs: np.ndarray) -> np.ndarray:
    """Seamless bilinear sample of one cube level (6, S, S, 3) at directions (N, 3) -> (N, 3)."""
    level = np.asarray(level, np.float64)
    s = level.shape[1]
    face, u, v = direction_to_face(dirs)
    x = (u + 1.0) * 0.5 * s - 0.5
    y = (v + 1.0) * 0.5 * s - 0.5
    x0, y0 = np.floor(x), np.floor(y)
    fx, fy = (x - x0)[:, None], (y - y0)[:, None]
    top = _texel(level, face, x0, y0) * (1 - fx) + _texel(level, face, x0 + 1, y0) * fx
    bottom = _texel(level, face, x0, y0 + 1) * (1 - fx) + _texel(level, face, x0 + 1, y0 + 1) * fx
    return top * (1 - fy) + bottom * fy


def sample_chain(levels: Sequence[np.ndarray], dirs: np.ndarray, lod: np.ndarray) -> np.ndarray:
    """Trilinear sample of a chain (list of (6, S_l, S_l, 3)) at (N, 3) directions, lods (N,)."""
    lod = np.clip(np.asarray(lod, np.float64), 0.0, len(levels) - 1)
    lo = np.floor(lod).astype(np.int64)
    hi = np.minimum(lo + 1, len(levels) - 1)
    t = (lod - lo)[:, None]
    out = np.zeros((len(lod), 3))
    for l in range(len(levels)):
        for sel, weight in ((lo == l, 1.0 - t), (hi == l, t)):
            if np.any(sel):
                out[sel] += weight[sel] * sample_face_bilinear(levels[l], dirs[sel])
    return out


def environment_light(position: np.ndarray, normal: np.ndarray, eye: np.ndarray,
                      albedo: np.ndarray, *, kd: np.ndarray, reflectivity: np.ndarray,
                      environment_diffuse: float, shininess: float, sh_coeffs: np.ndarray,
                      chain: Sequence[np.ndarray], intensity: float,
                      gloss_alpha: np.ndarray | None = None) -> np.ndarray:
    """Environment radiance (N, 3) at N pixels (see the module docstring)."""
    p = np.asarray(position, np.float64)
    n = np.asarray(normal, np.float64)
    t = np.asarray(albedo, np.float64)
    kd = np.asarray(kd, np.float64)
    f0 = np.asarray(reflectivity, np.float64)
    diffuse = environment_diffuse * kd * t * np.maximum(sh_irradiance(sh_coeffs, n), 0.0) / np.pi
    v = np.asarray(eye, np.float64).reshape(1, 3) - p
    v /= np.linalg.norm(v, axis=-1, keepdims=True)
    ndv = np.einsum("nk,nk->n", n, v)
    r = 2.0 * ndv[:, None] * n - v
    lod = np.full(len(p), environment_roughness(shininess) * (len(chain) - 1))
    fresnel = f0 + (1.0 - f0) * (1.0 - np.clip(ndv, 0.0, 1.0))[:, None] ** 5
    specular = fresnel * sample_chain(chain, r, lod) if np.any(f0 > 0) else 0.0
    if gloss_alpha is not None:
        a = np.asarray(gloss_alpha, np.float64).reshape(-1, 1)
        return intensity * (a * diffuse + (1.0 - a) * t * specular)
    return intensity * (diffuse + specular)


def sphere_map_uv(dirs: np.ndarray, view: np.ndarray) -> np.ndarray:
    """Texture coordinates (N, 2) of world directions (N, 3) in an eye-space sphere map; `view`
    is the camera's 4x4 world -> eye matrix."""
    d = np.asarray(dirs, np.float64) @ np.asarray(view, np.float64)[:3, :3].T
    m = d + np.array([0.0, 0.0, 1.0])
    length = np.linalg.norm(m, axis=-1, keepdims=True)
    m = np.where(length > 1e-6, m / np.maximum(length, 1e-300), np.array([1.0, 0.0, 0.0]))
    return np.stack([0.5 + 0.5 * m[:, 0], 0.5 - 0.5 * m[:, 1]], axis=-1)


def sample_image_bilinear(image: np.ndarray, uv: np.ndarray) -> np.ndarray:
    """Bilinear lookup with clamp to edge of an (H, W, C) image at texture coordinates (N, 2)."""
    img = np.asarray(image, np.float64)
    h, w = img.shape[:2]
    x = np.asarray(uv, np.float64)[:, 0] * w - 0.5
    y = np.asarray(uv, np.float64)[:, 1] * h - 0.5
    x0, y0 = np.floor(x), np.floor(y)
    fx, fy = (x - x0)[:, None], (y - y0)[:, None]

    def at(i, j):
        return img[np.clip(j, 0, h - 1).astype(np.int64), np.clip(i, 0, w - 1).astype(np.int64)]

    top = at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx
    bottom = at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx
    return top * (1 - fy) + bottom * fy


def dome_blur(visibility: np.ndarray, depth: np.ndarray, covered: np.ndarray, radius: float,
              tolerance: float) -> np.ndarray:
    """The renderer's blur of the dome visibility (H, W) over `radius` pixels, two separable
    bilateral passes (rows, then columns of the rows' result): 7 taps at offsets
    o = k radius / 3, k = -3..3 (rounded half up), weights exp(-o^2 / (2 sigma^2) - dz^2),
    sigma = radius / 2, dz = (z_tap - z) / (tolerance z) in view depth z (H, W); taps clamp to
    the image and skip uncovered pixels. Uncovered pixels return 0."""
    vis = np.where(covered, np.asarray(visibility, np.float64), 0.0)
    z = np.asarray(depth, np.float64)
    step = radius / 3.0
    sigma = max(radius * 0.5, 1e-6)
    safe_z = np.where(covered, z, 1.0)

    def one_pass(values: np.ndarray, axis: int) -> np.ndarray:
        n = values.shape[axis]
        index = np.arange(n)
        total = np.zeros_like(values)
        weights = np.zeros_like(values)
        for k in range(-3, 4):
            o = k * step
            q = np.clip(index + int(np.floor(o + 0.5)), 0, n - 1)
            tap_v, tap_z, tap_ok = (np.take(a, q, axis=axis) for a in (values, z, covered))
            dz = (tap_z - z) / (tolerance * safe_z)
            w = np.where(tap_ok, np.exp(-o * o / (2 * sigma * sigma) - dz * dz), 0.0)
            total += w * tap_v
            weights += w
        return np.where(covered, total / np.maximum(weights, 1e-300), 0.0)

    return one_pass(one_pass(vis, axis=1), axis=0)
