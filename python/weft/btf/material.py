"""BtfMaterial: the fitted per-texel reflectance model the renderer consumes (SPEC §3.5).

``P = albedo * (ambient + d(n.l)) + specular * max(n_s.h, 0)^exponent`` with ``d(x) = x`` (the
seed's linear model) or ``max(x, 0)`` (``clamp_diffuse``), ``h = normalize(l + v)`` and
``n_s = n`` or ``(0, 0, 1)`` (``flat_specular_normal``, seed eq. 4.30). Maps are float32
(H, W, 3); ``exponent_map`` (H, W) overrides the scalar ``exponent`` per texel.

Saved as a folder: ``material.json`` (scalars, map list, value ranges), one EXR per map (exact
floats) and an 8-bit PNG preview per map (normals encoded ``(n + 1) / 2``, SPEC §1.4).
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from typing import Any, Dict, Optional

import numpy as np

import weft

FORMAT = "weft-btf-material"
VERSION = 1
_MAPS = ("normal", "albedo", "ambient", "specular", "exponent_map")


@dataclass
class BtfMaterial:
    normal: np.ndarray
    albedo: np.ndarray
    ambient: np.ndarray
    specular: Optional[np.ndarray] = None
    exponent: float = 1.0
    exponent_map: Optional[np.ndarray] = None
    flat_specular_normal: bool = False
    clamp_diffuse: bool = False

    def __post_init__(self) -> None:
        self.validate()

    @property
    def shape(self) -> tuple:
        return tuple(self.normal.shape[:2])

    def validate(self) -> None:
        """Raises weft.InvalidArgument for wrong shapes, NaN/inf, non-unit normals or a bad
        exponent; converts maps to C-contiguous float32."""
        h, w = np.shape(self.normal)[:2] if np.ndim(self.normal) == 3 else (0, 0)
        for name in _MAPS:
            value = getattr(self, name)
            if value is None:
                if name in ("normal", "albedo", "ambient"):
                    raise weft.InvalidArgument(f"material map {name!r} is required")
                continue
            arr = np.ascontiguousarray(value, dtype=np.float32)
            want = (h, w) if name == "exponent_map" else (h, w, 3)
            if arr.shape != want or h == 0 or w == 0:
                raise weft.InvalidArgument(f"material map {name!r} must have shape {want}, "
                                           f"got {arr.shape}")
            if not np.all(np.isfinite(arr)):
                raise weft.InvalidArgument(f"material map {name!r} must be finite")
            setattr(self, name, arr)
        lengths = np.linalg.norm(self.normal, axis=-1)
        if np.any(np.abs(lengths - 1.0) > 1e-3):
            raise weft.InvalidArgument("material normals must have unit length")
        exps = [self.exponent] + ([] if self.exponent_map is None else [self.exponent_map])
        for e in exps:
            arr = np.asarray(e)
            if not np.all(np.isfinite(arr)) or np.any(arr < 0) or np.any(arr > 1e6):
                raise weft.InvalidArgument("specular exponents must lie in [0, 1e6]")
        self.exponent = float(self.exponent)

    def core_maps(self) -> Dict[str, Any]:
        """The dict the compiled functions take."""
        return dict(normal=self.normal, albedo=self.albedo, ambient=self.ambient,
                    specular=self.specular, exponent=self.exponent,
                    exponent_map=self.exponent_map,
                    flat_specular_normal=self.flat_specular_normal,
                    clamp_diffuse=self.clamp_diffuse)

    @classmethod
    def from_core(cls, maps: Dict[str, Any]) -> "BtfMaterial":
        return cls(**maps)

    def __repr__(self) -> str:
        h, w = self.shape
        if self.specular is None:
            spec = "none"
        elif self.exponent_map is not None:
            spec = "per-texel exponent"
        else:
            spec = f"exponent {self.exponent:g}"
        ns = "(0,0,1)" if self.flat_specular_normal else "n"
        return (f"<weft.BtfMaterial {w}x{h} specular {spec}, n_s={ns}, "
                f"{'clamped' if self.clamp_diffuse else 'linear'} diffuse>")

    def render_material(self) -> "weft.Material":
        """The renderer's material for these maps (SPEC §3.5). It draws
        ``albedo * (ambient + max(n.l, 0)) + specular * max(n_s.h, 0)^e`` with the specular term
        only where n.l > 0 (``clamp_diffuse`` semantics, whatever the flag says), from linear
        8-bit mipmapped textures, each holding value / scale rounded to 1/255 with one scale
        per channel = the map's maximum (so values above 1 are drawn; negative ones as 0):

        - ``albedo`` -> base texture T with K_D = its scale;
        - ``albedo * ambient`` (the constant term) -> the ambient map as radiance
          (``ambient_map_is_radiance``: not multiplied by T or the scene's ambient), K_A = scale;
        - ``specular`` -> the specular map's RGB with K_S = scale (none: K_S = 0), the scale
          at most 4x the channel's 99th percentile of non-zero values (rare outliers clipped);
        - ``exponent`` -> shininess; ``exponent_map`` -> the specular map's alpha, log-encoded
          between its minimum and maximum over texels with a non-zero specular texel
          (``shininess_max``); exponents below 1e-3 are drawn as 1e-3;
        - ``normal`` -> tangent-space normal map ((x / s, y / s, z) + 1) / 2 with
          ``normal_scale`` s = the largest |x|, |y| (at least 1e-3; x right, y up in the image,
          as the fit's frame), decoded (2 texel - 1) * (s, s, 1) and renormalised;
        - ``flat_specular_normal`` -> the highlight from the vertex normal (eq. 4.30).

        :meth:`as_drawn` returns exactly these quantised values as a BtfMaterial."""

        from weft._core import btf_render_material

        return btf_render_material(self.core_maps())

    def as_drawn(self) -> "BtfMaterial":
        """The material exactly as :meth:`render_material` draws it at texel centres: every map
        quantised as its texture holds it (scales as above), normals decoded and renormalised,
        ``clamp_diffuse = True``, the exponent (map) as the shader decodes it. The drawn albedo
        and constant term are exact; the ambient is their ratio (where the drawn albedo is 0
        but the constant term is not, albedo = 1e-30 and ambient = term / 1e-30). Its
        reconstruction (:func:`weft.btf.sample_errors`) is what the renderer draws, up to
        texture filtering between texels and float rounding."""
        from weft._core import btf_drawn_maps

        return BtfMaterial.from_core(btf_drawn_maps(self.core_maps()))

    def save(self, folder: str) -> None:
        """Writes the folder (created if needed): material.json, <map>.exr, <map>.png."""
        os.makedirs(folder, exist_ok=True)
        meta: Dict[str, Any] = {"format": FORMAT, "version": VERSION,
                                "width": self.shape[1], "height": self.shape[0],
                                "exponent": self.exponent,
                                "flat_specular_normal": self.flat_specular_normal,
                                "clamp_diffuse": self.clamp_diffuse, "maps": {}}
        for name in _MAPS:
            value = getattr(self, name)
            if value is None:
                continue
            weft.save_exr(os.path.join(folder, f"{name}.exr"), value)
            weft.save_png(os.path.join(folder, f"{name}.png"), preview(name, value))
            meta["maps"][name] = {"exr": f"{name}.exr", "png": f"{name}.png",
                                  "min": float(value.min()), "max": float(value.max())}
        with open(os.path.join(folder, "material.json"), "w", encoding="utf-8") as f:
            json.dump(meta, f, indent=2)

    @classmethod
    def load(cls, folder: str) -> "BtfMaterial":
        """Reads a folder written by :meth:`save`; raises weft.IoError for a missing or malformed
        folder and weft.InvalidArgument for inconsistent maps."""
        path = os.path.join(folder, "material.json")
        try:
            with open(path, encoding="utf-8") as f:
                meta = json.load(f)
        except (OSError, ValueError) as exc:
            raise weft.IoError(f"cannot read BTF material {path!r}: {exc}") from None
        if not isinstance(meta, dict) or meta.get("format") != FORMAT or \
                meta.get("version") != VERSION or not isinstance(meta.get("maps"), dict):
            raise weft.IoError(f"{path!r} is not a {FORMAT} version {VERSION} file")
        kwargs: Dict[str, Any] = {}
        for name, entry in meta["maps"].items():
            if name not in _MAPS or not isinstance(entry, dict) or "exr" not in entry:
                raise weft.IoError(f"{path!r}: unknown or malformed map entry {name!r}")
            image = weft.load_exr(os.path.join(folder, os.path.basename(str(entry["exr"]))))
            kwargs[name] = image[..., 0] if name == "exponent_map" else image[..., :3]
        try:
            return cls(exponent=float(meta.get("exponent", 1.0)),
                       flat_specular_normal=bool(meta.get("flat_specular_normal", False)),
                       clamp_diffuse=bool(meta.get("clamp_diffuse", False)), **kwargs)
        except TypeError as exc:
            raise weft.IoError(f"{path!r}: {exc}") from None


def preview(name: str, value: np.ndarray) -> np.ndarray:
    """8-bit preview of a map: normals as (n + 1) / 2, others scaled by their maximum."""
    if name == "normal":
        img = (value + 1.0) * 0.5
    else:
        top = float(np.max(np.abs(value))) or 1.0
        img = np.clip(value / top, 0.0, 1.0)
    return np.clip(np.rint(img * 255.0), 0, 255).astype(np.uint8)
