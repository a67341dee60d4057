"""The environment's dome of shadow lights in the renderer (SPEC §4.5, eq. 2.21-2.23): a sphere
above a ground plane under a sky; the ground's diffuse light against NumPy evaluations of
eq. 2.23 and of the exact visibility-weighted irradiance, and the dome maps' reuse/round robin."""

from __future__ import annotations

import numpy as np
import pytest
import weft
import weft.ibl
from ibl_envs import sky_gradient, to_faces
from weft.reference import ibl as ref_ibl

CENTRE, RADIUS = np.array([0.0, 0.8, 0.0]), 0.5
FACES = to_faces(sky_gradient(), 32, supersample=2)


def dome_scene(env, lights: int, **kw) -> weft.Scene:
    scene = weft.Scene()
    scene.ambient = (0.0, 0.0, 0.0)
    mat = weft.Material(kd=(1.0, 1.0, 1.0), environment_diffuse=1.0)
    scene.add_mesh(weft.Mesh.plane(4.0, 4.0), mat)
    m = np.eye(4, dtype=np.float32)
    m[:3, :3] *= RADIUS
    m[:3, 3] = CENTRE
    scene.add_mesh(weft.Mesh.uv_sphere(1.0, 48, 24), mat, transform=m)
    scene.set_environment(env, dome_lights=lights, **kw)
    return scene


def camera() -> weft.Camera:
    return weft.Camera(position=(0.0, 3.0, 3.0), target=(0.0, 0.0, 0.0), fov_y=0.9)


def dome_passes(stats) -> list:
    return [p["name"] for p in stats["passes"] if p["name"].startswith("dome")]


def test_dome_diffuse_converges_to_the_visibility_weighted_irradiance(make_renderer) -> None:
    # each dome light is soft (a cone of its cell's spread, environment.glsl), so the ground is no
    # longer eq. 2.23 with one-tap visibility per light; against the exact integral it is close
    # and closer with more lights. tests/python/render/test_dome_truth.py measures it in depth.
    env = weft.ibl.Environment(FACES)
    r = make_renderer(64, 64)
    exact_error = {}
    for n in (16, 64):
        debug = r.render_debug(dome_scene(env, n, dome_map_size=256), camera())
        ground = debug["mask"] & (debug["instance"] == 0)
        p, normal = debug["position"][ground], debug["normal"][ground]
        got = debug["linear"][ground][:, :3]
        sel = np.arange(len(p))[::9]
        exact = np.stack([ref_ibl.visible_irradiance(FACES, p[k], normal[k], CENTRE, RADIUS)
                          for k in sel]) / np.pi
        exact_error[n] = float(np.abs(got[sel] - exact).mean() / np.abs(exact).mean())
    # mean relative error, measured 0.017 / 0.0037
    assert exact_error[16] < 0.03 and exact_error[64] < 0.5 * exact_error[16], exact_error


def test_dome_maps_are_reused_and_refreshed_round_robin(make_renderer) -> None:
    env = weft.ibl.Environment(to_faces(sky_gradient(), 8))
    r = make_renderer(32, 32)
    scene = dome_scene(env, 16, dome_map_size=64, dome_refresh=4)
    r.render(scene, camera())
    assert len(dome_passes(r.stats)) == 16  # a new dome renders every map
    r.render(scene, camera())
    assert dome_passes(r.stats) == [] and sum(n.startswith("dome") for n in r.stats["reused"]) == 16
    # the sphere moves inside the ground's bounds: frusta stay, every map is stale, 4 of them
    # are refreshed per frame (the others keep their stale contents) until all are current
    m = np.eye(4, dtype=np.float32)
    m[:3, :3] *= RADIUS
    m[:3, 3] = CENTRE + [0.3, 0.0, 0.0]
    scene.set_transform(1, m)
    seen = set()
    for _ in range(4):
        r.render(scene, camera())
        passes = dome_passes(r.stats)
        assert len(passes) == 4 and not seen & set(passes)
        seen |= set(passes)
    assert len(seen) == 16
    r.render(scene, camera())
    assert dome_passes(r.stats) == []  # all fresh again
    # no dome -> no dome passes, nothing reused
    r.render(dome_scene(env, 0), camera())
    assert dome_passes(r.stats) == [] and not any(n.startswith("dome") for n in r.stats["reused"])


@pytest.mark.parametrize("kw", [dict(dome_lights=12), dict(dome_lights=72),
                                dict(dome_lights=16, dome_map_size=8),
                                dict(dome_lights=16, dome_refresh=-1)])
def test_bad_dome_parameters_are_rejected(kw) -> None:
    with pytest.raises(weft.InvalidArgument):
        weft.Scene().set_environment(weft.ibl.Environment(to_faces(sky_gradient(), 8)), **kw)
