"""NumPy reference for colour encoding and texture sampling (float64).

sRGB transfer functions, bilinear and trilinear sampling with REPEAT wrap (texel centres at
(i + 0.5) / W), box-filtered mip chains and the LOD a GPU derives from UV derivatives - what
the renderer's samplers compute, written independently of them.
"""

from __future__ import annotations

from typing import List, Sequence, Tuple, Union

import numpy as np

ArrayLike = Union[np.ndarray, Sequence[float], float]

__all__ = ["srgb_encode", "srgb_decode", "encode_u8", "texture_to_linear", "sample_bilinear_repeat",
           "build_mip_chain", "sample_trilinear_repeat", "texture_lod"]


# --------------------------------------------------------------------------------------------
# Colour encoding
# --------------------------------------------------------------------------------------------

def srgb_encode(linear: ArrayLike) -> np.ndarray:
    """Standard sRGB transfer function (linear -> encoded), float64, input clamped to [0, 1].

    ``12.92 x`` below 0.0031308, else ``1.055 x^(1/2.4) - 0.055``.
    """
    x = np.clip(np.asarray(linear, dtype=np.float64), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def srgb_decode(encoded: ArrayLike) -> np.ndarray:
    """Inverse of :func:`srgb_encode` (encoded in [0, 1] -> linear), float64."""
    x = np.clip(np.asarray(encoded, dtype=np.float64), 0.0, 1.0)
    return np.where(x <= 0.04045, x / 12.92, np.power((x + 0.055) / 1.055, 2.4))


def encode_u8(linear: ArrayLike) -> np.ndarray:
    """8-bit sRGB value of linear radiance: ``round(255 * srgb_encode(clamp(x, 0, 1)))``."""
    return np.rint(255.0 * srgb_encode(linear)).astype(np.uint8)


# --------------------------------------------------------------------------------------------
# Textures
# --------------------------------------------------------------------------------------------

def texture_to_linear(image: np.ndarray, srgb: bool = True) -> np.ndarray:
    """Converts a texture image to linear float64 RGBA (H, W, 4) the way the renderer sees it.

    ``image`` is uint8 (H, W), (H, W, 1), (H, W, 2) (grey + alpha), (H, W, 3) or (H, W, 4):
    grey is replicated to RGB, missing alpha is 1. With ``srgb`` the colour channels are
    sRGB-decoded (alpha never is).
    A floating-point image is taken as already linear and only expanded to RGBA.
    """
    img = np.asarray(image)
    if img.ndim == 2:
        img = img[:, :, None]
    if img.ndim != 3 or not 1 <= img.shape[2] <= 4 or img.shape[0] < 1 or img.shape[1] < 1:
        raise ValueError(f"texture image must be (H,W) or (H,W,1..4), got shape {img.shape}")
    floating = np.issubdtype(img.dtype, np.floating)
    data = img.astype(np.float64) if floating else img.astype(np.float64) / 255.0
    h, w, c = data.shape
    out = np.ones((h, w, 4), dtype=np.float64)
    if c <= 2:
        out[:, :, :3] = data[:, :, :1]
        if c == 2:
            out[:, :, 3] = data[:, :, 1]
    else:
        out[:, :, :3] = data[:, :, :3]
        if c == 4:
            out[:, :, 3] = data[:, :, 3]
    if srgb and not floating:
        out[:, :, :3] = srgb_decode(out[:, :, :3])
    return out


def sample_bilinear_repeat(tex_linear: np.ndarray, uv: np.ndarray) -> np.ndarray:
    """Bilinear lookup with REPEAT wrapping, no mipmaps (what a sampler does at LOD 0).

    ``tex_linear`` is (H, W, C) linear values (decode sRGB *before* filtering, as the hardware
    does); ``uv`` is (..., 2). Texel (i, j) has its centre at ((i + 0.5) / W, (j + 0.5) / H);
    v = 0 is the top row (row 0). Returns (..., C) float64.
    """
    tex = np.asarray(tex_linear, dtype=np.float64)
    if tex.ndim == 2:
        tex = tex[:, :, None]
    uv = np.asarray(uv, dtype=np.float64)
    if uv.shape[-1] != 2:
        raise ValueError(f"uv must have a last axis of 2, got shape {uv.shape}")
    h, w = tex.shape[:2]
    x = uv[..., 0] * w - 0.5
    y = uv[..., 1] * h - 0.5
    x0 = np.floor(x)
    y0 = np.floor(y)
    fx = (x - x0)[..., None]
    fy = (y - y0)[..., None]
    x0 = x0.astype(np.int64)
    y0 = y0.astype(np.int64)
    xi0 = np.mod(x0, w)
    xi1 = np.mod(x0 + 1, w)
    yi0 = np.mod(y0, h)
    yi1 = np.mod(y0 + 1, h)
    top = tex[yi0, xi0] * (1.0 - fx) + tex[yi0, xi1] * fx
    bottom = tex[yi1, xi0] * (1.0 - fx) + tex[yi1, xi1] * fx
    return top * (1.0 - fy) + bottom * fy


def _bilinear_clamp(tex: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Bilinear lookup at unnormalised texel coordinates (centres at i + 0.5), CLAMP_TO_EDGE."""
    h, w = tex.shape[:2]
    fx0 = np.floor(x - 0.5)
    fy0 = np.floor(y - 0.5)
    ax = (x - 0.5 - fx0)[..., None]
    ay = (y - 0.5 - fy0)[..., None]
    x0 = np.clip(fx0.astype(np.int64), 0, w - 1)
    x1 = np.clip(fx0.astype(np.int64) + 1, 0, w - 1)
    y0 = np.clip(fy0.astype(np.int64), 0, h - 1)
    y1 = np.clip(fy0.astype(np.int64) + 1, 0, h - 1)
    top = tex[y0, x0] * (1.0 - ax) + tex[y0, x1] * ax
    bottom = tex[y1, x0] * (1.0 - ax) + tex[y1, x1] * ax
    return top * (1.0 - ay) + bottom * ay


def build_mip_chain(tex_linear: np.ndarray, srgb: bool = True,
                    quantize: bool = True) -> List[np.ndarray]:
    """Mip levels of a texture as a GPU builds them with successive linear-filtered blits.

    Level k+1 has ``max(1, size_k // 2)`` texels per side; each texel is the bilinear sample
    (in linear space, CLAMP_TO_EDGE) of level k at its centre, i.e. the 2x2 box average for
    even sizes. With ``quantize`` every level is stored back to 8 bits (sRGB-encoded if
    ``srgb``) as an RGBA8 image would be. Returns the levels as linear float64 arrays.
    """
    level = np.asarray(tex_linear, dtype=np.float64)
    if level.ndim == 2:
        level = level[:, :, None]
    levels = [level]
    while level.shape[0] > 1 or level.shape[1] > 1:
        h, w = level.shape[:2]
        h2, w2 = max(1, h // 2), max(1, w // 2)
        yy, xx = np.mgrid[0:h2, 0:w2].astype(np.float64)
        level = _bilinear_clamp(level, (xx + 0.5) * (w / w2), (yy + 0.5) * (h / h2))
        if quantize:
            if srgb:
                level[..., :3] = srgb_decode(np.rint(srgb_encode(level[..., :3]) * 255.0) / 255.0)
                if level.shape[2] > 3:
                    level[..., 3:] = np.rint(np.clip(level[..., 3:], 0, 1) * 255.0) / 255.0
            else:
                level = np.rint(np.clip(level, 0.0, 1.0) * 255.0) / 255.0
        levels.append(level)
    return levels


def sample_trilinear_repeat(levels: Sequence[np.ndarray], uv: np.ndarray,
                            lod: ArrayLike) -> np.ndarray:
    """Trilinear lookup (bilinear in the two nearest mip levels, linear between them), REPEAT
    wrapping; ``lod`` (broadcastable to uv.shape[:-1]) is clamped to [0, len(levels) - 1]."""
    uv = np.asarray(uv, dtype=np.float64)
    lod = np.clip(np.broadcast_to(np.asarray(lod, dtype=np.float64), uv.shape[:-1]), 0.0,
                  len(levels) - 1)
    lod = np.where(np.isfinite(lod), lod, 0.0)
    lo = np.floor(lod).astype(np.int64)
    frac = (lod - lo)[..., None]
    out = np.zeros(uv.shape[:-1] + (levels[0].shape[-1],), dtype=np.float64)
    for k in np.unique(lo):
        sel = lo == k
        a = sample_bilinear_repeat(levels[k], uv[sel])
        b = sample_bilinear_repeat(levels[min(k + 1, len(levels) - 1)], uv[sel])
        out[sel] = a * (1.0 - frac[sel]) + b * frac[sel]
    return out


def texture_lod(uv: np.ndarray, labels: np.ndarray, width: int, height: int) -> np.ndarray:
    """Level of detail of a texture of ``width`` x ``height`` texels at every pixel, from the
    screen-space derivatives of an interpolated UV image (H, W, 2), as a fragment shader's
    implicit-LOD ``texture()`` computes it: differences inside each 2x2 pixel quad
    (d/dx within the row, d/dy within the column), ``rho = max(|d(uv)/dx|, |d(uv)/dy|)`` in
    texels, ``lod = log2(rho)``.

    Only neighbours with the same label count; where the quad partner belongs to something
    else (silhouettes) the pixel on the other side is used instead, and where neither exists
    the derivative of that direction is taken from the other one. Along silhouettes this can
    differ from the GPU, whose helper invocations extrapolate the triangle.
    """
    uv = np.asarray(uv, dtype=np.float64)
    labels = np.asarray(labels)
    h, w = labels.shape
    scale = np.array([float(width), float(height)])
    ys, xs = np.mgrid[0:h, 0:w]

    def derivative(axis: int) -> Tuple[np.ndarray, np.ndarray]:
        coord = xs if axis == 1 else ys
        size = w if axis == 1 else h
        partner = coord ^ 1  # the other pixel of the quad along this axis
        other = np.where(coord % 2 == 0, coord - 1, coord + 1)  # outside the quad
        result = np.zeros(uv.shape)
        valid = np.zeros(labels.shape, dtype=bool)
        for cand in (partner, other):
            ok = (cand >= 0) & (cand < size) & ~valid
            cc = np.clip(cand, 0, size - 1)
            if axis == 1:
                nb_label, nb_uv = labels[ys, cc], uv[ys, cc]
            else:
                nb_label, nb_uv = labels[cc, xs], uv[cc, xs]
            ok &= (nb_label == labels) & (labels >= 0)
            step = np.where(cand > coord, 1.0, -1.0)[..., None]
            result = np.where(ok[..., None], (nb_uv - uv) * step, result)
            valid |= ok
        return result * scale, valid

    dx, vx = derivative(1)
    dy, vy = derivative(0)
    rho_x = np.linalg.norm(dx, axis=-1)
    rho_y = np.linalg.norm(dy, axis=-1)
    rho_x = np.where(vx, rho_x, rho_y)
    rho_y = np.where(vy, rho_y, rho_x)
    rho = np.maximum(rho_x, rho_y)
    with np.errstate(divide="ignore"):
        lod = np.log2(rho)
    return np.where(np.isfinite(lod), lod, 0.0)
