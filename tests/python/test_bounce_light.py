"""One bounce of diffuse light (issue 18, render/BounceProbes.h): the receivers (instances that
cast no shadow) send their radiance to the shadow casters and hide the sky / ambient from them.

The truth is analytic: a caster far above a wide, uniformly bright ground sees the ground over
the fraction c(n) = (1 - n_y) / 2 of its cosine-weighted hemisphere (the view factor of a
surface tilted by acos(n_y) towards an infinite plane) and the sky over the rest, so its
ambient-lit radiance is K_A I_A (1 - c) + K_D L_ground c. The path-traced comparison is in
test_picture_reference.py.
"""

from __future__ import annotations

import numpy as np
import pytest

import weft
import weft.ibl

KA = 0.8           # the caster's K_A = K_D
GROUND = 0.5       # the ground's K_A = K_D: its radiance is GROUND * I_A under the ambient alone
AMBIENT = 1.0


def _translate(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = (x, y, z)
    return m


def floating_sphere(ambient: float = AMBIENT, ground_casts: bool = False):
    scene = weft.Scene()
    # wide enough that its horizon sits within 0.1 degrees of the sphere's
    scene.add_mesh(weft.Mesh.plane(4000.0, 4000.0, 1, 1),
                   weft.Material(ka=(GROUND,) * 3, kd=(GROUND,) * 3, ks=(0.0,) * 3,
                                 environment_diffuse=1.0),
                   cast_shadows=ground_casts)
    sphere = scene.add_mesh(weft.Mesh.uv_sphere(0.5, 64, 32),
                            weft.Material(ka=(KA,) * 3, kd=(KA,) * 3, ks=(0.0,) * 3,
                                          environment_diffuse=1.0),
                            transform=_translate(0.0, 3.0, 0.0))
    scene.ambient = (ambient,) * 3
    camera = weft.Camera(position=(0.0, 3.0, 2.2), target=(0.0, 3.0, 0.0), fov_y=0.7)
    return scene, camera, sphere


def sphere_pixels(debug, sphere: int):
    mask = debug["instance"] == sphere
    return debug["linear"][..., :3][mask], debug["normal"][mask]


def test_a_caster_sees_the_ground_it_floats_over(make_renderer):
    scene, camera, sphere = floating_sphere()
    debug = make_renderer(96, 72, bounce=True).render_debug(scene, camera)
    rgb, n = sphere_pixels(debug, sphere)
    assert len(rgb) > 1500
    c = (1.0 - n[:, 1]) / 2.0
    truth = KA * AMBIENT * (1.0 - c) + KA * GROUND * AMBIENT * c
    err = np.abs(rgb[:, 0] - truth) / truth
    assert err.mean() < 0.01 and err.max() < 0.03, (err.mean(), err.max())
    # the lower side, which sees mostly ground, is clearly darker than the upper
    assert rgb[n[:, 1] < -0.7, 0].mean() < 0.75 * rgb[n[:, 1] > 0.7, 0].mean()


def test_without_bounce_the_ambient_is_unoccluded(make_renderer):
    scene, camera, sphere = floating_sphere()
    rgb, _ = sphere_pixels(make_renderer(96, 72, bounce=False).render_debug(scene, camera), sphere)
    np.testing.assert_allclose(rgb, KA * AMBIENT, rtol=1e-4)


def test_the_environment_the_ground_hides_is_replaced_by_the_ground(make_renderer):
    """Under a uniform environment of radiance 1 the ground's radiance is GROUND (its diffuse
    light E / pi = 1 times K_D), so the caster gets K_D (1 - c) from the sky it sees and
    K_D GROUND c from the ground -- not the environment's lower half."""
    scene, camera, sphere = floating_sphere(ambient=0.0)
    faces = np.ones((6, 16, 16, 3), np.float32)
    scene.set_environment(weft.ibl.CubeMap(faces))
    debug = make_renderer(96, 72).render_debug(scene, camera)
    rgb, n = sphere_pixels(debug, sphere)
    c = (1.0 - n[:, 1]) / 2.0
    truth = KA * (1.0 - c) + KA * GROUND * c
    err = np.abs(rgb[:, 0] - truth) / truth
    assert err.mean() < 0.015 and err.max() < 0.04, (err.mean(), err.max())


def test_bounce_captures_are_reused_while_the_scene_stands_still(make_renderer):
    scene, camera, sphere = floating_sphere()
    r = make_renderer(48, 36)
    first = r.render(scene, camera)
    names = [p["name"] for p in r.stats["passes"]]
    assert "bounce_sh" in names and sum(n.startswith("bounce[") for n in names) == 6
    again = r.render(scene, camera)
    assert "bounce" in r.stats["reused"]
    assert not any(p["name"].startswith("bounce") for p in r.stats["passes"])
    np.testing.assert_array_equal(first, again)
    scene.set_transform(sphere, _translate(0.0, 2.0, 0.0))  # moved: captured again
    r.render(scene, camera)
    assert "bounce_sh" in [p["name"] for p in r.stats["passes"]]


def test_no_bounce_passes_without_receivers(make_renderer):
    scene, camera, sphere = floating_sphere(ground_casts=True)  # nothing is a receiver
    r = make_renderer(48, 36)
    r.render(scene, camera)
    assert not any(p["name"].startswith("bounce") for p in r.stats["passes"])
