"""Hair frames run only what they need: the deep opacity maps are reused while no map's view and
no strand drawn into it changed (RenderSettings::reuse_shadow_maps), and each hair instance is
shaded by a pipeline holding only its own model's code. Neither changes the picture: a reused
map draws what a fresh renderer draws, and two models in one frame draw what each draws alone."""

from __future__ import annotations

import numpy as np
import pytest
import weft

DOM_PASSES = ["hair_dom_depth", "hair_dom_opacity"]


def translation(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = (x, y, z)
    return m


def fur_ball(scene: weft.Scene, model: str, at) -> int:
    ball = weft.Mesh.uv_sphere(0.3, 12, 6)
    scene.add_mesh(ball, weft.Material(kd=(0.4, 0.3, 0.2)), translation(*at))
    fur = weft.generate_fur(ball, density=3000.0, segments=4, length=0.1)
    strands = weft.HairStrands(fur.points, fur.segments, default_transparency=0.3)
    return scene.add_hair(strands, weft.HairMaterial(model, diffuse=(0.5, 0.35, 0.2)),
                          translation(*at))


def scene_with(models) -> tuple:
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(4, 4), weft.Material())
    ids = [fur_ball(scene, m, (1.6 * i - 0.8 * (len(models) - 1), 0.4, 0.0))
           for i, m in enumerate(models)]
    sun = scene.add_light(weft.DirectionalLight(direction=(-0.3, -1.0, -0.4), intensity=2.0))
    return scene, ids, sun


def dom_passes(stats) -> list:
    return [p["name"] for p in stats["passes"] if p["name"] in DOM_PASSES]


def test_deep_opacity_maps_are_reused_until_their_strands_or_view_change(make_renderer):
    scene, (fur,), sun = scene_with(["kajiya_kay"])
    camera = weft.Camera(position=(0, 1.2, 2.2), target=(0, 0.3, 0))
    r = make_renderer(64, 48, shadow_map_size=256, msaa=1)
    first = r.render_linear(scene, camera)
    assert dom_passes(r.stats) == DOM_PASSES
    again = r.render_linear(scene, camera)
    assert dom_passes(r.stats) == [] and set(DOM_PASSES) <= set(r.stats["reused"])
    np.testing.assert_array_equal(first, again)
    # moved strands draw new maps, equal to a fresh renderer's
    scene.set_hair_transform(fur, translation(0.2, 0.4, 0.0))
    moved = r.render_linear(scene, camera)
    assert dom_passes(r.stats) == DOM_PASSES
    fresh = make_renderer(64, 48, shadow_map_size=256, msaa=1).render_linear(scene, camera)
    np.testing.assert_array_equal(moved, fresh)
    assert not np.array_equal(moved, first)
    # so does a turned light
    r.render_linear(scene, camera)
    assert dom_passes(r.stats) == []
    scene.set_light(sun, weft.DirectionalLight(direction=(0.3, -1.0, -0.4), intensity=2.0))
    r.render_linear(scene, camera)
    assert dom_passes(r.stats) == DOM_PASSES


def test_reuse_switched_off_draws_the_maps_every_frame(make_renderer):
    scene, _, _ = scene_with(["kajiya_kay"])
    camera = weft.Camera(position=(0, 1.2, 2.2), target=(0, 0.3, 0))
    r = make_renderer(32, 24, shadow_map_size=256, msaa=1, reuse_shadow_maps=False)
    for _ in range(2):
        r.render_linear(scene, camera)
        assert dom_passes(r.stats) == DOM_PASSES


def fur_columns(camera: weft.Camera, x: float, width: int, height: int) -> np.ndarray:
    """The image columns within 0.3 of a fur ball's centre (x, 0.4, 0): its strands only."""
    clip = np.asarray(camera.projection_matrix(width / height)) @ np.asarray(camera.view_matrix())
    cols = []
    for dx in (-0.3, 0.3):
        c = clip @ np.array([x + dx, 0.4, 0.0, 1.0])
        cols.append((c[0] / c[3] * 0.5 + 0.5) * width)
    return np.arange(int(np.ceil(cols[0])), int(np.floor(cols[1])) + 1)


@pytest.mark.parametrize("msaa", [1, 4])
def test_each_model_draws_in_a_mixed_frame_what_it_draws_alone(make_renderer, msaa):
    models = ["kajiya_kay", "marschner", "sadeghi"]
    camera = weft.Camera(position=(0, 1.2, 4.4), target=(0, 0.3, 0))
    mixed_scene, _, _ = scene_with(models)
    mixed = make_renderer(144, 48, shadow_map_size=256, msaa=msaa).render_linear(mixed_scene,
                                                                                  camera)
    for k, model in enumerate(models):
        # every fur drawn with this fur's model: the pixels that show this fur match
        same, _, _ = scene_with([model] * len(models))
        alone = make_renderer(144, 48, shadow_map_size=256, msaa=msaa).render_linear(same, camera)
        cols = fur_columns(camera, 1.6 * k - 1.6, 144, 48)
        assert len(cols) >= 6
        np.testing.assert_allclose(mixed[:, cols], alone[:, cols], atol=1e-6)
        # and the neighbours' models show: the comparison could fail
        other = fur_columns(camera, 1.6 * ((k + 1) % 3) - 1.6, 144, 48)
        assert np.abs(mixed[:, other] - alone[:, other]).max() > 1e-3


@pytest.mark.parametrize("msaa", [1, 4])
@pytest.mark.parametrize("primitive", ["lines", "ribbons"])
def test_transparent_hair_is_drawn_over_all_it_covers(make_renderer, primitive, msaa):
    """The OIT targets are cleared, drawn and composited only over the strands' projected bounds
    (grown by the widest ribbon and the anti-aliased strips' reach; the whole frame where a
    bound reaches behind the camera). The strands here lie in the plane y = 0, seen edge on, so
    their bounds have no height on screen: the ribbons' width and the strips' reach are all the
    rectangle has. A second hair behind the camera, which draws nothing, makes the rectangle the
    whole frame: the pictures must be the same."""
    xs = np.linspace(-0.5, 0.5, 2, dtype=np.float32)
    points = np.array([[x, 0.0, z] for z in np.linspace(-0.3, 0.3, 7) for x in xs], np.float32)
    behind = np.array([[0.0, 0.0, 3.0], [0.0, 0.1, 3.0]], np.float32)
    camera = weft.Camera(position=(0, 0, 2.0), target=(0, 0, 0))

    def frame(extra: bool):
        scene = weft.Scene()
        scene.background = (0.0, 0.0, 0.0)
        scene.ambient = (1.0, 1.0, 1.0)
        material = weft.HairMaterial("kajiya_kay", diffuse=(0.9, 0.8, 0.7))
        for p in [points, behind] if extra else [points]:
            scene.add_hair(weft.HairStrands(p, default_segments=1, default_thickness=30.0,
                                            default_transparency=0.5), material)
        r = make_renderer(80, 60, msaa=msaa)
        # ribbons 60 cm wide; lines get a 3 mm margin, less than a pixel: the strips' reach
        r.hair_primitive = primitive
        r.hair_width = 0.02 if primitive == "ribbons" else 1e-4
        image = r.render_linear(scene, camera)
        assert "hair_composite" in [p["name"] for p in r.stats["passes"]]
        return image

    tight, whole = frame(False), frame(True)
    assert np.mean(np.any(tight[..., :3] > 0.0, axis=-1)) > 0.005  # the hair is in view
    np.testing.assert_array_equal(tight, whole)
