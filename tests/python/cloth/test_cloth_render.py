"""The cloth in the renderer (SPEC §2.4, issue 5): drawn from its current state, two-sided,
holes left out, re-uploaded only when it changed (a sleeping cloth costs no upload), and
shaded like any other surface (the NumPy oracle from the same frame)."""

from __future__ import annotations

import numpy as np
import pytest
import weft
from weft import reference as ref

N = 16


def hanging_cloth(**kwargs) -> weft.Cloth:
    cloth = weft.Cloth(nx=N, ny=N, size=(1.0, 1.0), origin=(-0.5, 1.5, 0.0), axis_u=(1, 0, 0),
                       axis_v=(0, -1, 0), iterations=4, tethers=True, **kwargs)
    cloth.pin([0, N - 1])
    return cloth


def scene_with(cloth: weft.Cloth, material: weft.Material = None) -> weft.Scene:
    scene = weft.Scene()
    scene.add_cloth(cloth, material or weft.Material(kd=(0.8, 0.3, 0.2), ks=(0.2, 0.2, 0.2)))
    scene.add_light(weft.DirectionalLight(direction=(-0.2, -0.5, -1.0), cast_shadows=False))
    scene.ambient = (0.1, 0.1, 0.1)
    return scene


def closest_on_triangles(p: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Closest points on triangles (a, b, c) to points p, all (..., 3) (Ericson's regions)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.sum(ab * ap, -1), np.sum(ac * ap, -1)
    bp = p - b
    d3, d4 = np.sum(ab * bp, -1), np.sum(ac * bp, -1)
    cp = p - c
    d5, d6 = np.sum(ab * cp, -1), np.sum(ac * cp, -1)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = 1.0 / (va + vb + vc)
        out = a + ab * (vb * denom)[..., None] + ac * (vc * denom)[..., None]  # inside
        # edges
        v_ab = d1 / (d1 - d3)
        out = np.where(((vc <= 0) & (d1 >= 0) & (d3 <= 0))[..., None],
                       a + ab * v_ab[..., None], out)
        w_ac = d2 / (d2 - d6)
        out = np.where(((vb <= 0) & (d2 >= 0) & (d6 <= 0))[..., None],
                       a + ac * w_ac[..., None], out)
        w_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        out = np.where(((va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0))[..., None],
                       b + (c - b) * w_bc[..., None], out)
    # vertices
    out = np.where(((d1 <= 0) & (d2 <= 0))[..., None], a, out)
    out = np.where(((d3 >= 0) & (d4 <= d3))[..., None], b, out)
    out = np.where(((d6 >= 0) & (d5 <= d6))[..., None], c, out)
    return out


def surface_distance(points: np.ndarray, cloth: weft.Cloth) -> np.ndarray:
    """Distance from each point to the cloth's triangle mesh (exact over the 12 triangles with
    the nearest centroids)."""
    mesh = cloth.mesh()
    p, tri = mesh["positions"].astype(np.float64), mesh["indices"].reshape(-1, 3)
    a, b, c = p[tri[:, 0]], p[tri[:, 1]], p[tri[:, 2]]
    centroid = (a + b + c) / 3.0
    near = np.argsort(np.linalg.norm(points[:, None] - centroid[None], axis=-1), axis=1)[:, :12]
    q = closest_on_triangles(points[:, None], a[near], b[near], c[near])
    return np.linalg.norm(q - points[:, None], axis=-1).min(axis=1)


def test_cloth_is_drawn_where_it_is_and_follows_the_simulation(make_renderer) -> None:
    cloth = hanging_cloth()
    scene = scene_with(cloth)
    camera = weft.Camera(position=(0.0, 1.0, 2.5), target=(0.0, 1.0, 0.0), fov_y=0.9)
    renderer = make_renderer(96, 96)
    for _ in range(40):
        cloth.step(1 / 60)
    debug = renderer.render_debug(scene, camera)
    mask = debug["mask"]
    assert mask.mean() > 0.1
    spacing = 1.0 / (N - 1)
    d = surface_distance(debug["position"][mask].astype(np.float64), cloth)
    assert d.max() < 0.01 * spacing, d.max()  # on the surface, up to float rounding
    # the shading equation holds on the cloth like anywhere else
    material = ref.SurfaceMaterial.from_weft(scene.material(0))
    oracle = ref.shade_debug_frame(debug, camera.position, scene.lights, scene.ambient,
                                   scene.background, material, frame_albedo=True)
    err = np.abs(debug["linear"][..., :3] - oracle[..., :3]).max(axis=-1)[mask]
    assert err.max() <= 1e-3


def test_uploads_only_when_the_cloth_changed(make_renderer) -> None:
    cloth = hanging_cloth(sleep_threshold=0.05, sleep_steps=5)
    scene = scene_with(cloth)
    camera = weft.Camera(position=(0.0, 1.0, 2.5), target=(0.0, 1.0, 0.0))
    renderer = make_renderer(48, 48)
    renderer.render(scene, camera)
    first = renderer.stats
    assert first["mesh_uploads"] == 1 and first["upload_bytes"] >= N * N * 48
    renderer.render(scene, camera)
    assert renderer.stats["mesh_uploads"] == 0 and renderer.stats["upload_bytes"] == 0
    cloth.step(1 / 60)
    renderer.render(scene, camera)
    assert renderer.stats["mesh_uploads"] == 1
    for _ in range(600):  # until it sleeps
        cloth.step(1 / 60)
        if cloth.sleeping:
            break
    assert cloth.sleeping
    renderer.render(scene, camera)
    cloth.step(1 / 60)  # a sleeping cloth does not step ...
    renderer.render(scene, camera)
    assert renderer.stats["mesh_uploads"] == 0  # ... so nothing is uploaded


def test_back_face_is_shaded_with_the_flipped_normal(make_renderer) -> None:
    cloth = hanging_cloth()
    scene = scene_with(cloth)
    renderer = make_renderer(64, 64)
    for z in (2.5, -2.5):  # in front of and behind the cloth
        camera = weft.Camera(position=(0.0, 1.0, z), target=(0.0, 1.0, 0.0))
        debug = renderer.render_debug(scene, camera)
        mask = debug["mask"]
        assert mask.mean() > 0.1
        to_eye = np.asarray(camera.position) - debug["position"][mask]
        facing = np.sum(debug["normal"][mask] * to_eye, axis=1)
        assert np.all(facing > 0), "the normal must face the viewer on both sides"


def test_holes_are_left_out(make_renderer) -> None:
    cloth = hanging_cloth()
    mask = np.zeros((N, N), bool)
    mask[5:11, 5:11] = True
    cloth.set_holes(mask)
    scene = scene_with(cloth)
    camera = weft.Camera(position=(0.0, 1.0, 2.0), target=(0.0, 1.0, 0.0), fov_y=0.8)
    debug = make_renderer(96, 96).render_debug(scene, camera)
    # the hole's middle, (i, j) = (7.5, 7.5) in the flat cloth: x = 0, y = 1.5 - 0.5 = 1.0
    view = np.asarray(camera.view_matrix()) @ np.array([0.0, 1.0, 0.0, 1.0])
    clip = np.asarray(camera.projection_matrix(1.0)) @ view
    px = ((clip[:2] / clip[3]) * 0.5 + 0.5) * 96
    col, row = int(px[0]), int(px[1])
    assert not debug["mask"][row - 2:row + 3, col - 2:col + 3].any(), "the hole is drawn"
    assert debug["mask"].mean() > 0.2


def test_add_cloth_validation() -> None:
    scene = weft.Scene()
    with pytest.raises(TypeError):
        scene.add_cloth("not a cloth")
    cid = scene.add_cloth(hanging_cloth())
    assert scene.material(cid).two_sided
    with pytest.raises(ValueError, match="transform"):
        scene.set_transform(cid, np.eye(4))
