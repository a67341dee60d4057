"""The renderer uploads a frame's lights sorted by kind and shadow (render/FrameData.cpp) and
specializes its pipelines to the kinds present, each looped over with only its own code
(shading.glsl, forEachLight). Truth that shares none of that bookkeeping: the same scene with its
lights added in another order, or with a light that brings nothing, draws the same picture --
meshes, the debug shadow channel of the first shadowed scene light, and fur shadowed by its deep
opacity map, which the hair shaders find by the light's place in the sorted buffer."""

from __future__ import annotations

import numpy as np
import pytest
import weft
from weft import reference as ref


def translation(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = (x, y, z)
    return m


def lights():
    """One light of most groups, in an order the renderer sorts differently."""
    cookie = np.zeros((8, 8, 3), np.uint8)
    cookie[..., 0] = np.linspace(60, 255, 8).astype(np.uint8)[None, :]
    cookie[..., 1:] = 200
    return [
        weft.SpotLight(position=(0.5, 3.0, 1.0), direction=(-0.1, -1.0, -0.3), intensity=2.0,
                       cookie=weft.Texture(cookie, srgb=False, mipmaps=False),
                       cast_shadows=False),
        weft.PointLight(position=(-1.5, 2.0, 1.0), intensity=1.5, attenuation=(1.0, 0.2, 0.1)),
        weft.DirectionalLight(direction=(0.3, -1.0, -0.4), intensity=0.8,
                              angular_radius=0.02),  # soft shadow; the fur's deep opacity map
        weft.DirectionalLight(direction=(-0.5, -0.6, 0.2), color=(0.3, 0.4, 0.9),
                              intensity=0.3, cast_shadows=False),
        weft.SpotLight(position=(1.5, 2.5, -0.5), direction=(-0.5, -1.0, 0.2), intensity=1.5,
                       outer_angle=0.6),  # shadowed
    ]


def stage(order, extra=()):
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(6.0, 6.0, 2, 2),
                   weft.Material(kd=(0.8, 0.8, 0.8), ks=(0.2, 0.2, 0.2), shininess=20.0))
    sphere = weft.Mesh.uv_sphere(0.4, 24, 12)
    scene.add_mesh(sphere, weft.Material(kd=(0.7, 0.3, 0.2), ks=(0.4, 0.4, 0.4), shininess=40.0),
                   translation(-0.5, 0.5, 0.0))
    ball = translation(0.7, 0.35, 0.3)
    scene.add_mesh(weft.Mesh.uv_sphere(0.2, 12, 8), weft.Material(kd=(0.3, 0.2, 0.1)), ball)
    weft.add_fur(scene, weft.Mesh.uv_sphere(0.2, 12, 8), weft.HairMaterial("kajiya_kay"), ball,
                 segments=3, length=0.12)
    for light in [lights()[i] for i in order] + list(extra):
        scene.add_light(light)
    scene.ambient = (0.05, 0.05, 0.05)
    return scene, weft.Camera(position=(0.5, 2.5, 3.5), target=(0.0, 0.3, 0.0), fov_y=0.8)


@pytest.fixture(scope="module")
def renderer():
    r = weft.Renderer(96, 72, shadow_map_size=256, msaa=1)
    r.hair_dom_size = 64
    return r


def test_light_order_does_not_change_the_picture(renderer):
    a = renderer.render_linear(*stage([0, 1, 2, 3, 4]))
    assert any(p["name"].startswith("hair_dom") for p in renderer.stats["passes"])
    b = renderer.render_linear(*stage([4, 3, 2, 1, 0]))
    c = renderer.render_linear(*stage([2, 0, 4, 1, 3]))
    assert np.asarray(a)[..., :3].max() > 0.2  # lit
    for other in (b, c):  # the same sums in another order: within a half-float step
        assert ref.storage_excess(np.asarray(other), np.asarray(a)).max() < 1e-5


def test_debug_shadow_channel_follows_the_first_shadowed_scene_light(renderer):
    # scene order: the point light (shadowed) first, then the soft sun: the channel shows the
    # point light's shadow although the sun comes first in the sorted buffer
    debug = renderer.render_debug(*stage([1, 2, 3]))
    point_only = renderer.render_debug(*stage([1]))  # alone: nothing to sort
    sun_only = renderer.render_debug(*stage([2]))
    mask = debug["mask"]
    assert np.mean(point_only["shadow"][mask] < 0.5) > 0.01  # the test sees a shadow
    np.testing.assert_array_equal(debug["shadow"][mask], point_only["shadow"][mask])
    assert np.any(debug["shadow"][mask] != sun_only["shadow"][mask])


def test_a_light_that_brings_nothing_changes_nothing(renderer):
    a = renderer.render_linear(*stage([2, 4]))
    dark = weft.DirectionalLight(direction=(0.0, -1.0, 0.0), intensity=0.0, cast_shadows=False)
    b = renderer.render_linear(*stage([2, 4], extra=[dark]))
    np.testing.assert_array_equal(np.asarray(a), np.asarray(b))


def test_hair_without_a_deep_opacity_map_reads_the_shadow_map():
    """Fur that casts no shadow gets no deep opacity map, so its pipelines keep the shadow-map
    path for the sun (FEATURE_HAIR_SHADOW_MAPS): a board above half of the strands shadows
    them. Truth: the same strands with the board beside them instead (no shadow) and with no
    light at all."""
    xs = np.linspace(-0.8, 0.8, 9, dtype=np.float32)
    points = np.concatenate([np.stack([xs, np.full_like(xs, y), np.zeros_like(xs)], axis=1)
                             for y in np.linspace(-0.3, 0.3, 7)])

    def frame(board_x: float):
        scene = weft.Scene()
        scene.add_mesh(weft.Mesh.box((0.9, 0.05, 2.0)), weft.Material(),
                       translation(board_x, 1.0, 0.0))
        scene.add_hair(weft.HairStrands(points, default_segments=8), weft.HairMaterial(
            "kajiya_kay", diffuse=(0.6, 0.5, 0.4), specular=(0.0, 0.0, 0.0)),
            cast_shadows=False)
        scene.add_light(weft.DirectionalLight(direction=(0.0, -1.0, 0.0), intensity=1.0))
        scene.ambient = (0.02, 0.02, 0.02)
        r = weft.Renderer(96, 72, shadow_map_size=256, msaa=1)
        image = np.asarray(r.render_linear(scene, weft.Camera(position=(0.0, 0.0, 2.5),
                                                               target=(0.0, 0.0, 0.0),
                                                               fov_y=0.8)))[..., :3]
        assert not any(p["name"].startswith("hair_dom") for p in r.stats["passes"])
        return image.sum(axis=-1)

    shaded, lit = frame(-0.45), frame(3.0)  # the board over the left half / far to the side
    hair = lit > 0.1
    left = hair & (np.arange(96)[None, :] < 40)
    right = hair & (np.arange(96)[None, :] > 56)
    assert left.sum() > 20 and right.sum() > 20
    assert shaded[left].mean() < 0.3 * lit[left].mean()  # under the board: shadowed
    np.testing.assert_allclose(shaded[right].mean(), lit[right].mean(), rtol=0.05)
