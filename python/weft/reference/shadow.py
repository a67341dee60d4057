"""NumPy reference for the shadow-map test (SPEC §1.5): normal offset, slope-scaled clamped
depth bias and (2r+1)^2 percentage-closer filtering, exactly as ``glsl/common/shading.glsl``
specifies it, recomputed from a frame's debug outputs and the read-back shadow map."""

from __future__ import annotations

from typing import Any, Mapping, NamedTuple, Optional, Sequence, Union

import numpy as np

ArrayLike = Union[np.ndarray, Sequence[float], float]

from weft.reference.shading import LightDesc, _vec3

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


def shadow_lookup(position: np.ndarray, normal: np.ndarray, light_direction: ArrayLike,
                  shadow_map: np.ndarray, shadow_info: Any,
                  pcf_radius: Optional[int] = None) -> ShadowLookup:
    """Shadow-map test with normal offset, slope-scaled bias and PCF (SPEC §1.5).

    ``light_direction`` is the light's ``direction`` (pointing into the scene);
    ``shadow_map`` (S, S) depth in [0, 1] with row 0 at NDC y = -1; ``shadow_info`` is
    ``Renderer.shadow_info()`` (keys ``view_proj``, ``normal_offset_world``,
    ``bias_constant``, ``bias_slope``, ``bias_max``, ``pcf_radius``). Per receiver::

        ndl   = clamp(n.l, -1, 1),  sin = sqrt(max(0, 1 - ndl^2))
        p_off = p + n * normal_offset_world * sin
        c     = view_proj @ (p_off, 1);  ndc = c.xyz / c.w
        u, v  = ndc.xy * 0.5 + 0.5;  d = ndc.z
        outside the map or d > 1  ->  visibility 1
        bias  = min(bias_constant + bias_slope * sin / max(ndl, 1e-4), bias_max)
        visibility = fraction of the (2r+1)^2 texels around (floor(u S), floor(v S)) (clamped
                     to the map) with  d - bias <= depth
    """
    p = np.asarray(position, dtype=np.float64)
    n = np.asarray(normal, dtype=np.float64)
    smap = np.asarray(shadow_map, dtype=np.float64)
    if smap.ndim != 2 or smap.shape[0] != smap.shape[1] or smap.shape[0] < 1:
        raise ValueError(f"shadow_map must be square (S, S), got {smap.shape}")
    size = smap.shape[0]
    l = LightDesc(direction=tuple(_vec3(light_direction, "light_direction"))).to_light()
    view_proj = np.asarray(_info(shadow_info, "view_proj"), dtype=np.float64).reshape(4, 4)
    offset = float(_info(shadow_info, "normal_offset_world"))
    bias_constant = float(_info(shadow_info, "bias_constant"))
    bias_slope = float(_info(shadow_info, "bias_slope"))
    bias_max = float(_info(shadow_info, "bias_max"))
    radius = int(_info(shadow_info, "pcf_radius") if pcf_radius is None else pcf_radius)

    ndl = np.clip(np.einsum("...k,k->...", n, l), -1.0, 1.0)
    sin = np.sqrt(np.maximum(0.0, 1.0 - ndl * ndl))
    p_off = p + n * (offset * sin)[..., None]
    clip = np.einsum("ij,...j->...i", view_proj[:, :3], p_off) + view_proj[:, 3]
    w = clip[..., 3]
    safe_w = np.where(w != 0.0, w, 1.0)
    ndc = clip[..., :3] / safe_w[..., None]
    u = ndc[..., 0] * 0.5 + 0.5
    v = ndc[..., 1] * 0.5 + 0.5
    d = ndc[..., 2]
    outside = (u < 0.0) | (u > 1.0) | (v < 0.0) | (v > 1.0) | (d > 1.0) | (w == 0.0)
    outside |= ~np.isfinite(u) | ~np.isfinite(v) | ~np.isfinite(d)

    bias = np.minimum(bias_constant + bias_slope * sin / np.maximum(ndl, 1e-4), bias_max)
    ref = d - bias
    with np.errstate(invalid="ignore"):
        tx = np.floor(np.where(outside, 0.0, u) * size).astype(np.int64)
        ty = np.floor(np.where(outside, 0.0, v) * size).astype(np.int64)
    lit = np.zeros(d.shape, dtype=np.float64)
    for dy in range(-radius, radius + 1):
        rows = np.clip(ty + dy, 0, size - 1)
        for dx in range(-radius, radius + 1):
            cols = np.clip(tx + dx, 0, size - 1)
            lit += ref <= smap[rows, cols]
    vis = lit / float((2 * radius + 1) ** 2)
    vis = np.where(outside, 1.0, vis)
    return ShadowLookup(visibility=vis, depth=d, u=u, v=v)


def pcf_visibility(position: np.ndarray, normal: np.ndarray, light_direction: ArrayLike,
                   shadow_map: np.ndarray, shadow_info: Any) -> np.ndarray:
    """PCF shadow visibility in [0, 1] per receiver (SPEC §1.5); see :func:`shadow_lookup`."""
    return shadow_lookup(position, normal, light_direction, shadow_map, shadow_info).visibility
