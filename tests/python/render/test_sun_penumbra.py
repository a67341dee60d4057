"""A directional light with an angular radius (DirectionalLight.angular_radius) casts the
penumbra its disc casts. Truth: a straight occluder edge at height h over a ground, the light
straight above; at offset x from the edge's vertical projection the visible part of a disc of
angular radius a is the circular-segment fraction f(d) = 1/2 + (d sqrt(1 - d^2) + asin d) / pi
with d = x / (h tan a) clamped to [-1, 1] (analytic, no weft code)."""

import numpy as np
import pytest
import weft
import weft.ibl
import weft.scenes


def _scene(angular_radius: float, height: float):
    scene = weft.Scene()
    scene.ambient = (0.0, 0.0, 0.0)
    white = weft.Material(ka=(0, 0, 0), kd=(1, 1, 1), ks=(0, 0, 0))
    scene.add_mesh(weft.Mesh.plane(4.0, 4.0, 2, 2), white, cast_shadows=False)
    # a 2 x 2 occluder whose edge x = 0 runs across the middle of the view
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = (-1.0, height, 0.0)
    scene.add_mesh(weft.Mesh.plane(2.0, 2.0, 2, 2), white, transform=m)
    scene.add_light(weft.DirectionalLight(direction=(0.0, -1.0, 0.0), intensity=1.0,
                                          angular_radius=angular_radius))
    # looking up from below the occluder would see it; look down from between the two
    camera = weft.Camera(position=(0.0, height * 0.5, 0.001), target=(0.0, 0.0, 0.0), fov_y=1.2)
    return scene, camera


def _visible_fraction(d: np.ndarray) -> np.ndarray:
    d = np.clip(d, -1.0, 1.0)
    return 0.5 + (d * np.sqrt(1.0 - d * d) + np.arcsin(d)) / np.pi


@pytest.mark.parametrize("radius", [0.05, 0.12])
def test_penumbra_follows_the_disc(make_renderer, radius):
    h = 0.6
    scene, camera = _scene(radius, h)
    r = make_renderer(160, 160, shadow_map_size=2048)
    r.render(scene, camera)
    dbg = r.render_debug(scene, camera)
    ground = dbg["mask"] & (dbg["instance"] == 0)
    x = dbg["position"][..., 0][ground]
    lit = dbg["linear"][..., :3][ground].mean(axis=1)  # K_D L (n.l) vis with L = 1, n.l = 1
    width = h * np.tan(radius)
    near = np.abs(x) < 2.5 * width
    assert near.sum() > 200, near.sum()
    truth = _visible_fraction(x[near] / width)
    err = np.abs(lit[near] - truth)
    # measured: mean 0.010 (0.05 rad) and 0.025 (0.12 rad): the taps' noise (24 per pixel,
    # turned per point) and the map's texels
    assert err.mean() < 0.05, err.mean()
    # and it is a penumbra: without the radius the edge is one PCF kernel wide
    scene.set_light(0, weft.DirectionalLight(direction=(0.0, -1.0, 0.0), intensity=1.0))
    hard = r.render_debug(scene, camera)["linear"][..., :3][ground].mean(axis=1)
    assert np.abs(hard[near] - truth).mean() > 2.0 * err.mean()


def test_angular_radius_is_checked():
    for bad in (-0.1, 0.6, float("nan")):
        with pytest.raises(weft.InvalidArgument):
            weft.DirectionalLight(angular_radius=bad)
    light = weft.DirectionalLight()
    with pytest.raises(weft.InvalidArgument):
        light.angular_radius = float("inf")


def test_sky_sun_and_split_suns_carry_their_disc():
    sun = weft.ibl.sun_light((0.3, 0.8, 0.2))
    assert sun.angular_radius == pytest.approx(0.0046531, rel=1e-4)  # the sun's 0.2666 deg
    # a 3-degree disc split off an environment keeps its size (solid angle 2 pi (1 - cos a))
    d = weft.ibl.cube_texel_directions(64).reshape(-1, 3)
    toward = np.array([0.3, 0.8, 0.2]) / np.linalg.norm([0.3, 0.8, 0.2])
    faces = np.full((6 * 64 * 64, 3), 0.2, np.float32)
    faces[d @ toward > np.cos(np.radians(3.0))] = 500.0
    scene = weft.Scene()
    weft.scenes.light_with_environment(scene, weft.ibl.CubeMap(faces.reshape(6, 64, 64, 3)),
                                       sun_lights=1)
    assert scene.lights[-1].angular_radius == pytest.approx(np.radians(3.0), rel=0.2)
