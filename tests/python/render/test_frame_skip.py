"""A frame runs only what its scene needs (SPEC §6): shadow maps are reused while no light view
and no caster changed, re-rendered when one did; a resting cloth costs no upload and no shadow
pass; the pass lists say so, and reuse never changes the picture."""

from __future__ import annotations

import numpy as np
import weft


def translation(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = (x, y, z)
    return m


def shadow_passes(stats) -> list:
    return [p["name"] for p in stats["passes"] if p["name"].startswith("shadow")]


def make_scene():
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(6, 6), weft.Material())
    box = scene.add_mesh(weft.Mesh.box((0.6, 0.6, 0.6)), weft.Material(kd=(0.8, 0.3, 0.2)),
                         translation(0, 0.8, 0))
    sun = scene.add_light(weft.DirectionalLight(direction=(-0.4, -1.0, -0.3)))
    scene.add_light(weft.SpotLight(position=(1.5, 2.5, 1.0), direction=(-0.5, -1, -0.3),
                                   outer_angle=0.7, radius=8.0))
    return scene, box, sun


def test_shadow_maps_are_reused_until_something_they_show_changes(make_renderer) -> None:
    scene, box, sun = make_scene()
    camera = weft.Camera(position=(0, 3, 4))
    r = make_renderer(64, 48, shadow_map_size=512)
    first = r.render(scene, camera)
    assert shadow_passes(r.stats) == ["shadow[0]", "shadow[1]"] and r.stats["reused"] == []
    again = r.render(scene, camera)
    assert shadow_passes(r.stats) == [] and r.stats["reused"] == ["shadow[0]", "shadow[1]"]
    np.testing.assert_array_equal(first, again)
    # the camera does not change what the lights see
    r.render(scene, weft.Camera(position=(1, 2, 4)))
    assert shadow_passes(r.stats) == []
    # a moved caster re-renders every map; the result equals a fresh renderer's
    scene.set_transform(box, translation(0.3, 0.8, 0))
    moved = r.render(scene, camera)
    assert shadow_passes(r.stats) == ["shadow[0]", "shadow[1]"]
    fresh = make_renderer(64, 48, shadow_map_size=512).render(scene, camera)
    np.testing.assert_array_equal(moved, fresh)
    assert not np.array_equal(moved, first)
    # a changed light view re-renders too
    r.render(scene, camera)
    assert shadow_passes(r.stats) == []
    scene.set_light(sun, weft.DirectionalLight(direction=(0.4, -1.0, -0.3)))
    r.render(scene, camera)
    assert shadow_passes(r.stats) == ["shadow[0]", "shadow[1]"]


def test_reuse_can_be_switched_off(make_renderer) -> None:
    scene, _, _ = make_scene()
    camera = weft.Camera(position=(0, 3, 4))
    r = make_renderer(32, 24, shadow_map_size=256, reuse_shadow_maps=False)
    for _ in range(2):
        r.render(scene, camera)
        assert shadow_passes(r.stats) == ["shadow[0]", "shadow[1]"] and r.stats["reused"] == []


def test_resting_cloth_costs_no_upload_and_no_shadow_pass(make_renderer) -> None:
    cloth = weft.Cloth(nx=8, ny=8, origin=(-0.5, 1.0, -0.5), sleep_threshold=0.05, sleep_steps=3)
    cloth.pin([0, 7])
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(4, 4), weft.Material())
    scene.add_cloth(cloth)
    scene.add_light(weft.DirectionalLight(direction=(-0.3, -1.0, -0.2)))
    camera = weft.Camera(position=(0, 2, 3))
    r = make_renderer(32, 24, shadow_map_size=256)
    cloth.step(1 / 60)
    r.render(scene, camera)
    assert r.stats["mesh_uploads"] == 1 and shadow_passes(r.stats) == ["shadow[0]"]
    cloth.step(1 / 60)
    r.render(scene, camera)  # the cloth moved: new mesh, new shadow
    assert r.stats["mesh_uploads"] == 1 and shadow_passes(r.stats) == ["shadow[0]"]
    for _ in range(1000):
        cloth.step(1 / 60)
        if cloth.sleeping:
            break
    assert cloth.sleeping
    r.render(scene, camera)
    r.render(scene, camera)
    assert r.stats["mesh_uploads"] == 0 and shadow_passes(r.stats) == []
    assert r.stats["reused"] == ["shadow[0]"]
