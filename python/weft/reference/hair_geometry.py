"""NumPy references for the hair geometry of SPEC §5.1: .hair bytes (written and parsed with
``struct``/NumPy from shared/formats/hair.md), strand tangents, camera-facing ribbons and fur
grown from a mesh (002 listing 1 with weft's per-strand variation), independent of the C++.
"""

from __future__ import annotations

import struct
from typing import Dict, Optional, Sequence

import numpy as np

from weft.reference.hair import hash32, unit_random

HEADER = struct.Struct("<4sIIIIff3f88s")


def hair_bytes(points: np.ndarray, segments: Optional[np.ndarray] = None,
               thickness: Optional[np.ndarray] = None, transparency: Optional[np.ndarray] = None,
               colors: Optional[np.ndarray] = None, default_segments: int = 0,
               strands: Optional[int] = None, flags_extra: int = 0, info: bytes = b"") -> bytes:
    """A .hair file. ``strands`` defaults to len(segments) or P / (default_segments + 1)."""
    points = np.asarray(points, dtype="<f4").reshape(-1, 3)
    flags = 2 | flags_extra
    arrays = []
    if segments is not None:
        flags |= 1
        arrays.append(np.asarray(segments, dtype="<u2").tobytes())
    arrays.append(points.tobytes())
    for bit, arr in ((4, thickness), (8, transparency), (16, colors)):
        if arr is not None:
            flags |= bit
            arrays.append(np.asarray(arr, dtype="<f4").tobytes())
    if strands is None:
        strands = len(segments) if segments is not None else len(points) // (default_segments + 1)
    header = HEADER.pack(b"HAIR", strands, len(points), flags, default_segments, 1.0, 0.0,
                         1.0, 1.0, 1.0, info.ljust(88, b"\0"))
    return header + b"".join(arrays)


def parse_hair_bytes(data: bytes) -> Dict[str, np.ndarray]:
    """The arrays of a well-formed .hair file (no validation: a reference for round trips)."""
    sig, strands, count, flags, dseg, dthick, dtrans, r, g, b, info = HEADER.unpack_from(data)
    assert sig == b"HAIR"
    pos = HEADER.size
    out: Dict[str, np.ndarray] = {"flags": np.array(flags), "default_segments": np.array(dseg)}
    if flags & 1:
        out["segments"] = np.frombuffer(data, "<u2", strands, pos)
        pos += 2 * strands
    for bit, name, width in ((2, "points", 3), (4, "thickness", 1), (8, "transparency", 1),
                             (16, "colors", 3)):
        if flags & bit:
            arr = np.frombuffer(data, "<f4", count * width, pos)
            out[name] = arr.reshape(count, 3) if width == 3 else arr
            pos += 4 * count * width
    return out


def _strand_ranges(offsets: Sequence[int]):
    return [(int(offsets[s]), int(offsets[s + 1])) for s in range(len(offsets) - 1)]


def tangents(points: np.ndarray, offsets: Sequence[int]) -> np.ndarray:
    """Central-difference unit tangents; fallback tip - root, then (0, 1, 0)."""
    p = np.asarray(points, dtype=np.float64)
    out = np.zeros_like(p)
    for a, b in _strand_ranges(offsets):
        whole = p[b - 1] - p[a]
        n = np.linalg.norm(whole)
        whole = whole / n if n > 1e-12 else np.array([0.0, 1.0, 0.0])
        idx = np.arange(a, b)
        d = p[np.minimum(idx + 1, b - 1)] - p[np.maximum(idx - 1, a)]
        length = np.linalg.norm(d, axis=1, keepdims=True)
        out[a:b] = np.where(length > 1e-12, d / np.maximum(length, 1e-300), whole)
    return out


def ribbons(points: np.ndarray, offsets: Sequence[int], thickness: np.ndarray,
            eye: Sequence[float], width_scale: float) -> np.ndarray:
    """(2P, 3): p -/+ s w/2 with s = unit(t x (eye - p))."""
    p = np.asarray(points, dtype=np.float64)
    t = tangents(p, offsets)
    s = np.cross(t, np.asarray(eye, dtype=np.float64) - p)
    s /= np.linalg.norm(s, axis=1, keepdims=True)
    half = s * (0.5 * width_scale * np.asarray(thickness, dtype=np.float64))[:, None]
    out = np.empty((2 * len(p), 3))
    out[0::2] = p - half
    out[1::2] = p + half
    return out


def _srgb_to_linear(c: np.ndarray) -> np.ndarray:
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def sample_bilinear(image: np.ndarray, uv: np.ndarray) -> np.ndarray:
    """Linear RGB of an sRGB uint8 image at uv (repeat, texel centres, v = 0 top row)."""
    img = image if image.ndim == 3 else image[:, :, None]
    h, w = img.shape[:2]
    lin = _srgb_to_linear(img[:, :, :3].astype(np.float64) / 255.0)
    if lin.shape[2] == 1:
        lin = np.repeat(lin, 3, axis=2)
    x, y = uv[0] * w - 0.5, uv[1] * h - 0.5
    fx, fy = np.floor(x), np.floor(y)
    tx, ty = x - fx, y - fy
    out = np.zeros(3)
    for dy in (0, 1):
        for dx in (0, 1):
            c = lin[int(fy + dy) % h, int(fx + dx) % w]
            out += c * (tx if dx else 1 - tx) * (ty if dy else 1 - ty)
    return out


def _basis(n: np.ndarray):
    sign = 1.0 if n[2] >= 0 else -1.0
    a = -1.0 / (sign + n[2])
    b = n[0] * n[1] * a
    return (np.array([1 + sign * n[0] ** 2 * a, sign * b, -sign * n[0]]),
            np.array([b, sign + n[1] ** 2 * a, -n[1]]))


def _random(seed: int, index: int, channel: int) -> float:
    """Uniform [0, 1) of the C++ generators: hash(hash(seed) ^ (index * 8 + channel))."""
    mixed = int(hash32(np.array([seed]))[0]) ^ ((index * 8 + channel) & 0xFFFFFFFF)
    return float(unit_random(np.array([mixed]))[0])


def fur(positions: np.ndarray, normals: np.ndarray, uvs: np.ndarray, indices: np.ndarray,
        level: int = 1, segments: int = 10, length: float = 0.3, length_jitter: float = 0.0,
        direction_jitter: float = 0.0, down: Sequence[float] = (0.0, -0.5, 0.0),
        texture: Optional[np.ndarray] = None, seed: int = 1):
    """Fur points (S * (segments + 1), 3) and per-strand colours (S, 3) or None."""
    tris = np.asarray(indices).reshape(-1, 3)
    down = np.asarray(down, dtype=np.float64)
    seg_len = length / segments
    pts, cols = [], []
    strand = 0
    for i0, i1, i2 in tris:
        p = np.asarray(positions, np.float64)[[i0, i1, i2]]
        nrm = np.asarray(normals, np.float64)[[i0, i1, i2]]
        uv = np.asarray(uvs, np.float64)[[i0, i1, i2]]
        subs = []
        for inverted, third in ((0, 1 / 3), (1, 2 / 3)):
            rows = level - inverted
            for j in range(rows):
                for i in range(rows - j):
                    subs.append(((i + third) / level, (j + third) / level))
        for b1, b2 in subs:
            w = np.array([1 - b1 - b2, b1, b2])
            root = w @ p
            n = w @ nrm
            n = n / np.linalg.norm(n)
            d = n.copy()
            if direction_jitter > 0:
                e1, e2 = _basis(n)
                tilt = direction_jitter * _random(seed, strand, 0)
                spin = 2 * np.pi * _random(seed, strand, 1)
                d = np.cos(tilt) * n + np.sin(tilt) * (np.cos(spin) * e1 + np.sin(spin) * e2)
            ln = seg_len * (1 + length_jitter * (2 * _random(seed, strand, 2) - 1))
            strand_pts = [root]
            for _ in range(segments):
                strand_pts.append(strand_pts[-1] + d * ln)
                d = d + down * ln
            pts.extend(strand_pts)
            if texture is not None:
                cols.append(sample_bilinear(texture, w @ uv))
            strand += 1
    return np.array(pts), (np.array(cols) if texture is not None else None)


__all__ = ["fur", "hair_bytes", "parse_hair_bytes", "ribbons", "sample_bilinear", "tangents"]
