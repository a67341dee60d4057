"""The reference scene set of issue 18: each builds a weft.Scene + weft.Camera that weft renders
as it is and :mod:`~weft.reference.picture.mitsuba_export` exports for the path tracer.

- ``spheres_sky``: a diffuse and a glossy sphere on a ground plane under the synthetic sky, lit
  the way ``weft.scenes.light_with_environment`` lights a scene (SH9 diffuse, GGX reflections,
  16 dome shadow lights);
- ``spheres_sun``: the same under the sky with a sun, the sun split off as a directional light
  with a shadow map (``sun_lights=1``, weft's best path for a sun);
- ``cloth``: ``weft.scenes.cloth_scene`` (cloth draped over a sphere, a sun with its shadow and
  a constant ambient, read as a uniform sky and drawn as the background by both);
- ``dome``: a sphere floating over the ground under the sky: the ground's soft shadow comes from
  the dome of shadow lights alone.

Materials are written so that both renderers mean the same thing (conventions.py): glossy ones
are GGX coats (``Material.specular_model = 'ggx'``) of ``reflectivity = F0`` (or, in the cloth
scene's materials, the F0 of their ``ks``), so that weft's highlight and its reflection are the
coat the reference draws, and ``ka = kd`` so that the ambient is a sky's light.
(With the seed's Blinn-Phong specular, matched to the coat at its peak, the cloth scene scored
FLIP 0.044 against 0.037 as a coat: its highlight lacks the GGX tail, ~1% of a sunlit ground's
light, and its Schlick-weighted reflection makes a glossy sphere's rim glow.)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, Optional, Sequence, Tuple

import numpy as np

#: Names of the reference scenes, in report order.
SCENES: Tuple[str, ...] = ("spheres_sky", "spheres_sun", "cloth", "dome")
#: Cube size of the reference skies (weft's default specular chain size).
SKY_SIZE = 64


@dataclass
class ReferenceScene:
    """A built reference scene: what both renderers draw and how to judge it."""
    name: str
    scene: object
    camera: object
    #: instance ids of the ground (the rest are "objects" in the masks)
    ground: Tuple[int, ...] = (0,)
    #: scale applied to both linear images before clamp + sRGB
    exposure: float = 1.0
    #: direction *towards* the key light, for the lit / unlit split of the objects (None: none)
    key_light: Optional[Tuple[float, float, float]] = None
    #: whether weft draws the environment as its background (Scene.set_environment keyword)
    background_drawn: bool = False
    description: str = ""
    #: the truth's environment (cube faces) when weft lights with less of it (a split-off sun)
    reference_environment: Optional[np.ndarray] = None
    #: whether the truth has the weft scene's lights (False: they are weft's split-off sun)
    reference_lights: bool = True
    settings: Dict[str, object] = field(default_factory=dict)


def glossy_material(kd: Sequence[float], f0: float, shininess: float, **kw):
    """A weft.Material whose highlight and environment reflection are one GGX coat of ``f0``
    (``ks`` the coat's Blinn-Phong equivalent, for ``specular_model='blinn_phong'`` in ``kw``)."""
    import weft

    kw.setdefault("specular_model", "ggx")
    return weft.Material(ka=kd, kd=kd, ks=(f0 * (shininess + 2.0) / 8.0,) * 3,
                         shininess=shininess, reflectivity=(f0,) * 3, **kw)


def diffuse_material(kd: Sequence[float], **kw):
    import weft

    return weft.Material(ka=kd, kd=kd, ks=(0.0,) * 3, **kw)


def _translate(x: float, y: float, z: float, scale: float = 1.0) -> np.ndarray:
    m = np.eye(4, dtype=np.float32)
    m[:3, :3] *= scale
    m[:3, 3] = (x, y, z)
    return m


def _ground_and_spheres(floating: bool = False):
    import weft

    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(10.0, 10.0, 4, 4), diffuse_material((0.5, 0.5, 0.48)),
                   cast_shadows=False)
    sphere = weft.Mesh.uv_sphere(1.0, 64, 32)
    if floating:
        scene.add_mesh(sphere, diffuse_material((0.7, 0.7, 0.7)),
                       transform=_translate(0.0, 0.95, 0.0, 0.45))
        camera = weft.Camera(position=(0.0, 1.9, 3.4), target=(0.0, 0.45, 0.0), fov_y=0.8)
    else:
        scene.add_mesh(sphere, diffuse_material((0.7, 0.32, 0.2)),
                       transform=_translate(-0.6, 0.5, 0.0, 0.5))
        scene.add_mesh(sphere, glossy_material((0.15, 0.3, 0.6), 0.04, 400.0),
                       transform=_translate(0.6, 0.5, 0.0, 0.5))
        camera = weft.Camera(position=(0.0, 1.3, 3.3), target=(0.0, 0.45, 0.0), fov_y=0.7)
    scene.ambient = (0.0, 0.0, 0.0)
    return scene, camera


def _set_environment(scene, faces: np.ndarray, **kw) -> bool:
    """light_with_environment, then the environment drawn as background where weft can (the
    keyword is being added to Scene.set_environment); returns whether it is drawn."""
    import weft.ibl
    import weft.scenes

    env = weft.scenes.light_with_environment(scene, weft.ibl.CubeMap(faces), **kw)
    try:
        scene.set_environment(env, dome_lights=kw.get("dome_lights", 16),
                              dome_blur=kw.get("dome_blur", 4.0), background=True)
        return True
    except TypeError:
        return False


def build(name: str, dome_lights: int = 16, specular_samples: Optional[int] = None,
          cloth_steps: int = 180) -> ReferenceScene:
    """Builds reference scene ``name`` (one of :data:`SCENES`). ``dome_lights`` and
    ``specular_samples`` (the GGX prefilter's samples, None: weft's default) are weft settings
    the benchmark varies; the Mitsuba reference does not depend on them."""
    import weft
    import weft.scenes
    from weft._core import InvalidArgument
    from weft.reference.picture.environment import SUN_DIRECTION, sky_faces

    settings: Dict[str, object] = {"dome_lights": dome_lights}
    if name in ("spheres_sky", "spheres_sun", "dome"):
        scene, camera = _ground_and_spheres(floating=(name == "dome"))
        sun = name == "spheres_sun"
        kw = dict(dome_lights=dome_lights, sun_lights=1 if sun else 0)
        faces = sky_faces(SKY_SIZE, sun=sun)
        drawn = _set_environment(scene, faces, **kw)
        if specular_samples is not None:
            env = scene.environment
            scene.set_environment(env, dome_lights=dome_lights, dome_blur=4.0,
                                  specular_samples=int(specular_samples),
                                  **({"background": True} if drawn else {}))
            settings["specular_samples"] = int(specular_samples)
        descriptions = {
            "spheres_sky": "diffuse + glossy spheres on a ground plane under a sky",
            "spheres_sun": "the same under a sky with a sun (split off as a shadowed light)",
            "dome": "a sphere floating over the ground under a sky (dome shadows)"}
        return ReferenceScene(name, scene, camera, ground=(0,), exposure=1.0,
                              key_light=tuple(SUN_DIRECTION) if sun else None,
                              background_drawn=drawn, description=descriptions[name],
                              reference_environment=faces if sun else None,
                              reference_lights=not sun, settings=settings)
    if name == "cloth":
        scene, camera, cloth = weft.scenes.cloth_scene(resolution=32, steps=cloth_steps)
        for i in range(scene.instance_count):
            m = scene.material(i)
            m.ka = m.kd  # the ambient as a sky's light (see the module doc)
            m.specular_model = "ggx"  # ... and its specular the reference's coat
            scene.set_material(i, m)
        # ... and that uniform sky is what both show behind the scene
        scene.background = scene.ambient
        light = scene.lights[0]
        d = -np.asarray(light.direction, np.float64)
        return ReferenceScene(name, scene, camera, ground=(0,), exposure=1.0,
                              key_light=tuple(d / np.linalg.norm(d)),
                              description="cloth over a sphere, a sun with its shadow, ambient",
                              settings={"cloth_steps": cloth_steps})
    raise InvalidArgument(f"unknown reference scene {name!r}; known: {', '.join(SCENES)}")
