"""NumPy reference ("oracle") for weft's per-pixel shading and shadow test, in float64.

Everything here is written from the equations of SPEC §1.3 and §1.5 and never calls the
renderer: it takes the debug outputs of a frame (world position, shading normal, UV, coverage
and shadow visibility, see ``Renderer.render_debug``) plus a description of the scene, and
recomputes what every covered pixel must look like.

Shading (SPEC §1.3, eq. 2.5, 2.8, 2.9 and 2.10), per pixel with position p, unit normal n,
camera position c, ``v = normalize(c - p)`` and ``T = base_color * texture(uv)``::

    colour = I_A * K_A * T
    for each light, l and L from :func:`incident` (SPEC §1.2):
        directional: l = -normalize(direction), L = color * intensity
        point:       l = normalize(x_L - p), L = color * intensity * a(|x_L - p|) with
                     a(d) = 1 / (k_c + k_l d + k_q d^2) (eq. 2.3) or max(0, 1 - d^2/r^2) (eq. 2.4)
        spot:        as point, times smoothstep(cos outer, cos inner, -l . axis) and the cookie
                     texture (bilinear, clamped, level 0) at the point's projection on the cone
        if n.l > 0:
            h = normalize(l + v)                             # eq. 2.8
            I_D = (n.l) L                                    # eq. 2.5
            I_S = max(n.h, 0)^shininess L                    # eq. 2.9
            colour += vis * (I_D K_D T + I_S K_S)            # eq. 2.10, a = 1

``vis`` is the PCF shadow visibility of the light (1 for lights without shadows). A debug frame
reports it for the first shadow-casting light; others can be computed with
:func:`pcf_visibility` from their shadow maps.

Shadows (SPEC §1.5): the receiver is offset along its normal, projected into the light's
clip space, and compared against a (2r+1)^2 texel neighbourhood of the shadow map with a
slope-scaled, clamped depth bias; see :func:`shadow_lookup`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, Iterable, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from weft.reference.texture import (
    _bilinear_clamp,
    build_mip_chain,
    encode_u8,
    sample_bilinear_repeat,
    sample_trilinear_repeat,
    texture_lod,
    texture_to_linear,
)

ArrayLike = Union[np.ndarray, Sequence[float], float]
Vec3 = Tuple[float, float, float]

__all__ = ["LightDesc", "SurfaceMaterial", "as_light", "attenuation", "incident", "spot_basis",
           "first_shadow_light", "material_maps", "blinn_phong", "shade_debug_frame",
           "OracleErrors", "compare_frame"]


# --------------------------------------------------------------------------------------------
# Scene description
# --------------------------------------------------------------------------------------------

def _vec3(value: Any, name: str) -> np.ndarray:
    arr = np.asarray(value, dtype=np.float64).reshape(-1)
    if arr.size == 1:
        arr = np.repeat(arr, 3)
    if arr.shape != (3,):
        raise ValueError(f"{name} must be a 3-vector, got {value!r}")
    return arr


@dataclass(frozen=True)
class LightDesc:
    """A light as the oracle needs it (SPEC §1.2): ``kind`` is "directional", "point" or
    "spot".

    ``direction`` points from the light into the scene (directional: the vector towards the
    light is ``l = -normalize(direction)``; spot: the cone's axis); the radiance is
    ``L = color * intensity`` times the attenuation of point and spot lights
    (``attenuation`` = (k_c, k_l, k_q), or the radius form when ``radius > 0``), the spot cone
    (``inner_angle``/``outer_angle``, half-angles in radians) and the spot's ``cookie`` (an
    image as ``weft.Texture`` takes it; ``cookie_srgb`` says whether uint8 texels are sRGB).
    """

    direction: Vec3 = (0.0, -1.0, 0.0)
    color: Vec3 = (1.0, 1.0, 1.0)
    intensity: float = 1.0
    cast_shadows: bool = True
    kind: str = "directional"
    position: Vec3 = (0.0, 0.0, 0.0)
    attenuation: Vec3 = (1.0, 0.0, 0.0)
    radius: float = 0.0
    inner_angle: float = 0.35
    outer_angle: float = 0.5
    cookie: Optional[np.ndarray] = field(default=None, compare=False)
    cookie_srgb: bool = True

    def to_light(self) -> np.ndarray:
        """Unit vector from the surface towards the light, ``l``."""
        d = _vec3(self.direction, "direction")
        norm = np.linalg.norm(d)
        if not np.isfinite(norm) or norm == 0.0:
            raise ValueError(f"light direction must be finite and non-zero, got {self.direction}")
        return -d / norm

    def radiance(self) -> np.ndarray:
        """``L = color * intensity`` (RGB)."""
        return _vec3(self.color, "color") * float(self.intensity)


def as_light(light: Any) -> LightDesc:
    """Accepts a :class:`LightDesc`, a ``weft.DirectionalLight``/``PointLight``/``SpotLight``
    (or any object with their attributes) or a dict with those keys (``kind`` defaults to
    the class name, else "directional")."""
    if isinstance(light, LightDesc):
        return light
    if isinstance(light, Mapping):
        get = light.get
        kind = str(get("kind", "directional"))
    else:
        def get(key: str, default: Any = None) -> Any:
            return getattr(light, key, default)
        name = type(light).__name__
        kind = {"PointLight": "point", "SpotLight": "spot"}.get(name, get("kind", "directional"))
    if kind not in ("directional", "point", "spot"):
        raise ValueError(f"unknown light kind {kind!r}")
    cookie = get("cookie", None)
    cookie_srgb = bool(getattr(cookie, "srgb", True))
    if cookie is not None and not isinstance(cookie, np.ndarray):
        cookie = np.asarray(cookie.image)  # a weft.Texture
    return LightDesc(
        direction=tuple(_vec3(get("direction", (0.0, -1.0, 0.0)), "direction")),
        color=tuple(_vec3(get("color", (1.0, 1.0, 1.0)), "color")),
        intensity=float(get("intensity", 1.0)),
        cast_shadows=bool(get("cast_shadows", True)),
        kind=kind,
        position=tuple(_vec3(get("position", (0.0, 0.0, 0.0)), "position")),
        attenuation=tuple(_vec3(get("attenuation", (1.0, 0.0, 0.0)), "attenuation")),
        radius=float(get("radius", 0.0)),
        inner_angle=float(get("inner_angle", 0.35)),
        outer_angle=float(get("outer_angle", 0.5)),
        cookie=cookie,
        cookie_srgb=bool(get("cookie_srgb", cookie_srgb)),
    )


def attenuation(light: LightDesc, distance: ArrayLike) -> np.ndarray:
    """a(d) of a point or spot light: eq. 2.4 when ``radius > 0``, else eq. 2.3."""
    d = np.asarray(distance, dtype=np.float64)
    if light.radius > 0.0:
        return np.maximum(0.0, 1.0 - d * d / (light.radius * light.radius))
    kc, kl, kq = light.attenuation
    return 1.0 / (kc + kl * d + kq * d * d)


def spot_basis(axis: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
    """The (right, up) vectors spanning a spot light's cookie, from its unit axis."""
    a = _vec3(axis, "axis")
    a = a / np.linalg.norm(a)
    ref = np.array([0.0, 0.0, 1.0]) if abs(a[1]) > 0.99 else np.array([0.0, 1.0, 0.0])
    right = np.cross(a, ref)
    right /= np.linalg.norm(right)
    return right, np.cross(right, a)


def _smoothstep(e0: float, e1: float, x: np.ndarray) -> np.ndarray:
    t = np.clip((x - e0) / (e1 - e0), 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def _sample_bilinear_clamp(image: np.ndarray, uv: np.ndarray) -> np.ndarray:
    """Bilinear lookup with clamp-to-edge addressing at normalised uv (texel centres at
    (i + 0.5) / size)."""
    h, w = image.shape[:2]
    return _bilinear_clamp(image, uv[..., 0] * w, uv[..., 1] * h)


def incident(light: Any, position: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Unit vectors ``l`` towards the light and the radiance ``L`` arriving at ``position``
    (..., 3), both (..., 3): colour * intensity times attenuation, spot cone and cookie."""
    lt = as_light(light)
    p = np.asarray(position, dtype=np.float64)
    base = lt.radiance()
    if lt.kind == "directional":
        return np.broadcast_to(lt.to_light(), p.shape).copy(), np.broadcast_to(base, p.shape).copy()
    d = _vec3(lt.position, "position") - p
    dist = np.linalg.norm(d, axis=-1)
    l = d / np.maximum(dist, 1e-20)[..., None]
    radiance = base * attenuation(lt, dist)[..., None]
    if lt.kind == "spot":
        axis = _vec3(lt.direction, "direction")
        axis = axis / np.linalg.norm(axis)
        cos_angle = -np.einsum("...k,k->...", l, axis)
        radiance = radiance * _smoothstep(np.cos(lt.outer_angle), np.cos(lt.inner_angle),
                                          cos_angle)[..., None]
        if lt.cookie is not None:
            right, up = spot_basis(axis)
            q = p - _vec3(lt.position, "position")
            with np.errstate(divide="ignore", invalid="ignore"):
                z = np.einsum("...k,k->...", q, axis) * np.tan(lt.outer_angle)
                uv = 0.5 + 0.5 * np.stack([np.einsum("...k,k->...", q, right),
                                           -np.einsum("...k,k->...", q, up)],
                                          axis=-1) / z[..., None]
            front = cos_angle > 0.0
            uv = np.where(front[..., None], uv, 0.5)
            cookie = texture_to_linear(lt.cookie, lt.cookie_srgb)[:, :, :3]
            radiance = np.where(front[..., None], radiance * _sample_bilinear_clamp(cookie, uv),
                                radiance)
    return l, radiance


def first_shadow_light(lights: Iterable[Any]) -> Optional[int]:
    """Index of the first light with ``cast_shadows`` (the one whose visibility the renderer
    reports in ``render_debug()["shadow"]``), or None."""
    for i, light in enumerate(lights):
        if as_light(light).cast_shadows:
            return i
    return None


@dataclass
class SurfaceMaterial:
    """Blinn-Phong material of SPEC eq. 2.10 with an optional base-colour texture.

    ``texture`` is the *image* the ``weft.Texture`` was made from (uint8, any shape
    ``weft.Texture`` accepts) or a float image that is already linear; ``texture_srgb`` says
    whether uint8 texels are sRGB-encoded. ``T = base_color * texture(uv)``, white without a
    texture. Textures are sampled bilinearly at level 0 (exact for ``mipmaps=False``), or, with
    ``texture_mipmaps`` and a per-pixel LOD, trilinearly from a mip chain built like the GPU's.
    """

    ka: Vec3 = (1.0, 1.0, 1.0)
    kd: Vec3 = (1.0, 1.0, 1.0)
    ks: Vec3 = (0.0, 0.0, 0.0)
    shininess: float = 32.0
    base_color: Vec3 = (1.0, 1.0, 1.0)
    texture: Optional[np.ndarray] = None
    texture_srgb: bool = True
    texture_mipmaps: bool = False
    _linear: Optional[np.ndarray] = field(default=None, init=False, repr=False, compare=False)
    _levels: Optional[List[np.ndarray]] = field(default=None, init=False, repr=False,
                                                compare=False)

    @classmethod
    def from_weft(cls, material: Any, texture_image: Optional[np.ndarray] = None,
                  texture_srgb: Optional[bool] = None,
                  texture_mipmaps: Optional[bool] = None) -> "SurfaceMaterial":
        """Copies the coefficients of a ``weft.Material`` (or any object with the same
        attributes). The texture's image defaults to ``material.texture.image``; pass
        ``texture_image`` (the array the ``weft.Texture`` was made from) otherwise.
        ``texture_srgb``/``texture_mipmaps`` default to the texture's ``srgb``/``mipmaps``
        (True/False where it does not say)."""
        tex = getattr(material, "texture", None)
        if texture_image is None and tex is not None:
            texture_image = getattr(tex, "image", None)
            if texture_image is None:
                raise ValueError("the material has a texture but no image was given; pass "
                                 "texture_image= (the array the weft.Texture was made from)")
        if texture_srgb is None:
            texture_srgb = bool(getattr(tex, "srgb", True)) if tex is not None else True
        if texture_mipmaps is None:
            texture_mipmaps = bool(getattr(tex, "mipmaps", False)) if tex is not None else False
        return cls(ka=tuple(_vec3(material.ka, "ka")), kd=tuple(_vec3(material.kd, "kd")),
                   ks=tuple(_vec3(material.ks, "ks")), shininess=float(material.shininess),
                   base_color=tuple(_vec3(material.base_color, "base_color")),
                   texture=None if texture_image is None else np.asarray(texture_image),
                   texture_srgb=texture_srgb,
                   texture_mipmaps=texture_mipmaps and texture_image is not None)

    @property
    def texture_size(self) -> Optional[Tuple[int, int]]:
        """(width, height) of the texture, None without one."""
        if self.texture is None:
            return None
        shape = np.shape(self.texture)
        return int(shape[1]), int(shape[0])

    def albedo(self, uv: np.ndarray, lod: Optional[ArrayLike] = None) -> np.ndarray:
        """``T = base_color * texture(uv)`` for uv (..., 2) -> (..., 3) linear RGB.

        Without ``lod`` (or without mipmaps) the texture is sampled bilinearly at level 0;
        with a ``lod`` per sample (see :func:`texture_lod`) and ``texture_mipmaps`` it is
        sampled trilinearly from :func:`build_mip_chain`.
        """
        uv = np.asarray(uv, dtype=np.float64)
        base = _vec3(self.base_color, "base_color")
        if self.texture is None:
            return np.broadcast_to(base, uv.shape[:-1] + (3,)).copy()
        if self._linear is None:
            self._linear = texture_to_linear(self.texture, self.texture_srgb)
        if lod is None or not self.texture_mipmaps:
            return base * sample_bilinear_repeat(self._linear[:, :, :3], uv)
        if self._levels is None:
            self._levels = [lvl[:, :, :3] for lvl in build_mip_chain(self._linear,
                                                                     self.texture_srgb)]
        return base * sample_trilinear_repeat(self._levels, uv, lod)


def material_maps(materials: Sequence[SurfaceMaterial], labels: np.ndarray,
                  uv: np.ndarray, mip_lod: bool = False,
                  lod_bias: float = 0.0) -> Dict[str, np.ndarray]:
    """Per-pixel material arrays from a label image.

    ``labels`` (H, W) integer: index into ``materials`` per pixel, negative = no material
    (those pixels get zeros). Returns ``ka``, ``kd``, ``ks``, ``albedo`` (H, W, 3) and
    ``shininess`` (H, W), float64, ready for :func:`blinn_phong`. With ``mip_lod``, textures
    that have mipmaps are sampled at the LOD :func:`texture_lod` estimates from ``uv``
    (which must then be the whole (H, W, 2) UV image), plus ``lod_bias``.
    """
    labels = np.asarray(labels)
    uv = np.asarray(uv, dtype=np.float64)
    shape = labels.shape
    out = {key: np.zeros(shape + (3,)) for key in ("ka", "kd", "ks", "albedo")}
    out["shininess"] = np.ones(shape)
    if labels.size and labels.max(initial=-1) >= len(materials):
        raise ValueError(f"label {int(labels.max())} but only {len(materials)} materials")
    for index, mat in enumerate(materials):
        sel = labels == index
        if not np.any(sel):
            continue
        out["ka"][sel] = _vec3(mat.ka, "ka")
        out["kd"][sel] = _vec3(mat.kd, "kd")
        out["ks"][sel] = _vec3(mat.ks, "ks")
        out["shininess"][sel] = float(mat.shininess)
        lod = None
        if mip_lod and mat.texture_mipmaps and mat.texture is not None:
            tw, th = mat.texture_size  # type: ignore[misc]
            lod = texture_lod(uv, labels, tw, th)[sel] + lod_bias
        out["albedo"][sel] = mat.albedo(uv[sel], lod)
    return out


# --------------------------------------------------------------------------------------------
# Shading
# --------------------------------------------------------------------------------------------

def _normalize(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(n > 0.0, n, 1.0)


def blinn_phong(position: np.ndarray, normal: np.ndarray, camera_position: ArrayLike,
                lights: Sequence[Any], ambient: ArrayLike, *, albedo: np.ndarray,
                ka: ArrayLike = 1.0, kd: ArrayLike = 1.0, ks: ArrayLike = 0.0,
                shininess: ArrayLike = 32.0,
                shadow: Union[None, ArrayLike, Mapping[int, ArrayLike]] = None) -> np.ndarray:
    """Blinn-Phong radiance of SPEC §1.3 (eq. 2.5, 2.8, 2.9, 2.10) for directional, point and
    spot lights (see :func:`incident`).

    Parameters
    ----------
    position, normal:
        (..., 3) world position and *unit* shading normal per pixel (the normal is used as
        given, like the renderer's debug output).
    camera_position:
        (3,) eye position; ``v = normalize(camera_position - position)``.
    lights:
        sequence of lights (anything :func:`as_light` accepts), in scene order.
    ambient:
        ``I_A`` (RGB).
    albedo:
        (..., 3) ``T = base_color * texture(uv)``.
    ka, kd, ks, shininess:
        material coefficients, broadcastable to (..., 3) (``shininess`` to (...)).
    shadow:
        (...) visibility of the first shadow-casting light (e.g. ``render_debug()["shadow"]``
        or :func:`pcf_visibility`), or a mapping {light index: (...) visibility} for any
        lights; None means fully lit. Lights without an entry are not shadowed.

    Returns (..., 3) float64 linear radiance, not clamped.
    """
    p = np.asarray(position, dtype=np.float64)
    n = np.asarray(normal, dtype=np.float64)
    t = np.asarray(albedo, dtype=np.float64)
    lead = p.shape[:-1]
    v = _normalize(np.asarray(camera_position, dtype=np.float64).reshape(3) - p)

    def coefficient(value: ArrayLike) -> Union[np.ndarray, float]:
        if np.ndim(value) == 0:
            return float(value)  # type: ignore[arg-type]
        return np.broadcast_to(np.asarray(value, dtype=np.float64), lead + (3,))

    ka, kd, ks = coefficient(ka), coefficient(kd), coefficient(ks)
    shin = np.asarray(shininess, dtype=np.float64)
    colour = _vec3(ambient, "ambient") * ka * t
    if shadow is None:
        visibility: Dict[int, np.ndarray] = {}
    elif isinstance(shadow, Mapping):
        visibility = {int(k): np.asarray(v, dtype=np.float64)[..., None]
                      for k, v in shadow.items()}
    else:
        first = first_shadow_light(lights)
        visibility = {} if first is None else {
            first: np.asarray(shadow, dtype=np.float64)[..., None]}
    for index, raw in enumerate(lights):
        l, radiance = incident(raw, p)
        ndl = np.einsum("...k,...k->...", n, l)
        lit = ndl > 0.0
        h = _normalize(l + v)
        ndh = np.maximum(np.einsum("...k,...k->...", n, h), 0.0)
        spec = np.power(ndh, shin)
        term = (np.maximum(ndl, 0.0)[..., None] * radiance * kd * t
                + spec[..., None] * radiance * ks)
        term = np.where(lit[..., None], term, 0.0)
        if index in visibility:
            term = term * visibility[index]
        colour = colour + term
    return colour


# --------------------------------------------------------------------------------------------
# Whole frames
# --------------------------------------------------------------------------------------------

def shade_debug_frame(debug: Mapping[str, np.ndarray], camera_position: ArrayLike,
                      lights: Sequence[Any], ambient: ArrayLike, background: ArrayLike,
                      materials: Union[SurfaceMaterial, Sequence[SurfaceMaterial]],
                      labels: Optional[np.ndarray] = None,
                      shadow: Union[None, np.ndarray, Mapping[int, np.ndarray]] = None,
                      mip_lod: bool = True,
                      lod_bias: float = 0.0,
                      frame_albedo: bool = False) -> np.ndarray:
    """Recomputes a frame's linear RGBA image (H, W, 4) from its ``render_debug`` outputs.

    ``debug`` needs ``position``, ``normal``, ``uv``, ``mask`` and (unless ``shadow`` is
    given) ``shadow``; ``shadow`` overrides the visibility as in :func:`blinn_phong` (e.g. a
    {light index: visibility} mapping for several shadow-casting lights). ``materials`` is one
    material for every covered pixel, or a list indexed by ``labels`` (H, W) (defaults to
    ``debug["instance"]`` when the frame has one). Uncovered pixels get ``(background, 1)``;
    covered pixels ``(blinn_phong(...), 1)``
    (SPEC §1.3 eq. 2.5, 2.8–2.10; shadows §1.5). Mip-mapped textures are sampled trilinearly
    at the LOD estimated from the frame's UV derivatives (``mip_lod``; see
    :func:`texture_lod` for where that is approximate; ``lod_bias`` is added to it), others
    bilinearly at level 0. With ``frame_albedo`` the texture term T is taken from the frame's
    ``albedo`` output instead: the oracle then checks the shading equation alone, free of the
    sampler's implementation-defined precision (tested separately against NumPy sampling).
    """
    mask = np.asarray(debug["mask"], dtype=bool)
    uv = np.asarray(debug["uv"], dtype=np.float64)
    if isinstance(materials, SurfaceMaterial):
        mats: List[SurfaceMaterial] = [materials]
        labels = np.where(mask, 0, -1)
    else:
        mats = list(materials)
        if labels is None:
            if "instance" not in debug:
                raise ValueError("several materials need a label image (labels= or "
                                 "debug['instance'])")
            labels = np.asarray(debug["instance"])
        labels = np.where(mask, np.asarray(labels), -1)
        if np.any(mask & (labels < 0)):
            raise ValueError(f"{int(np.sum(mask & (labels < 0)))} covered pixels have no material")
    maps = material_maps(mats, labels, uv, mip_lod=mip_lod, lod_bias=lod_bias)
    vis = debug["shadow"] if shadow is None else shadow
    albedo = np.asarray(debug["albedo"], dtype=np.float64) if frame_albedo else maps["albedo"]
    colour = blinn_phong(debug["position"], debug["normal"], camera_position, lights, ambient,
                         albedo=albedo, ka=maps["ka"], kd=maps["kd"], ks=maps["ks"],
                         shininess=maps["shininess"], shadow=vis)
    out = np.ones(mask.shape + (4,), dtype=np.float64)
    out[..., :3] = np.where(mask[..., None], colour, _vec3(background, "background"))
    return out


class OracleErrors(NamedTuple):
    """How far a rendered frame is from the oracle, over the compared pixels (RGB)."""

    max_abs: float        # max |linear - oracle|
    mean_abs: float       # mean |linear - oracle|
    p99_abs: float        # 99th percentile of the per-pixel max |linear - oracle|
    max_u8: int           # max |color - encode_u8(oracle)| in 8-bit levels
    u8_over_1: float      # fraction of pixels more than one 8-bit level off
    covered: int          # number of pixels compared

    def as_dict(self) -> Dict[str, float]:
        return dict(self._asdict())


# The renderer keeps linear radiance in half floats (RGBA16F: 11 significant bits), and Vulkan
# lets a float -> half conversion round to nearest or toward zero: a linear value v reads back
# within LINEAR_STORAGE_RTOL * |v| of the float the shader computed (one half-float ulp).
LINEAR_STORAGE_RTOL = 2.0 ** -10


def storage_excess(linear: np.ndarray, oracle: np.ndarray) -> np.ndarray:
    """|linear - oracle| beyond the half-float storage rounding of the oracle's value (>= 0)."""
    oracle = np.asarray(oracle, dtype=np.float64)
    diff = np.abs(np.asarray(linear, dtype=np.float64) - oracle)
    return np.maximum(diff - LINEAR_STORAGE_RTOL * np.abs(oracle), 0.0)


def compare_frame(debug: Mapping[str, np.ndarray], oracle_linear: np.ndarray,
                  mask: Optional[np.ndarray] = None) -> OracleErrors:
    """Compares ``debug["linear"]`` and ``debug["color"]`` with the oracle's linear image on
    ``mask`` (default: the covered pixels, ``debug["mask"]``)."""
    if mask is None:
        mask = np.asarray(debug["mask"], dtype=bool)
    oracle = np.asarray(oracle_linear, dtype=np.float64)[..., :3][mask]
    linear = np.asarray(debug["linear"], dtype=np.float64)[..., :3][mask]
    color = np.asarray(debug["color"])[..., :3][mask].astype(np.int64)
    if oracle.size == 0:
        return OracleErrors(0.0, 0.0, 0.0, 0, 0.0, 0)
    diff = np.abs(linear - oracle)
    u8 = np.abs(color - encode_u8(oracle).astype(np.int64)).max(axis=-1)
    return OracleErrors(max_abs=float(diff.max()), mean_abs=float(diff.mean()),
                        p99_abs=float(np.percentile(diff.max(axis=-1), 99.0)),
                        max_u8=int(u8.max()), u8_over_1=float(np.mean(u8 > 1)),
                        covered=int(np.count_nonzero(mask)))
