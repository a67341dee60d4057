"""How weft's lighting units and materials map onto a physically based renderer (Mitsuba 3).

Each mapping is a place where a reference can silently lie, so each is written out here once
and tested (tests/python/render/test_picture_reference.py):

- **Lights.** weft's direct diffuse is ``K_D T (n.l) L`` with ``L = colour * intensity`` (no
  1/pi, glsl/common/shading.glsl). A Lambertian BRDF of albedo ``rho`` gives ``rho / pi * E
  (n.l)``, so with ``rho = K_D T`` a light must bring the irradiance ``E = pi L`` at normal
  incidence: a Mitsuba ``directional`` emitter of ``irradiance = pi L`` and a ``point`` emitter
  of ``intensity = pi L`` (weft's attenuation ``1 / d^2``, i.e. terms (0, 0, 1)).
- **Environment.** weft's environment diffuse is ``K_D T E(n) / pi`` (environment.glsl): exactly
  a Lambertian ``rho = K_D T`` under the radiance, so the environment maps 1:1 (times
  ``Scene.environment_intensity``) when ``environment_diffuse = 1``.
- **Ambient.** weft adds ``I_A K_A T`` without occlusion. The physical reading is a uniform sky of
  radiance ``I_A`` (a ``constant`` emitter): a Lambertian surface under it gets ``K_D T I_A``
  where nothing occludes it, so the two agree only when ``K_A = K_D`` (noted otherwise).
- **Glossy.** weft has two specular terms: a direct highlight and an environment reflection.
  With ``Material.specular_model = 'ggx'`` the highlight is exactly the GGX lobe described below
  (D, Smith masking, the dielectric's Fresnel of F0; shading.glsl ``highlight``) and the
  reflection is weighted by that lobe's directional albedo, so the export is that material.
  The seed's default, ``'blinn_phong'``, is approximated by the same coat: its highlight is
  ``K_S (n.h)^s L`` (no Fresnel, no masking, no n.l, unnormalised) and its reflection ``F(n.v) *
  prefiltered GGX radiance(R)`` with Schlick's ``F0 = reflectivity`` and GGX
  ``alpha = sqrt(2 / (s + 2))`` (environmentRoughness: perceptual roughness sqrt(alpha)), no
  DFG scale, added to an undiminished Lambertian ``K_D T``. The material both approximate is
  that sum: a Lambertian ``K_D T`` plus a GGX microfacet lobe (``alpha``, dielectric Fresnel of
  ``ior = (1 + sqrt F0) / (1 - sqrt F0)``, Smith masking). Mitsuba has no additive BSDF, so it
  is a ``blendbsdf`` of weight w between ``diffuse`` (K_D T / (1 - w)) and ``roughconductor``
  (eta = ior, k = 0: a conductor without absorption has the dielectric's Fresnel; specular
  reflectance 1 / w): (1 - w) f_d + w f_s is exactly the sum. (Mitsuba's ``roughplastic``
  couples the two through the coat's transmission and darkens the base by ~30% at F0 = 0.02:
  a different material, not a better truth.) Without a ``reflectivity`` the lobe's F0 is the
  one whose peak matches weft's highlight at normal incidence: ``f = F0 D(n) / (4 cos^2)``
  with ``D(n) = 1 / (pi alpha^2)`` brings ``F0 / (4 pi alpha^2) * E = F0 L / (4 alpha^2)``
  (E = pi L) against ``K_S L``, so ``F0 = 4 alpha^2 K_S = 8 K_S / (s + 2)`` (weft's 'ggx'
  coat takes the same F0). Known mismatches of 'blinn_phong' (weft's, not the reference's): the
  highlight's shape away from normal incidence and at grazing light (no n.l, Fresnel or GGX
  tail: a sunlit glossy ground ~1% dark), and a reflection without masking / energy (DFG) term,
  too bright at grazing angles.
- **Camera.** weft.Camera's ``fov_y`` is the full vertical angle (glm::perspective): Mitsuba
  ``perspective`` with ``fov_axis = 'y'`` and ``fov = degrees(fov_y)``, ``look_at`` the same
  position / target / up.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Sequence, Tuple

import numpy as np

#: Largest F0 a dielectric coat is given (an IOR of ~39; F0 near 1 is a metal, not a plastic).
MAX_PLASTIC_F0 = 0.9


def blinn_phong_alpha(shininess: float) -> float:
    """GGX alpha that weft pairs with a Blinn-Phong exponent: sqrt(2 / (s + 2)) (environment.glsl
    environmentRoughness returns sqrt of this as the perceptual roughness)."""
    return float(math.sqrt(2.0 / (float(shininess) + 2.0)))


def highlight_f0(ks: float, shininess: float) -> float:
    """F0 of a GGX coat whose highlight peak at normal incidence equals weft's Blinn-Phong
    ``K_S (n.h)^s L`` under the same light: 8 K_S / (s + 2) (derivation in the module doc)."""
    return float(8.0 * float(ks) / (float(shininess) + 2.0))


def ior_from_f0(f0: float) -> float:
    """Relative index of refraction whose normal-incidence Fresnel reflectance is ``f0``."""
    r = math.sqrt(min(max(float(f0), 1e-8), MAX_PLASTIC_F0))
    return (1.0 + r) / (1.0 - r)


def grey(v: Sequence[float]) -> float:
    """The mean of an RGB triple (Mitsuba's coat has one scalar IOR)."""
    return float(np.mean(np.asarray(v, np.float64)))


@dataclass
class Notes:
    """Where an export is approximate: one line per mismatch, shown in reports."""
    lines: List[str] = field(default_factory=list)

    def add(self, line: str) -> None:
        if line not in self.lines:
            self.lines.append(line)


def material_bsdf(material, notes: Notes, label: str = "") -> dict:
    """Mitsuba BSDF dict of a weft.Material (untextured): ``diffuse`` of ``K_D * base_color``
    without any specular, else :func:`sum_bsdf` (see the module doc). Two-sided materials are
    wrapped in ``twosided``."""
    from weft._core import InvalidArgument

    if material.texture is not None or material.normal_map is not None \
            or material.specular_map is not None or material.ambient_map is not None:
        raise InvalidArgument(f"{label}: textured materials are not exported to Mitsuba (only "
                              "constant K_D, K_S, base_color, reflectivity)")
    if material.phantom or material.gloss_in_alpha or material.dynamic_reflection:
        raise InvalidArgument(f"{label}: phantom / gloss_in_alpha / dynamic_reflection materials "
                              "have no Mitsuba equivalent")
    albedo = np.asarray(material.kd, np.float64) * np.asarray(material.base_color, np.float64)
    if np.any(albedo > 1.0):
        notes.add(f"{label}: K_D T > 1 ({tuple(albedo)}) is not energy conserving; Mitsuba clamps "
                  "nothing but a path tracer's bounce light then grows without bound")
    reflectivity = np.asarray(material.reflectivity, np.float64)
    ks = grey(material.ks)
    if np.any(reflectivity > 0.0):
        f0 = grey(reflectivity)
        if np.ptp(reflectivity) > 1e-6:
            notes.add(f"{label}: coloured reflectivity {tuple(reflectivity)} exported as its mean "
                      f"F0 {f0:.3f} (one IOR)")
    elif ks > 0.0:
        f0 = highlight_f0(ks, material.shininess)
    else:
        f0 = 0.0
    albedo = np.clip(albedo, 0.0, None)
    if f0 <= 0.0:
        bsdf = {"type": "diffuse", "reflectance": _rgb(albedo)}
    else:
        if f0 > MAX_PLASTIC_F0:
            notes.add(f"{label}: F0 {f0:.3f} clamped to {MAX_PLASTIC_F0} for a dielectric lobe")
        bsdf = sum_bsdf(albedo, f0, blinn_phong_alpha(material.shininess), notes, label)
    if material.two_sided:
        bsdf = {"type": "twosided", "material": bsdf}
    return bsdf


def _rgb(value) -> dict:
    return {"type": "rgb", "value": [float(c) for c in value]}


def sum_bsdf(albedo: np.ndarray, f0: float, alpha: float, notes: Notes, label: str = "") -> dict:
    """Lambertian ``albedo`` + GGX lobe (``alpha``, dielectric Fresnel of ``f0``), summed: a
    ``blendbsdf`` of weight w between diffuse(albedo / (1 - w)) and an absorption-free
    roughconductor of specular reflectance 1 / w (Mitsuba checks RGB reflectances against 1,
    so w leaves the diffuse part <= 1 and the lobe's scale is a uniform spectrum)."""
    peak = float(np.max(albedo))
    w = float(np.clip(1.0 - peak, 0.05, 0.5))
    diffuse = albedo / (1.0 - w)
    if np.any(diffuse > 1.0):
        notes.add(f"{label}: K_D T {tuple(albedo)} clamped to {1.0 - w:.2f} beside its GGX lobe")
        diffuse = np.minimum(diffuse, 1.0)
    return {"type": "blendbsdf", "weight": w,
            "bsdf_0": {"type": "diffuse", "reflectance": _rgb(diffuse)},
            "bsdf_1": {"type": "roughconductor", "distribution": "ggx", "alpha": float(alpha),
                       "eta": ior_from_f0(f0), "k": 0.0,
                       "specular_reflectance": {"type": "uniform", "value": 1.0 / w}}}


def light_emitter(light, notes: Notes, label: str = "") -> dict:
    """Mitsuba emitter dict of a weft light: irradiance / intensity pi * colour * intensity."""
    import weft
    from weft._core import InvalidArgument

    radiance = np.asarray(light.color, np.float64) * float(light.intensity)
    value = {"type": "rgb", "value": [float(c) for c in math.pi * radiance]}
    if isinstance(light, weft.DirectionalLight):
        d = np.asarray(light.direction, np.float64)
        return {"type": "directional", "direction": [float(c) for c in d / np.linalg.norm(d)],
                "irradiance": value}
    if isinstance(light, weft.PointLight):
        if float(light.radius) > 0.0 or tuple(light.attenuation) != (0.0, 0.0, 1.0):
            notes.add(f"{label}: point light attenuation {tuple(light.attenuation)} / radius "
                      f"{light.radius} exported as physical 1/d^2")
        return {"type": "point", "position": [float(c) for c in light.position],
                "intensity": value}
    raise InvalidArgument(f"{label}: {type(light).__name__} is not exported to Mitsuba "
                          "(directional and point lights only)")


def sensor_fov_degrees(fov_y: float) -> float:
    """Mitsuba's ``fov`` (degrees, with fov_axis 'y') of weft.Camera.fov_y (radians, full)."""
    return float(math.degrees(float(fov_y)))


def look_at(camera) -> Tuple[List[float], List[float], List[float]]:
    """(origin, target, up) of a weft.Camera, as lists."""
    return ([float(c) for c in camera.position], [float(c) for c in camera.target],
            [float(c) for c in camera.up])
