"""The anti-aliasing reference (issue 18): the same frame rendered at ``factor`` x ``factor``
the resolution (same camera, same renderer settings), box-downsampled in linear light, is the
pixel-area average a perfectly anti-aliased frame shows. The error of the normal frame is the
mean |difference| of the displayed 8-bit values (clamp + sRGB of both, in 1/255 units, averaged
over RGB) over the pixels on geometric edges: mesh silhouettes (instance id changes between
8-neighbours, background included) and, separately, hair (pixels that are, or touch, hair).

Hair drawn as 1-pixel ``lines`` has no resolution-independent width (at 4x it would be 1/4 as
wide), so the hair reference draws ``ribbons`` of a world width in both frames;
:func:`hair_scene` sizes it to about one pixel of the normal frame, the case that aliases.
"""

from __future__ import annotations

from typing import Callable, Dict, Optional

import numpy as np

from weft.reference.picture.compare import edge_mask, to_display

#: Supersampling factor per axis of the reference (4 x 4 = 16 samples per pixel).
FACTOR = 4


def box_downsample(image: np.ndarray, factor: int) -> np.ndarray:
    """Mean over factor x factor blocks of (H*f, W*f, C) -> (H, W, C)."""
    h, w = image.shape[0] // factor, image.shape[1] // factor
    return image[:h * factor, :w * factor].reshape(h, factor, w, factor, -1).mean(axis=(1, 3))


def _copy_settings(src, dst, factor: int) -> None:
    """The frame's settings for the supersampled reference -- except anti-aliasing: the
    reference is point-sampled (msaa 1, so hair is drawn without its coverage strips), a truth
    that shares no AA code with the frame it judges; blurs in pixels scale with the factor."""
    for name in ("shadow_map_size", "pcf_radius", "bias_constant", "bias_slope", "bias_max",
                 "normal_offset", "hair_primitive", "hair_width", "hair_transparency",
                 "hair_dom", "hair_dom_size", "bounce", "ambient_occlusion"):
        if hasattr(src, name):
            try:
                setattr(dst, name, getattr(src, name))
            except (AttributeError, TypeError):
                pass  # read-only on this build
    if hasattr(dst, "msaa"):
        dst.msaa = 1
    if hasattr(src, "ambient_occlusion_blur"):
        dst.ambient_occlusion_blur = min(64.0, src.ambient_occlusion_blur * factor)


def aa_edge_error(scene, camera, renderer, factor: int = FACTOR,
                  make_renderer: Optional[Callable[[int, int], object]] = None,
                  exposure: float = 1.0) -> Dict[str, object]:
    """AA edge error of ``renderer``'s frame of ``scene`` against the ``factor``^2 supersampled
    frame: ``mesh_edges`` and ``hair_edges`` (mean |d| in 1/255 units, None where the frame has
    no such pixels), their pixel counts, and the images."""
    import weft

    w, h = int(renderer.width), int(renderer.height)
    debug = renderer.render_debug(scene, camera)  # never multisampled: ids and masks only
    if getattr(renderer, "hair_transparency", False) and getattr(scene, "hair_count", 0):
        # transparent strands (WBOIT) are not in the debug "hair" id map: take their pixels
        # from a debug frame that draws them opaque
        renderer.hair_transparency = False
        try:
            debug["hair"] = renderer.render_debug(scene, camera)["hair"]
        finally:
            renderer.hair_transparency = True
    normal = np.asarray(renderer.render_linear(scene, camera), np.float64)[..., :3]
    big = (make_renderer or (lambda ww, hh: weft.Renderer(ww, hh)))(w * factor, h * factor)
    _copy_settings(renderer, big, factor)
    hi = np.asarray(big.render_linear(scene, camera), np.float64)[..., :3]
    reference = box_downsample(hi, factor)
    diff = np.abs(to_display(normal, exposure) - to_display(reference, exposure)).mean(axis=-1)
    diff *= 255.0
    ids = np.where(debug["mask"], np.asarray(debug["instance"]), -1)
    hair = np.asarray(debug["hair"]) >= 0 if "hair" in debug else np.zeros(ids.shape, bool)
    hair_px = edge_mask(np.where(hair, -2, 0)) | hair
    mesh_edges = edge_mask(np.where(hair, -1, ids)) & ~hair_px
    out: Dict[str, object] = {"factor": factor, "width": w, "height": h,
                              "normal": normal, "reference": reference, "diff": diff}
    for key, m in (("mesh_edges", mesh_edges), ("hair_edges", hair_px)):
        out[key] = float(diff[m].mean()) if m.any() else None
        out[key + "_pixels"] = int(m.sum())
    out["interior"] = float(diff[~(mesh_edges | hair_px)].mean())
    return out


def hair_scene(width: int = 160, height: int = 120, strands: int = 300):
    """A small head of hair for the hair AA reference: straight-ish generated strands in front
    of a grey backdrop, lit by a sun; returns (scene, camera, ribbon width in metres) with the
    width about one pixel of a ``height``-row frame at the hair's distance."""
    import weft

    scene = weft.Scene()
    hair = weft.generate_hair(strands, strands * 16, style="wavy")
    scene.add_hair(hair, weft.HairMaterial("kajiya_kay"))
    lo, hi = scene.bounds()
    lo, hi = np.asarray(lo), np.asarray(hi)
    centre = 0.5 * (lo + hi)
    backdrop = np.eye(4, dtype=np.float32)
    backdrop[:3, :3] = np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]], np.float32)  # faces +Z
    backdrop[:3, 3] = (centre[0], centre[1], lo[2] - 0.5)
    scene.add_mesh(weft.Mesh.plane(8.0, 8.0), weft.Material(kd=(0.5, 0.5, 0.5)),
                   transform=backdrop)
    scene.add_light(weft.DirectionalLight(direction=(-0.3, -0.5, -1.0), intensity=1.0))
    scene.ambient = (0.2, 0.2, 0.2)
    fov = 0.6
    distance = 1.2 * float(max(hi[1] - lo[1], (hi[0] - lo[0]) * height / width)) / (
        2.0 * np.tan(fov / 2)) + float(hi[2] - centre[2])
    camera = weft.Camera(position=tuple(centre + (0.0, 0.0, distance)), target=tuple(centre),
                         fov_y=fov)
    pixel = 2.0 * distance * np.tan(fov / 2) / height
    return scene, camera, float(pixel)


def fur_scene(width: int = 320, height: int = 240):
    """The demo's furry ball (cpp/src/app/DemoScene.cpp: 9000 strands/m^2, 6 segments, 9 cm,
    25% transparent, so drawn through WBOIT) on a ground under a sun; returns (scene, camera,
    ribbon width in metres about one pixel of a ``height``-row frame at the ball)."""
    import weft

    scene = weft.Scene()
    ball = weft.Mesh.uv_sphere(0.28, 24, 12)
    at = np.eye(4)
    at[:3, 3] = (0.0, 0.3, 0.0)
    scene.add_mesh(ball, weft.Material(kd=(0.35, 0.22, 0.1)), transform=at)
    fur = weft.generate_fur(ball, density=9000.0, segments=6, length=0.09, length_jitter=0.3,
                            direction_jitter=0.35, down=(0.0, -6.0, 0.0))
    fur = weft.HairStrands(np.asarray(fur.points), np.asarray(fur.segments),
                           default_transparency=0.25)
    scene.add_hair(fur, weft.HairMaterial("kajiya_kay", diffuse=(0.5, 0.32, 0.15),
                                          specular=(0.15, 0.15, 0.15)), at)
    scene.add_mesh(weft.Mesh.plane(4.0, 4.0), weft.Material(kd=(0.4, 0.5, 0.3)),
                   cast_shadows=False)
    scene.add_light(weft.DirectionalLight(direction=(-0.4, -1.0, -0.5), intensity=2.0))
    scene.ambient = (0.25, 0.28, 0.35)
    eye, target, fov = np.array([0.0, 0.55, 1.3]), np.array([0.0, 0.3, 0.0]), 0.6
    camera = weft.Camera(position=tuple(eye), target=tuple(target), fov_y=fov)
    pixel = 2.0 * float(np.linalg.norm(eye - target)) * np.tan(fov / 2) / height
    return scene, camera, float(pixel)
