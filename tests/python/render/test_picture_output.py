"""The picture a user sees: exposure and tone mapping in the output pass, the environment drawn
behind the scene. (MSAA against a supersampled render: test_picture_reference.py.)

Truths used: the sRGB transfer function and the operators' defining properties (not their
formulas re-typed), and the environment's own texels for the background."""

from __future__ import annotations

import numpy as np
import pytest
import weft
import weft.ibl
from weft.reference.texture import srgb_decode

W, H = 96, 72
OPERATORS = ("clamp", "aces", "agx", "neutral")


def flat_scene(value) -> weft.Scene:
    """No geometry: every pixel is the background colour, a known linear radiance."""
    scene = weft.Scene()
    scene.background = tuple(float(v) for v in value)
    return scene


CAMERA = weft.Camera(position=(0, 0, 3), target=(0, 0, 0))


def shown(value, **settings) -> np.ndarray:
    """The linear value the colour output shows for a background radiance (sRGB decoded)."""
    r = weft.Renderer(8, 8, **settings)
    image = r.render(flat_scene(value), CAMERA)
    return srgb_decode(image[4, 4, :3] / 255.0)


def test_exposure_is_a_power_of_two_scale_of_the_radiance() -> None:
    # EV +1 shows exactly what twice the radiance shows, under every operator
    for op in OPERATORS:
        a = shown((0.2, 0.1, 0.05), exposure=1.0, tone_map=op)
        b = shown((0.4, 0.2, 0.1), exposure=0.0, tone_map=op)
        assert np.abs(a - b).max() < 2e-3, (op, a, b)
    assert np.abs(shown((0.1, 0.1, 0.1), exposure=-2.0) - 0.025).max() < 2e-3  # clamp: linear


def test_operators_are_monotone_bounded_and_keep_black() -> None:
    values = [0.0, 0.02, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0]
    for op in OPERATORS:
        grey = np.array([shown((v, v, v), tone_map=op)[0] for v in values])
        assert grey[0] < 2e-3, (op, grey)
        assert np.all(np.diff(grey) >= -1e-3), (op, grey)
        assert grey.max() <= 1.0
    # clamp clips: 1, 3, 10 and 100 all show as white; the filmic operators keep them apart
    clamp = np.array([shown((v, v, v), tone_map="clamp")[0] for v in (1.0, 3.0, 10.0)])
    assert np.allclose(clamp, 1.0, atol=2e-3)
    for op in ("aces", "agx", "neutral"):
        hi = np.array([shown((v, v, v), tone_map=op)[0] for v in (1.0, 3.0, 10.0)])
        assert np.all(np.diff(hi) > 0.005), (op, hi)


def test_neutral_leaves_low_values_as_they_are() -> None:
    # Khronos PBR Neutral: below its compression start (0.76) a colour is only offset by at
    # most 0.04 (the toe), so mid-range colours keep their values and hue
    colour = (0.5, 0.3, 0.2)
    got = shown(colour, tone_map="neutral")
    assert np.abs(got - (np.array(colour) - 0.04)).max() < 4e-3, got


def test_a_renderer_switching_operators_shows_what_each_shows_alone() -> None:
    # each operator has its own output pipeline: switching on one renderer must pick it up
    scene = flat_scene((3.0, 1.0, 0.3))
    r = weft.Renderer(8, 8)
    for op in OPERATORS + OPERATORS[::-1]:
        r.tone_map = op
        np.testing.assert_array_equal(r.render(scene, CAMERA),
                                      weft.Renderer(8, 8, tone_map=op).render(scene, CAMERA))
    # and the four differ, so that could fail
    shows = {tuple(shown((3.0, 1.0, 0.3), tone_map=op).round(3)) for op in OPERATORS}
    assert len(shows) == len(OPERATORS), shows


def test_linear_output_is_neither_exposed_nor_tone_mapped() -> None:
    scene = flat_scene((5.0, 2.0, 0.5))
    for op in OPERATORS:
        r = weft.Renderer(8, 8, exposure=3.0, tone_map=op)
        linear = r.render_linear(scene, CAMERA)
        assert np.allclose(linear[..., :3], (5.0, 2.0, 0.5), atol=1e-6)


def test_output_settings_are_checked() -> None:
    r = weft.Renderer(8, 8)
    assert (r.msaa, r.exposure, r.tone_map) == (4, 0.0, "clamp")
    for bad in (0, 3, 16):
        with pytest.raises(weft.InvalidArgument, match="msaa"):
            r.msaa = bad
        with pytest.raises(weft.InvalidArgument, match="msaa"):
            weft.Renderer(8, 8, msaa=bad)
    with pytest.raises(weft.InvalidArgument, match="tone_map"):
        r.tone_map = "filmic"
    for bad in (float("nan"), float("inf"), 100.0):
        with pytest.raises(weft.InvalidArgument, match="exposure"):
            r.exposure = bad
    r.tone_map = "agx"
    r.exposure = -1.5
    assert (r.tone_map, r.exposure) == ("agx", -1.5)
    assert r.msaa_samples in (1, 2, 4)


def face_colours() -> tuple:
    """A cube map whose six faces each hold one colour, and those colours."""
    colours = np.array([[1.0, 0.1, 0.1], [0.1, 1.0, 0.1], [0.1, 0.1, 1.0],
                        [1.0, 1.0, 0.1], [0.1, 1.0, 1.0], [1.0, 0.1, 1.0]], np.float32)
    faces = np.broadcast_to(colours[:, None, None, :], (6, 16, 16, 3)).copy()
    return weft.ibl.CubeMap(faces), colours


def test_environment_is_drawn_behind_the_scene() -> None:
    cube, colours = face_colours()
    scene = weft.Scene()
    scene.background = (0.0, 0.0, 0.0)
    scene.set_environment(cube, intensity=2.0, background=True)
    r = weft.Renderer(W, H)
    # looking down each axis, the image centre shows that face's texels, times the intensity
    for face, direction in enumerate([(1, 0, 0), (-1, 0, 0), (0, 1, 0.001), (0, -1, 0.001),
                                      (0, 0, 1), (0, 0, -1)]):
        camera = weft.Camera(position=(0, 0, 0), target=direction, fov_y=0.7)
        linear = r.render_linear(scene, camera)
        centre = linear[H // 2 - 4:H // 2 + 4, W // 2 - 4:W // 2 + 4, :3].reshape(-1, 3)
        assert np.abs(centre - 2.0 * colours[face]).max() < 0.01, (face, centre.mean(axis=0))
    # without background=True the clear colour stays
    scene.set_environment(cube, intensity=2.0)
    assert np.abs(r.render_linear(scene, camera)[..., :3]).max() == 0.0


def test_background_blur_reads_the_glossy_chain() -> None:
    cube, colours = face_colours()
    scene = weft.Scene()
    camera = weft.Camera(position=(0, 0, 0), target=(0, 0, -1), fov_y=0.7)
    r = weft.Renderer(W, H)
    sharp_edge = None
    for blur in (0.0, 1.0):
        scene.set_environment(cube, background=True, background_blur=blur)
        centre = r.render_linear(scene, camera)[H // 2, W // 2, :3]
        if blur == 0.0:
            sharp_edge = centre
            assert np.abs(centre - colours[5]).max() < 0.01
        else:  # roughness 1 spreads over the neighbouring faces: towards the mean colour
            mean = colours.mean(axis=0)
            assert np.abs(centre - mean).max() < np.abs(sharp_edge - mean).max() * 0.6, centre
    with pytest.raises(weft.InvalidArgument, match="background_blur"):
        scene.set_environment(cube, background=True, background_blur=1.5)


def test_background_image_wins_over_the_environment() -> None:
    cube, _ = face_colours()
    scene = weft.Scene()
    scene.set_environment(cube, background=True)
    scene.background_image = weft.Texture(np.full((4, 4, 4), 255, np.uint8))
    linear = weft.Renderer(W, H).render_linear(scene, weft.Camera(position=(0, 0, 3),
                                                                  target=(0, 0, 0)))
    assert np.allclose(linear[..., :3], 1.0, atol=1e-3)
