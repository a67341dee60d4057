"""NumPy reference for the shadow-map test (SPEC §1.5): normal offset, slope-scaled clamped
depth bias and (2r+1)^2 percentage-closer filtering for orthographic (directional), perspective
(spot) and six-view (point) shadow maps, exactly as ``glsl/common/shading.glsl`` specifies it,
recomputed from a frame's debug outputs and the read-back shadow maps."""

from __future__ import annotations

from typing import Any, Mapping, NamedTuple, Optional, Sequence, Union

import numpy as np

from weft.reference.shading import LightDesc, _vec3, as_light, incident

ArrayLike = Union[np.ndarray, Sequence[float], float]

__all__ = ["ShadowLookup", "shadow_lookup", "pcf_visibility"]


class ShadowLookup(NamedTuple):
    """Result of :func:`shadow_lookup`: PCF visibility in [0, 1], the receiver's light-space
    depth ``d`` (what ``render_debug()["light_depth"]`` reports) and its map coordinates."""

    visibility: np.ndarray
    depth: np.ndarray
    u: np.ndarray
    v: np.ndarray


def _info(info: Any, key: str) -> Any:
    return info[key] if isinstance(info, Mapping) else getattr(info, key)


def _has(info: Any, key: str) -> bool:
    return key in info if isinstance(info, Mapping) else hasattr(info, key)


def _cube_face(d: np.ndarray) -> np.ndarray:
    """View of a point light (+X, -X, +Y, -Y, +Z, -Z) that sees direction d (..., 3): the
    largest absolute component, ties going to x, then y (as the shader)."""
    a = np.abs(d)
    x_major = (a[..., 0] >= a[..., 1]) & (a[..., 0] >= a[..., 2])
    y_major = ~x_major & (a[..., 1] >= a[..., 2])
    face = np.where(x_major, np.where(d[..., 0] >= 0, 0, 1),
                    np.where(y_major, np.where(d[..., 1] >= 0, 2, 3),
                             np.where(d[..., 2] >= 0, 4, 5)))
    return face


def _linear_depth(d: np.ndarray, near: float, far: float) -> np.ndarray:
    return near * far / (far - d * (far - near))


def shadow_lookup(position: np.ndarray, normal: np.ndarray, light: Any,
                  shadow_map: Union[np.ndarray, Sequence[np.ndarray]], shadow_info: Any,
                  pcf_radius: Optional[int] = None) -> ShadowLookup:
    """Shadow-map test with normal offset, slope-scaled bias and PCF (SPEC §1.5).

    ``light`` is a light (anything :func:`weft.reference.shading.as_light` accepts) or, for a
    directional light, its ``direction`` (pointing into the scene). ``shadow_map`` is the
    (S, S) depth map in [0, 1] with row 0 at NDC y = -1 (``Renderer.shadow_map``), or for a
    point light its six views (6, S, S) in the order +X, -X, +Y, -Y, +Z, -Z.
    ``shadow_info`` is ``Renderer.shadow_info()`` (keys ``views``/``view_proj``,
    ``perspective``, ``near``, ``far``, ``normal_offset_world``, ``bias_constant``,
    ``bias_slope``, ``bias_max``, ``pcf_radius``). Per receiver, with l towards the light::

        ndl   = clamp(n.l, -1, 1),  sin = sqrt(max(0, 1 - ndl^2))
        off   = normal_offset_world (orthographic) or normal_offset_world * |x_L - p|
        q     = p + n * off * sin
        view  = 0, or for a point light the face of q - x_L (largest component)
        c     = views[view] @ (q, 1);  ndc = c.xyz / c.w
        u, v  = ndc.xy * 0.5 + 0.5;  d = ndc.z
        outside the map or c.w <= 0  ->  visibility 1;  z = min(d, 1) (the views enclose the
        casters only: a receiver beyond the far plane is compared as if on it)
        bias  = min(bias_constant + bias_slope * sin / max(ndl, 1e-4), bias_max)
        orthographic: lit tap when  z - bias <= depth
        perspective:  lit tap when  lin(z) - bias (far - near) <= lin(depth),
                      lin(z) = near far / (far - z (far - near))
        visibility = fraction of lit taps among the (2r+1)^2 texels around
                     (floor(u S), floor(v S)) (clamped to the map)

    That is the forward pass's test where a pixel covers at most 2r+1 texels of the map; where
    it covers more, the pass spreads the same taps over the pixel's footprint instead (from the
    position's screen derivatives, which a receiver list does not have; shading.glsl).
    """
    p = np.asarray(position, dtype=np.float64)
    n = np.asarray(normal, dtype=np.float64)
    if isinstance(light, (np.ndarray, list, tuple)):
        lt = LightDesc(direction=tuple(_vec3(light, "light direction")))
    else:
        lt = as_light(light)
    maps = np.asarray(shadow_map, dtype=np.float64)
    if maps.ndim == 2:
        maps = maps[None]
    if maps.ndim != 3 or maps.shape[1] != maps.shape[2] or maps.shape[1] < 1:
        raise ValueError(f"shadow_map must be (S, S) or (views, S, S), got {maps.shape}")
    size = maps.shape[1]
    views = _info(shadow_info, "views") if _has(shadow_info, "views") else \
        [_info(shadow_info, "view_proj")]
    views = [np.asarray(v, dtype=np.float64).reshape(4, 4) for v in views]
    if lt.kind == "point" and (len(views) != 6 or maps.shape[0] != 6):
        raise ValueError("a point light needs its six shadow views and maps")
    perspective = bool(_info(shadow_info, "perspective")) if _has(shadow_info, "perspective") \
        else False
    near = float(_info(shadow_info, "near")) if perspective else 0.0
    far = float(_info(shadow_info, "far")) if perspective else 1.0
    offset = float(_info(shadow_info, "normal_offset_world"))
    bias_constant = float(_info(shadow_info, "bias_constant"))
    bias_slope = float(_info(shadow_info, "bias_slope"))
    bias_max = float(_info(shadow_info, "bias_max"))
    radius = int(_info(shadow_info, "pcf_radius") if pcf_radius is None else pcf_radius)

    l, _ = incident(lt, p)
    ndl = np.clip(np.einsum("...k,...k->...", n, l), -1.0, 1.0)
    sin = np.sqrt(np.maximum(0.0, 1.0 - ndl * ndl))
    if perspective:
        offset = offset * np.linalg.norm(_vec3(lt.position, "position") - p, axis=-1)
    q = p + n * (offset * sin)[..., None]
    if lt.kind == "point":
        face = _cube_face(q - _vec3(lt.position, "position"))
    else:
        face = np.zeros(q.shape[:-1], dtype=np.int64)
    stacked = np.stack(views)  # (V, 4, 4)
    m = stacked[face]          # (..., 4, 4)
    clip = np.einsum("...ij,...j->...i", m[..., :, :3], q) + m[..., :, 3]
    w = clip[..., 3]
    safe_w = np.where(w != 0.0, w, 1.0)
    ndc = clip[..., :3] / safe_w[..., None]
    u = ndc[..., 0] * 0.5 + 0.5
    v = ndc[..., 1] * 0.5 + 0.5
    d = ndc[..., 2]
    outside = (u < 0.0) | (u > 1.0) | (v < 0.0) | (v > 1.0) | (w <= 0.0)
    outside |= ~np.isfinite(u) | ~np.isfinite(v) | ~np.isfinite(d)

    bias = np.minimum(bias_constant + bias_slope * sin / np.maximum(ndl, 1e-4), bias_max)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.minimum(d, 1.0)  # beyond the far plane: compared as if on it
        ref = _linear_depth(z, near, far) - bias * (far - near) if perspective else z - bias
        tx = np.floor(np.where(outside, 0.0, u) * size).astype(np.int64)
        ty = np.floor(np.where(outside, 0.0, v) * size).astype(np.int64)
    stored_maps = _linear_depth(maps, near, far) if perspective else maps
    lit = np.zeros(d.shape, dtype=np.float64)
    for dy in range(-radius, radius + 1):
        rows = np.clip(ty + dy, 0, size - 1)
        for dx in range(-radius, radius + 1):
            cols = np.clip(tx + dx, 0, size - 1)
            lit += ref <= stored_maps[face, rows, cols]
    vis = lit / float((2 * radius + 1) ** 2)
    vis = np.where(outside, 1.0, vis)
    return ShadowLookup(visibility=vis, depth=d, u=u, v=v)


def pcf_visibility(position: np.ndarray, normal: np.ndarray, light: Any,
                   shadow_map: Union[np.ndarray, Sequence[np.ndarray]],
                   shadow_info: Any) -> np.ndarray:
    """PCF shadow visibility in [0, 1] per receiver (SPEC §1.5); see :func:`shadow_lookup`."""
    return shadow_lookup(position, normal, light, shadow_map, shadow_info).visibility
