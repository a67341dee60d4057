"""NumPy (float64) reference of the hair shading models of SPEC §5.2.

Written from the equations, independently of ``glsl/common/hair_shading.glsl``: angles from
``arcsin``/``arccos`` instead of ``atan2``, Fresnel from the angle form of Fresnel's equations,
Marschner's azimuthal roots from the eigenvalues of the cubic's companion matrix instead of the
closed trigonometric/hyperbolic forms. Conventions (shared with the GLSL)::

    sin(theta_i) = l.t, sin(theta_o) = v.t, theta_h = (theta_i + theta_o) / 2,
    theta_d = (theta_o - theta_i) / 2, phi in [0, pi] between l and v projected onto the
    plane normal to t (pi/2 when a projection vanishes, |proj| < 1e-6)
    f = diffuse * sin(t, l) + specular of the model

- Kajiya-Kay: ``specular * max(0, cos(theta_i + theta_o)) ** shininess`` - the cosine of the
  angle between v and the cone of mirror directions of l; with l in the normal plane it is the
  angle between v and that plane (seed eq. 3).
- Marschner et al. 2003: ``sum_p M_p(theta_h) N_p(phi) / cos^2(theta_d)``, unit-area Gaussians
  ``M_p = g(beta_p; theta_h - alpha_p)``; ``N_R = F(eta', cos(phi/2)) cos(phi/2) / 4``; N_TT and
  N_TRT sum ``A(p, h) x / (x^2 + eps^2)``, x = |2 dphi/dh|, over the offsets h = sin(gamma) with
  ``(6pc/pi - 2) gamma - 8pc/pi^3 gamma^3 + p pi = phi (mod 2 pi)``, c = asin(1/eta'),
  eta' = sqrt(eta^2 - sin^2 theta_d) / cos theta_d, ``A(1, h) = (1 - F)^2 T``,
  ``A(2, h) = (1 - F)^2 F T^2``, ``T = exp(-2 sigma_a / cos(theta_t) (1 + cos 2 gamma_t))``,
  sin(theta_t) = sin(theta_d) / eta, sin(gamma_t) = h / eta', F unpolarised Fresnel with eta'.
  eps (``caustic_width``) regularises the TRT caustics: 1/x away from them, zero instead of
  infinite where two paths merge, so N is continuous in phi.
- Sadeghi et al. 2010: ``sum_p C_p I_p M'_p(theta_h) N'_p(phi) / cos^2(theta_d)`` with
  unit-height Gaussians, ``N'_R = cos(phi/2)``, ``N'_TT = g'(xi_TT; pi - phi)``,
  ``N'_TRT = cos(phi/2) + I_g g'(xi_g; G - phi)``, G per strand in [min, max] from
  :func:`glint_angle`.

``1 / cos^2(theta_d)`` uses ``max(cos^2(theta_d), MIN_COS2)``.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any, Optional, Tuple

import numpy as np

MIN_COS2 = 1e-3
MODELS = ("kajiya_kay", "marschner", "sadeghi")
Vec3 = Tuple[float, float, float]


@dataclass
class HairParams:
    """The fields of ``weft.HairMaterial`` (same names and defaults, radians)."""

    model: str = "sadeghi"
    diffuse: Vec3 = (0.0, 0.0, 0.0)
    specular: Vec3 = (0.3, 0.3, 0.3)
    shininess: float = 80.0
    shift: Vec3 = (np.radians(-5.0), np.radians(2.5), np.radians(7.5))
    width: Vec3 = (np.radians(7.0), np.radians(3.5), np.radians(14.0))
    eta: float = 1.55
    absorption: Vec3 = (0.2, 0.35, 0.6)
    caustic_width: float = 0.2
    color_r: Vec3 = (1.0, 1.0, 1.0)
    color_tt: Vec3 = (0.9, 0.6, 0.3)
    color_trt: Vec3 = (0.8, 0.5, 0.25)
    intensity: Vec3 = (1.0, 1.0, 1.0)
    tt_azimuthal_width: float = np.radians(10.0)
    glint_intensity: float = 0.5
    glint_width: float = np.radians(5.0)
    glint_angle_min: float = np.radians(30.0)
    glint_angle_max: float = np.radians(45.0)

    @classmethod
    def from_material(cls, material: Any) -> "HairParams":
        """Copies every field from a ``weft.HairMaterial`` (or any object with the names)."""
        return cls(**{f.name: getattr(material, f.name) for f in fields(cls)})


def hash32(x: np.ndarray) -> np.ndarray:
    """The integer hash of the hair subsystem (uint32 in, uint32 out)."""
    x = np.asarray(x, dtype=np.uint32).copy()
    with np.errstate(over="ignore"):
        x ^= x >> np.uint32(16)
        x *= np.uint32(0x7FEB352D)
        x ^= x >> np.uint32(15)
        x *= np.uint32(0x846CA68B)
        x ^= x >> np.uint32(16)
    return x


def unit_random(x: np.ndarray) -> np.ndarray:
    """Uniform [0, 1) from the top 24 bits of hash32(x)."""
    return (hash32(x) >> np.uint32(8)).astype(np.float64) / 16777216.0


def glint_angle(p: HairParams, strand_ids: np.ndarray) -> np.ndarray:
    """Sadeghi's per-strand glint half-angle G in [glint_angle_min, glint_angle_max]."""
    u = unit_random(strand_ids)
    return p.glint_angle_min + (p.glint_angle_max - p.glint_angle_min) * u


def _unit(a: np.ndarray) -> np.ndarray:
    a = np.asarray(a, dtype=np.float64)
    return a / np.linalg.norm(a, axis=-1, keepdims=True)


def angles(t: np.ndarray, l: np.ndarray, v: np.ndarray) -> dict:
    """theta_i, theta_o, theta_h, theta_d, phi and sin(t, l) for (N,3) directions."""
    t, l, v = _unit(t), _unit(l), _unit(v)
    sin_i = np.clip(np.sum(l * t, axis=-1), -1.0, 1.0)
    sin_o = np.clip(np.sum(v * t, axis=-1), -1.0, 1.0)
    lp = l - sin_i[:, None] * t
    vp = v - sin_o[:, None] * t
    nl, nv = np.linalg.norm(lp, axis=-1), np.linalg.norm(vp, axis=-1)
    degenerate = (nl < 1e-6) | (nv < 1e-6)
    denom = np.where(degenerate, 1.0, nl * nv)
    cos_phi = np.clip(np.sum(lp * vp, axis=-1) / denom, -1.0, 1.0)
    phi = np.where(degenerate, np.pi / 2, np.arccos(cos_phi))
    theta_i, theta_o = np.arcsin(sin_i), np.arcsin(sin_o)
    return dict(theta_i=theta_i, theta_o=theta_o, theta_h=(theta_i + theta_o) / 2,
                theta_d=(theta_o - theta_i) / 2, phi=phi, sin_tl=np.sqrt(1.0 - sin_i ** 2))


def _inv_cos2(theta_d: np.ndarray) -> np.ndarray:
    return 1.0 / np.maximum(np.cos(theta_d) ** 2, MIN_COS2)


def kajiya_kay(p: HairParams, a: dict) -> np.ndarray:
    """Kajiya-Kay specular (N,3)."""
    c = np.maximum(np.cos(a["theta_i"] + a["theta_o"]), 0.0)
    return np.outer(c ** p.shininess, p.specular)


def gauss_unit_height(width: float, x: np.ndarray) -> np.ndarray:
    return np.exp(-0.5 * (x / width) ** 2)


def sadeghi(p: HairParams, a: dict, strand_ids: np.ndarray) -> np.ndarray:
    """Sadeghi et al. 2010 specular (N,3)."""
    th, phi = a["theta_h"], a["phi"]
    m = [gauss_unit_height(p.width[k], th - p.shift[k]) for k in range(3)]
    n_r = np.cos(phi / 2)
    n_tt = gauss_unit_height(p.tt_azimuthal_width, np.pi - phi)
    n_trt = n_r + p.glint_intensity * gauss_unit_height(p.glint_width,
                                                         glint_angle(p, strand_ids) - phi)
    lobes = [(p.color_r, p.intensity[0], m[0] * n_r), (p.color_tt, p.intensity[1], m[1] * n_tt),
             (p.color_trt, p.intensity[2], m[2] * n_trt)]
    f = sum(np.outer(value * i, c) for c, i, value in lobes)
    return f * _inv_cos2(a["theta_d"])[:, None]


def fresnel(eta: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    """Unpolarised Fresnel reflectance at incidence angle gamma (angle form of Fresnel's
    equations; total internal reflection cannot happen for eta > 1 from outside)."""
    eta = np.broadcast_to(np.asarray(eta, dtype=np.float64), np.shape(gamma))
    gi = np.abs(np.asarray(gamma, dtype=np.float64))
    gt = np.arcsin(np.sin(gi) / eta)
    normal = ((eta - 1) / (eta + 1)) ** 2
    small = gi < 1e-6
    gi_s = np.where(small, 0.5, gi)
    gt_s = np.where(small, np.arcsin(np.sin(0.5) / eta), gt)
    rs = np.sin(gi_s - gt_s) / np.sin(gi_s + gt_s)
    with np.errstate(divide="ignore", invalid="ignore"):
        rp = np.tan(gi_s - gt_s) / np.tan(gi_s + gt_s)
    rp = np.where(np.abs(gi_s + gt_s - np.pi / 2) < 1e-12, 0.0, rp)  # Brewster angle
    return np.where(small, normal, 0.5 * (rs ** 2 + rp ** 2))


def _real_cubic_roots(a: np.ndarray, b: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Real roots of a x^3 + b x + d (N,3), NaN where a root is complex."""
    n = a.shape[0]
    comp = np.zeros((n, 3, 3))
    comp[:, 0, 1] = -b / a
    comp[:, 0, 2] = -d / a
    comp[:, 1, 0] = 1.0
    comp[:, 2, 1] = 1.0
    ev = np.linalg.eigvals(comp)
    return np.where(np.abs(ev.imag) <= 1e-7 * np.maximum(1.0, np.abs(ev.real)), ev.real, np.nan)


def marschner_n(p: HairParams, lobe: int, phi: np.ndarray, eta_p: np.ndarray,
                cos_theta_t: np.ndarray) -> np.ndarray:
    """Marschner's azimuthal N_p (N,3) for lobe 1 (TT) or 2 (TRT)."""
    c = np.arcsin(1.0 / eta_p)
    a = -8.0 * lobe * c / np.pi ** 3
    b = 6.0 * lobe * c / np.pi - 2.0
    target = phi + 2.0 * np.pi * (lobe - 1)  # the branch of phi(p, gamma) that reaches phi
    roots = _real_cubic_roots(a, b, lobe * np.pi - target)
    sigma = np.asarray(p.absorption, dtype=np.float64)[None, :] / cos_theta_t[:, None]
    out = np.zeros((phi.shape[0], 3))
    for k in range(3):
        g = roots[:, k]
        ok = np.isfinite(g) & (np.abs(g) <= np.pi / 2)
        g = np.where(ok, g, 0.0)
        h = np.sin(g)
        gt = np.arcsin(np.clip(h / eta_p, -1.0, 1.0))
        f = fresnel(eta_p, g)
        tr = np.exp(-2.0 * sigma * (1.0 + np.cos(2.0 * gt))[:, None])
        att = ((1.0 - f) ** 2)[:, None] * tr
        if lobe == 2:
            att = att * f[:, None] * tr
        dphi_dgamma = 3.0 * a * g ** 2 + b
        dphi_dh = dphi_dgamma / np.maximum(np.cos(g), 1e-6)
        x = 2.0 * np.abs(dphi_dh)
        weight = x / (x ** 2 + p.caustic_width ** 2)
        out += np.where(ok[:, None], att * weight[:, None], 0.0)
    return out


def marschner(p: HairParams, a: dict) -> np.ndarray:
    """Marschner et al. 2003 specular (N,3)."""
    td, th, phi = a["theta_d"], a["theta_h"], a["phi"]
    cos_d = np.sqrt(np.maximum(np.cos(td) ** 2, MIN_COS2))
    eta_p = np.sqrt(p.eta ** 2 - np.sin(td) ** 2) / cos_d
    cos_theta_t = np.sqrt(1.0 - (np.sin(td) / p.eta) ** 2)

    def m(k: int) -> np.ndarray:
        return gauss_unit_height(p.width[k], th - p.shift[k]) / (p.width[k] * np.sqrt(2 * np.pi))

    n_r = fresnel(eta_p, phi / 2) * np.cos(phi / 2) / 4.0
    f = (m(0) * n_r)[:, None] * np.ones(3)
    f = f + m(1)[:, None] * marschner_n(p, 1, phi, eta_p, cos_theta_t)
    f = f + m(2)[:, None] * marschner_n(p, 2, phi, eta_p, cos_theta_t)
    return f * _inv_cos2(td)[:, None]


def shade(p: HairParams, t: np.ndarray, l: np.ndarray, v: np.ndarray,
          strand_ids: Optional[np.ndarray] = None) -> np.ndarray:
    """f (N,3) float64 for tangents t, light and view directions l, v (N,3)."""
    t = np.atleast_2d(np.asarray(t, dtype=np.float64))
    l = np.atleast_2d(np.asarray(l, dtype=np.float64))
    v = np.atleast_2d(np.asarray(v, dtype=np.float64))
    ids = np.zeros(t.shape[0], dtype=np.uint32) if strand_ids is None else \
        np.asarray(strand_ids, dtype=np.uint32)
    a = angles(t, l, v)
    f = np.outer(a["sin_tl"], p.diffuse)
    if p.model == "kajiya_kay":
        return f + kajiya_kay(p, a)
    if p.model == "marschner":
        return f + marschner(p, a)
    if p.model == "sadeghi":
        return f + sadeghi(p, a, ids)
    raise ValueError(f"unknown hair model {p.model!r}")


def directions_for(theta_i: np.ndarray, theta_o: np.ndarray,
                   phi: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Unit (t, l, v) with the given angles (t = +X, l in the XY plane): for sweeps."""
    theta_i, theta_o, phi = np.broadcast_arrays(np.asarray(theta_i, float),
                                                np.asarray(theta_o, float), np.asarray(phi, float))
    n = theta_i.size
    t = np.tile([1.0, 0.0, 0.0], (n, 1))
    l = np.stack([np.sin(theta_i), np.cos(theta_i), np.zeros(n)], axis=-1).reshape(n, 3)
    v = np.stack([np.sin(theta_o), np.cos(theta_o) * np.cos(phi), np.cos(theta_o) * np.sin(phi)],
                 axis=-1).reshape(n, 3)
    return t, l, v


__all__ = ["HairParams", "MODELS", "MIN_COS2", "angles", "directions_for", "fresnel",
           "glint_angle", "hash32", "kajiya_kay", "marschner", "marschner_n", "sadeghi", "shade",
           "unit_random"]
