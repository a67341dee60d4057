"""A weft.Scene + weft.Camera as a Mitsuba 3 scene (``mi.load_dict``, variant ``scalar_rgb``),
and its render: the independent, path-traced truth for weft's picture.

What is exported (conventions.py says how each unit maps): mesh instances (object -> world
transforms applied to positions and normals here), cloth instances (their current world-space
mesh, two-sided), untextured diffuse / glossy materials, directional and point lights, the
scene's environment (weft.ibl.Environment radiance times its intensity, as an ``envmap``) and
the constant ambient (as a ``constant`` sky). Textures, spot lights and hair raise
weft.InvalidArgument; approximations are listed in the returned :class:`Export`'s notes.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

import numpy as np

from weft.reference.picture import conventions as conv
from weft.reference.picture.environment import cube_to_equirect

VARIANT = "scalar_rgb"
#: Path length limit of the reference: enough bounces that the rest is far below FLIP's
#: threshold for the albedos used (<= 0.75: 0.75^12 ~ 3%, and Russian roulette is unbiased).
MAX_DEPTH = 12


def import_mitsuba():
    """Mitsuba 3 with the scalar RGB variant set (the LLVM variants need an LLVM this machine's
    Debian does not provide). Raises ImportError when it is not installed."""
    import mitsuba as mi

    if mi.variant() != VARIANT:
        mi.set_variant(VARIANT)
    return mi


@dataclass
class Export:
    """A Mitsuba scene dict and what in it only approximates weft's model."""
    scene: Dict[str, Any]
    notes: List[str] = field(default_factory=list)


def _mesh_arrays(scene, index: int):
    """World-space positions, normals (N, 3) and triangles (M, 3) of instance ``index``."""
    mesh = scene.mesh(index)
    if mesh is None:
        cloth = scene.cloth(index)
        data = cloth.mesh()  # world space already
        return (np.asarray(data["positions"], np.float64), np.asarray(data["normals"], np.float64),
                np.asarray(data["indices"], np.uint32).reshape(-1, 3))
    m = np.asarray(scene.transform(index), np.float64)
    p = np.asarray(mesh.positions, np.float64)
    n = np.asarray(mesh.normals, np.float64)
    p = p @ m[:3, :3].T + m[:3, 3]
    n = n @ np.linalg.inv(m[:3, :3])  # inverse transpose, applied to row vectors
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
    return p, n, np.asarray(mesh.indices, np.uint32).reshape(-1, 3)


def _mitsuba_mesh(mi, name: str, positions, normals, triangles, bsdf: dict):
    props = mi.Properties()
    props["bsdf"] = mi.load_dict(bsdf)
    mesh = mi.Mesh(name, len(positions), len(triangles), props=props, has_vertex_normals=True)
    params = mi.traverse(mesh)
    params["vertex_positions"] = np.ascontiguousarray(positions, np.float32).ravel()
    params["vertex_normals"] = np.ascontiguousarray(normals, np.float32).ravel()
    params["faces"] = np.ascontiguousarray(triangles, np.uint32).ravel()
    params.update()
    return mesh


def environment_emitter(mi, faces: np.ndarray, intensity: float = 1.0,
                        width: Optional[int] = None) -> dict:
    """An ``envmap`` emitter of weft cube faces (6, S, S, 3) world-space radiance."""
    bitmap = cube_to_equirect(faces, width)
    return {"type": "envmap", "bitmap": mi.Bitmap(bitmap), "scale": float(intensity)}


def sensor(mi, camera, width: int, height: int, spp: int, seed: int = 0) -> dict:
    """Mitsuba's perspective sensor for a weft.Camera: vertical fov, box pixel filter (the
    true pixel-area average: an anti-aliased reference, no blur across pixels)."""
    origin, target, up = conv.look_at(camera)
    return {"type": "perspective", "fov_axis": "y", "fov": conv.sensor_fov_degrees(camera.fov_y),
            "near_clip": float(camera.near), "far_clip": float(camera.far),
            "to_world": mi.ScalarTransform4f().look_at(origin=origin, target=target, up=up),
            "sampler": {"type": "independent", "sample_count": int(spp), "seed": int(seed)},
            "film": {"type": "hdrfilm", "width": int(width), "height": int(height),
                     "rfilter": {"type": "box"}, "pixel_format": "rgb"}}


def export_scene(scene, camera, width: int, height: int, spp: int = 64,
                 integrator: str = "path", seed: int = 0, max_depth: int = MAX_DEPTH,
                 environment: Optional[np.ndarray] = None, lights: bool = True) -> Export:
    """The Mitsuba scene dict of a weft scene seen by ``camera`` on a ``width`` x ``height``
    film. ``integrator``: 'path' (full global illumination) or 'direct' (one bounce of direct
    light and environment: what weft computes without its ambient approximations).
    ``environment`` (cube faces, world radiance) replaces the scene's own and ``lights=False``
    leaves the scene's lights out: the truth of a sky whose sun weft split off as a light is
    the sky with its sun."""
    from weft._core import InvalidArgument

    if integrator not in ("path", "direct"):
        raise InvalidArgument(f"integrator must be 'path' or 'direct', got {integrator!r}")
    if getattr(scene, "hair_count", 0):
        raise InvalidArgument("hair is not exported to Mitsuba (no matching fibre model)")
    mi = import_mitsuba()
    notes = conv.Notes()
    d: Dict[str, Any] = {"type": "scene"}
    d["integrator"] = ({"type": "path", "max_depth": int(max_depth)} if integrator == "path"
                       else {"type": "direct"})
    d["sensor"] = sensor(mi, camera, width, height, spp, seed)
    if environment is None and scene.environment is not None:
        environment = (np.asarray(scene.environment.radiance.faces, np.float64)
                       * float(scene.environment_intensity))
    for i in range(int(scene.instance_count)):
        material = scene.material(i)
        label = f"instance {i}"
        bsdf = conv.material_bsdf(material, notes, label)
        if scene.cloth(i) is not None and bsdf["type"] != "twosided":
            bsdf = {"type": "twosided", "material": bsdf}  # cloth is always drawn two-sided
        if environment is not None and material.environment_diffuse not in (0.0, 1.0):
            notes.add(f"{label}: environment_diffuse {material.environment_diffuse} (the "
                      "reference lights every surface with the whole environment)")
        if environment is not None and material.environment_diffuse == 0.0:
            notes.add(f"{label}: environment_diffuse 0 (weft leaves its diffuse unlit by the "
                      "environment; the reference does not)")
        p, n, t = _mesh_arrays(scene, i)
        d[f"instance_{i}"] = _mitsuba_mesh(mi, f"instance_{i}", p, n, t, bsdf)
    for k, light in enumerate(scene.lights if lights else []):
        if float(light.intensity) <= 0.0:
            continue
        d[f"light_{k}"] = conv.light_emitter(light, notes, f"light {k}")
    ambient = np.asarray(scene.ambient, np.float64)
    # weft's ambient I_A K_A T is unoccluded; a uniform sky of radiance I_A is its physical
    # meaning (equal where nothing occludes it, when K_A = K_D). Mitsuba takes one environment
    # emitter, so with an environment the ambient is added to its radiance.
    if environment is not None:
        d["environment"] = environment_emitter(mi, np.asarray(environment, np.float64) + ambient)
    elif np.any(ambient > 0.0):
        d["ambient"] = {"type": "constant",
                        "radiance": {"type": "rgb", "value": [float(c) for c in ambient]}}
    if np.any(ambient > 0.0):
        for i in range(int(scene.instance_count)):
            m = scene.material(i)
            if not np.allclose(np.asarray(m.ka), np.asarray(m.kd)):
                notes.add(f"instance {i}: ambient with K_A {tuple(m.ka)} != K_D {tuple(m.kd)} "
                          "(the reference's uniform sky lights it with K_D)")
    return Export(d, notes.lines)


def render_mitsuba(scene, camera, width: int, height: int, spp: int = 64,
                   integrator: str = "path", seed: int = 0, **kw) -> np.ndarray:
    """Linear RGB (H, W, 3) float32 of the scene rendered by Mitsuba (``kw``: export_scene's
    ``environment``, ``lights``, ``max_depth``)."""
    mi = import_mitsuba()
    exported = export_scene(scene, camera, width, height, spp, integrator, seed, **kw)
    image = mi.render(mi.load_dict(exported.scene), spp=int(spp), seed=int(seed))
    return np.asarray(image, np.float32)[..., :3]
