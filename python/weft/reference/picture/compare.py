"""Comparing weft's linear frame with the path-traced reference: both go through the same
exposure + clamp + sRGB, then FLIP (LDR, ``flip_evaluator``; Andersson et al. 2020) per pixel and
the mean relative error of the linear luminance, over the whole image, the covered pixels
(background masked), the objects (not the ground), the geometric edges (where weft's instance
id changes between 8-neighbours; background pixels only once weft draws the sky there) and,
with a key light, the objects' unlit side (n . l <= 0: only bounce / environment light there).
"""

from __future__ import annotations

from typing import Dict, Optional, Sequence

import numpy as np

LUMA = np.array([0.2126, 0.7152, 0.0722])


def srgb_encode(x: np.ndarray) -> np.ndarray:
    """Linear [0, 1] -> sRGB [0, 1] (IEC 61966-2-1)."""
    x = np.clip(np.asarray(x, np.float64), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def to_display(linear: np.ndarray, exposure: float = 1.0) -> np.ndarray:
    """The displayed picture: linear RGB times ``exposure``, clamped, sRGB-encoded, (H, W, 3)."""
    return srgb_encode(np.asarray(linear, np.float64)[..., :3] * float(exposure))


def flip_map(reference_display: np.ndarray, test_display: np.ndarray) -> np.ndarray:
    """Per-pixel LDR-FLIP error (H, W) of two sRGB [0, 1] images (default 67 pixels/degree)."""
    import flip_evaluator

    err, _, _ = flip_evaluator.evaluate(np.ascontiguousarray(reference_display, np.float32),
                                        np.ascontiguousarray(test_display, np.float32), "LDR",
                                        applyMagma=False, computeMeanError=False)
    return np.asarray(err, np.float64).reshape(reference_display.shape[:2])


def edge_mask(ids: np.ndarray) -> np.ndarray:
    """Pixels whose id differs from one of their 8 neighbours (both sides of a silhouette)."""
    ids = np.asarray(ids)
    p = np.pad(ids, 1, mode="edge")
    h, w = ids.shape
    out = np.zeros((h, w), bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dy or dx:
                out |= p[1 + dy:1 + dy + h, 1 + dx:1 + dx + w] != ids
    return out


def masks(debug: Dict[str, np.ndarray], ground: Sequence[int] = (0,),
          key_light: Optional[Sequence[float]] = None,
          background_drawn: bool = False) -> Dict[str, np.ndarray]:
    """The regions of a frame from weft's ``render_debug`` outputs. Until weft draws the
    environment behind the scene its background is a colour, not the sky, so ``edges`` then
    keep only covered pixels (``edges_all`` has both sides)."""
    ids = np.where(debug["mask"], np.asarray(debug["instance"]), -1)
    if "hair" in debug:
        ids = np.where(np.asarray(debug["hair"]) >= 0, -2 - np.asarray(debug["hair"]), ids)
    covered = ids != -1
    objects = covered & ~np.isin(ids, list(ground))
    out = {"whole": np.ones(ids.shape, bool), "covered": covered, "objects": objects,
           "edges": edge_mask(ids)}
    if not background_drawn:
        out["edges_all"] = out["edges"]
        out["edges"] = out["edges"] & covered
    if key_light is not None:
        ndl = np.asarray(debug["normal"], np.float64) @ np.asarray(key_light, np.float64)
        out["unlit"] = objects & (ndl <= 0.0) & ~out["edges"]
        out["lit"] = objects & (ndl > 0.2) & ~out["edges"]
    return out


def compare(weft_linear: np.ndarray, reference_linear: np.ndarray,
            regions: Dict[str, np.ndarray], exposure: float = 1.0) -> Dict[str, object]:
    """FLIP and relative errors of ``weft_linear`` against ``reference_linear`` (both linear RGB)
    per region: ``flip`` (mean per-pixel FLIP), ``rel`` (sum |dY| / sum Y of the exposed linear
    luminance) and ``bias`` (sum dY / sum Y: < 0 where weft is too dark). Also returns the FLIP
    map and both display images."""
    test_d = to_display(weft_linear, exposure)
    ref_d = to_display(reference_linear, exposure)
    fmap = flip_map(ref_d, test_d)
    yt = np.asarray(weft_linear, np.float64)[..., :3] @ LUMA * exposure
    yr = np.asarray(reference_linear, np.float64)[..., :3] @ LUMA * exposure
    stats: Dict[str, Dict[str, float]] = {}
    for name, m in regions.items():
        if not m.any():
            continue
        denom = max(float(yr[m].sum()), 1e-12)
        stats[name] = {"flip": float(fmap[m].mean()),
                       "rel": float(np.abs(yt[m] - yr[m]).sum() / denom),
                       "bias": float((yt[m] - yr[m]).sum() / denom),
                       "pixels": int(m.sum())}
    return {"regions": stats, "flip_map": fmap, "weft_display": test_d, "reference_display": ref_d}


def side_by_side(weft_display: np.ndarray, reference_display: np.ndarray,
                 fmap: np.ndarray, scale: int = 1) -> np.ndarray:
    """uint8 (H, 3W, 3): weft | reference | FLIP map (magma-like ramp, 0 black .. 1 white)."""
    ramp = np.clip(fmap, 0.0, 1.0)[..., None]
    flip_rgb = np.concatenate([np.sqrt(ramp), ramp ** 1.5, 0.35 * ramp * (1 - ramp) * 4], -1)
    img = np.concatenate([weft_display, reference_display, np.clip(flip_rgb, 0, 1)], axis=1)
    img = (img * 255.0 + 0.5).astype(np.uint8)
    if scale > 1:
        img = img.repeat(scale, axis=0).repeat(scale, axis=1)
    return img
