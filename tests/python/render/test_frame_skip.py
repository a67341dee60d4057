"""A frame runs only what its scene needs (SPEC §6): shadow maps are reused while no light view
and no caster changed, re-rendered when one did; while some casters move and the rest stand
still, the still ones' depth is kept and only the moving ones are drawn over it; a resting
cloth costs no upload and no shadow pass; the pass lists say so, and reuse never changes the
picture."""

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
    # a moved caster re-renders every map (the still plane once into its own maps, copied in,
    # the box over it); the result equals a fresh renderer's
    scene.set_transform(box, translation(0.3, 0.8, 0))
    moved = r.render(scene, camera)
    assert shadow_passes(r.stats) == ["shadow_still[0]", "shadow_still[1]", "shadow_copy",
                                      "shadow[0]", "shadow[1]"]
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
    r.render(scene, camera)  # the cloth moved: new mesh, new shadow over the still ground's
    assert r.stats["mesh_uploads"] == 1
    assert shadow_passes(r.stats) == ["shadow_still[0]", "shadow_copy", "shadow[0]"]
    for _ in range(1000):
        cloth.step(1 / 60)
        if cloth.sleeping:
            break
    assert cloth.sleeping
    r.render(scene, camera)
    r.render(scene, camera)
    assert r.stats["mesh_uploads"] == 0 and shadow_passes(r.stats) == []
    assert r.stats["reused"] == ["shadow[0]"]


def test_only_the_moving_casters_are_drawn_while_the_rest_stand_still(make_renderer) -> None:
    """The still casters' depth is drawn once and copied in every frame; the moving ones are
    drawn over it. Each frame equals a renderer that draws every caster every frame."""
    scene, box, sun = make_scene()
    camera = weft.Camera(position=(0, 3, 4))
    r = make_renderer(64, 48, shadow_map_size=512)
    every = make_renderer(64, 48, shadow_map_size=512, reuse_shadow_maps=False)
    passes = []
    for k in range(4):
        scene.set_transform(box, translation(0.1 * k, 0.8, 0))  # the box moves every frame
        got = r.render(scene, camera)
        passes.append(shadow_passes(r.stats))
        np.testing.assert_array_equal(got, every.render(scene, camera))
    both = ["shadow[0]", "shadow[1]"]
    assert passes[0] == both  # nothing known to stand still yet
    assert passes[1] == ["shadow_still[0]", "shadow_still[1]", "shadow_copy"] + both
    assert passes[2] == passes[3] == ["shadow_copy"] + both
    assert {"shadow_still[0]", "shadow_still[1]"} <= set(r.stats["reused"])
    # the box's shadow moved with it: the maps were not simply kept
    first = r.shadow_map(0)
    scene.set_transform(box, translation(-0.5, 0.8, 0))
    r.render(scene, camera)
    assert not np.array_equal(first, r.shadow_map(0))
    # a still caster that starts to move (a ball inside the others' bounds, so the light views
    # stay) and a moving one that stops draw the still maps anew
    ball = scene.add_mesh(weft.Mesh.uv_sphere(0.2, 12, 6), weft.Material(),
                          translation(-1.0, 0.3, 1.0))
    r.render(scene, camera)
    r.render(scene, camera)
    scene.set_transform(ball, translation(-1.2, 0.3, 1.0))
    got = r.render(scene, camera)
    assert shadow_passes(r.stats) == ["shadow_still[0]", "shadow_still[1]", "shadow_copy"] + both
    np.testing.assert_array_equal(got, every.render(scene, camera))
    # a turned light draws every caster at once
    scene.set_light(sun, weft.DirectionalLight(direction=(0.4, -1.0, -0.3)))
    scene.set_transform(box, translation(0.2, 0.8, 0))
    r.render(scene, camera)
    assert shadow_passes(r.stats) == both
