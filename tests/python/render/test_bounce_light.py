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
from weft.reference import LINEAR_STORAGE_RTOL

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
    debug = make_renderer(96, 72, bounce=True, ambient_occlusion=0).render_debug(scene, camera)
    rgb, n = sphere_pixels(debug, sphere)
    assert len(rgb) > 1500
    c = (1.0 - n[:, 1]) / 2.0
    truth = KA * AMBIENT * (1.0 - c) + KA * GROUND * AMBIENT * c
    err = np.abs(rgb[:, 0] - truth) / truth
    assert err.mean() < 0.01 and err.max() < 0.03, (err.mean(), err.max())
    # the lower side, which sees mostly ground, is clearly darker than the upper
    assert rgb[n[:, 1] < -0.7, 0].mean() < 0.75 * rgb[n[:, 1] > 0.7, 0].mean()


def _sunlit_ground_seen(p, n, centre, radius, sun, rng, samples=4000):
    """Ray-cast truth: the cosine-weighted fraction of the hemisphere of (p, n) that sees the
    ground y = 0 lit by the sun, past a sphere (centre, radius) that blocks both the view and
    the sun."""
    t = np.cross(n, (0.0, 0.0, 1.0) if abs(n[2]) < 0.9 else (1.0, 0.0, 0.0))
    t /= np.linalg.norm(t)
    b = np.cross(n, t)
    u1, u2 = rng.random(samples), rng.random(samples)
    r, phi = np.sqrt(u1), 2.0 * np.pi * u2
    d = (r * np.cos(phi))[:, None] * t + (r * np.sin(phi))[:, None] * b + \
        np.sqrt(1.0 - u1)[:, None] * n

    def hits(origin, dirs):  # (N, 3) origins or one origin, unit dirs: the sphere ahead
        oc = origin - centre
        bb = np.sum(dirs * oc, axis=-1)
        cc = np.sum(oc * oc, axis=-1) - radius ** 2
        disc = bb * bb - cc
        return (disc > 0.0) & (-bb + np.sqrt(np.maximum(disc, 0.0)) > 1e-4)

    down = d[:, 1] < -1e-6
    dist = -p[1] / np.where(down, d[:, 1], -1.0)
    ground = down & ~hits(p + 1e-4 * n, d)
    x = p + dist[:, None] * d
    lit = ground & ~hits(x, np.broadcast_to(sun, x.shape))
    return lit.mean()


def test_the_unlit_side_sees_the_ground_from_where_it_is(make_renderer):
    """A sphere resting on a sunlit ground: its unlit side is lit by the ground alone, and the
    ground near the sphere lies in its shadow. From the sphere's centre the lower side would see
    that shadow where it sees the sunlit ground beside it: one capture point left the sides
    16% too dark. Truth: a ray cast of the sunlit ground each pixel's point sees."""
    sun = np.array([0.55, 0.62, 0.36])
    sun /= np.linalg.norm(sun)
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(40.0, 40.0, 4, 4),
                   weft.Material(ka=(GROUND,) * 3, kd=(GROUND,) * 3, ks=(0.0,) * 3),
                   cast_shadows=False)
    radius, centre = 0.5, np.array([0.0, 0.5, 0.0])
    sphere = scene.add_mesh(weft.Mesh.uv_sphere(radius, 64, 32),
                            weft.Material(ka=(KA,) * 3, kd=(KA,) * 3, ks=(0.0,) * 3),
                            transform=_translate(*centre))
    scene.ambient = (0.0,) * 3
    for i, light in enumerate(scene.lights):
        light.intensity = 0.0
        light.cast_shadows = False
        scene.set_light(i, light)
    scene.add_light(weft.DirectionalLight(direction=tuple(-sun), color=(1.0, 1.0, 1.0),
                                          intensity=1.0, cast_shadows=True))
    camera = weft.Camera(position=(0.0, 0.5, 2.2), target=(0.0, 0.5, 0.0), fov_y=0.7)
    debug = make_renderer(96, 72, bounce=True).render_debug(scene, camera)
    mask = debug["instance"] == sphere
    shown = debug["linear"][..., 0][mask]
    normals = debug["normal"][mask][:, :3]
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    unlit = normals @ sun < -0.1
    rng = np.random.default_rng(7)
    lit_ground = GROUND * sun[1]  # the sunlit ground's radiance (weft's n.l L K_D)
    truth = np.array([KA * lit_ground * _sunlit_ground_seen(centre + radius * n, n, centre,
                                                            radius, sun, rng)
                      for n in normals[unlit]])
    for lo, hi in ((-1.0, -0.5), (-0.5, 0.0)):
        band = (normals[unlit][:, 1] >= lo) & (normals[unlit][:, 1] < hi)
        assert band.sum() > 15
        ratio = shown[unlit][band].sum() / truth[band].sum()
        # measured 0.95 / 1.01 (one capture point at the centre: 0.94 / 0.84)
        assert abs(ratio - 1.0) < 0.08, (lo, hi, ratio)


@pytest.mark.parametrize("sky", ["environment", "ambient"])
def test_a_mirror_sphere_reflects_the_ground_where_its_rays_meet_it(make_renderer, sky):
    """A black mirror sphere resting on a sunlit white ground reflects, along each pixel's
    reflected ray, the ground that ray meets: sunlit or in the sphere's shadow. Looked up from
    the capture's centre instead, the rays of the lower half end in the shadow under the
    sphere (mean error 36% of the sunlit ground, measured); with the capture's depths they meet
    the ground where they should (7%, the rest the soft shadow's edge and the capture's 16 x 16
    texels). The same under a black ambient sky (no environment): 13%, of which 8% is the
    split-sum fit's DFG (Karis 2014) that the ambient's reflection is weighted with (0.917 at
    this lobe's roughness for F0 = 1; the environment's is Schlick's Fresnel alone); 85% before
    a caster reflected its capture there (it reflected only the sky). Truth: a ray cast of each
    reflected ray and of the sun's shadow."""
    sun = np.array([0.55, 0.62, 0.36])
    sun /= np.linalg.norm(sun)
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(40.0, 40.0, 4, 4),
                   weft.Material(ka=(0.0,) * 3, kd=(0.8,) * 3, ks=(0.0,) * 3),
                   cast_shadows=False)
    radius, centre = 0.5, np.array([0.0, 0.5, 0.0])
    sphere = scene.add_mesh(weft.Mesh.uv_sphere(radius, 96, 48),
                            weft.Material(ka=(0.0,) * 3, kd=(0.0,) * 3, ks=(0.0,) * 3,
                                          shininess=4000.0, reflectivity=(1.0,) * 3),
                            transform=_translate(*centre))
    scene.ambient = (0.0 if sky == "environment" else 1e-4,) * 3
    for i, light in enumerate(scene.lights):
        light.intensity = 0.0
        light.cast_shadows = False
        scene.set_light(i, light)
    scene.add_light(weft.DirectionalLight(direction=tuple(-sun), color=(1.0, 1.0, 1.0),
                                          intensity=1.0, cast_shadows=True))
    if sky == "environment":  # a black sky
        dark = np.full((6, 16, 16, 3), 1e-4, np.float32)
        scene.set_environment(weft.ibl.Environment(weft.ibl.CubeMap(dark)), dome_lights=0)
    eye = np.array([0.0, 0.6, 2.4])
    camera = weft.Camera(position=tuple(eye), target=(0.0, 0.35, 0.0), fov_y=0.6)
    # the ambient is read as a sky where ambient occlusion is on (its default)
    debug = make_renderer(128, 96, bounce=True,
                          ambient_occlusion=8 if sky == "ambient" else 0).render_debug(scene,
                                                                                       camera)
    mask = debug["instance"] == sphere
    p = debug["position"][mask][:, :3].astype(np.float64)
    n = debug["normal"][mask][:, :3].astype(np.float64)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    v = eye - p
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    r = 2.0 * np.sum(n * v, axis=1, keepdims=True) * n - v
    lower = (n[:, 1] < -0.2) & (r[:, 1] < -0.05)
    assert lower.sum() > 500
    p, r = p[lower], r[lower]
    hit = p + (-p[:, 1] / r[:, 1])[:, None] * r  # where each reflected ray meets the ground
    oc = hit - centre
    b = oc @ sun
    disc = b * b - (np.sum(oc * oc, axis=1) - radius ** 2)
    shadowed = (disc > 0.0) & (-b + np.sqrt(np.maximum(disc, 0.0)) > 0.0)
    lit_ground = 0.8 * sun[1]
    truth = np.where(shadowed, 0.0, lit_ground)
    assert 0.05 < shadowed.mean() < 0.5  # both kinds of ground are reflected
    err = np.abs(debug["linear"][..., 0][mask][lower] - truth).mean() / lit_ground
    assert err < (0.12 if sky == "environment" else 0.16), err


def test_without_bounce_the_ambient_is_unoccluded(make_renderer):
    scene, camera, sphere = floating_sphere()
    r = make_renderer(96, 72, bounce=False, ambient_occlusion=0)
    rgb, _ = sphere_pixels(r.render_debug(scene, camera), sphere)
    np.testing.assert_allclose(rgb, KA * AMBIENT, rtol=LINEAR_STORAGE_RTOL)


def test_the_environment_the_ground_hides_is_replaced_by_the_ground(make_renderer):
    """Under a uniform environment of radiance 1 the ground's radiance is GROUND (its diffuse
    light E / pi = 1 times K_D), so the caster gets K_D (1 - c) from the sky it sees and
    K_D GROUND c from the ground -- not the environment's lower half."""
    scene, camera, sphere = floating_sphere(ambient=0.0)
    faces = np.ones((6, 16, 16, 3), np.float32)
    scene.set_environment(weft.ibl.CubeMap(faces))
    debug = make_renderer(96, 72, bounce=True).render_debug(scene, camera)
    rgb, n = sphere_pixels(debug, sphere)
    c = (1.0 - n[:, 1]) / 2.0
    truth = KA * (1.0 - c) + KA * GROUND * c
    err = np.abs(rgb[:, 0] - truth) / truth
    assert err.mean() < 0.015 and err.max() < 0.04, (err.mean(), err.max())


def test_bounce_captures_are_reused_while_the_scene_stands_still(make_renderer):
    scene, camera, sphere = floating_sphere()
    r = make_renderer(48, 36, bounce=True)
    first = r.render(scene, camera)
    names = [p["name"] for p in r.stats["passes"]]
    # two rounds of six faces: the second sees the ground lit by the sphere (caster_bounce)
    assert "bounce_sh_first" in names and "bounce_sh" in names
    assert "bounce_radiance_first" in names and "bounce_radiance" in names
    assert sum(n.startswith("bounce0[") for n in names) == 6
    assert sum(n.startswith("bounce1[") for n in names) == 6
    again = r.render(scene, camera)
    assert "bounce" in r.stats["reused"]
    # only the casters' radiance (a few dozen fragments) is summed again: lights may move
    assert [p["name"] for p in r.stats["passes"] if p["name"].startswith("bounce")] == \
        ["bounce_radiance"]
    np.testing.assert_array_equal(first, again)
    scene.set_transform(sphere, _translate(0.0, 2.0, 0.0))  # moved: captured again
    r.render(scene, camera)
    assert "bounce_sh" in [p["name"] for p in r.stats["passes"]]
    r.render(scene, camera)
    r.pcf_radius = 2  # new settings shade the receivers differently: captured again
    r.render(scene, camera)
    assert "bounce_sh" in [p["name"] for p in r.stats["passes"]]


def test_no_bounce_passes_without_receivers(make_renderer):
    scene, camera, sphere = floating_sphere(ground_casts=True)  # nothing is a receiver
    r = make_renderer(48, 36, bounce=True)
    r.render(scene, camera)
    assert not any(p["name"].startswith("bounce") for p in r.stats["passes"])


# ---------------------------------------------------------------------------------------------
# Ambient occlusion: the constant ambient of a scene without an environment, read as a uniform
# sky, occluded by the casters through a dome of soft shadow lights
# ---------------------------------------------------------------------------------------------

def sphere_over_ground(radius: float = 0.5, height: float = 1.0):
    """A black ground (K_D = 0, so the multi-bounce correction is the identity: the fit's
    cubic never exceeds v at rho = 0) with K_A = 1 under a sphere: what the ground shows is
    I_A times the visibility of the sky."""
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(40.0, 40.0, 1, 1),
                   weft.Material(ka=(1.0,) * 3, kd=(0.0,) * 3, ks=(0.0,) * 3), cast_shadows=False)
    scene.add_mesh(weft.Mesh.uv_sphere(radius, 64, 32),
                   weft.Material(ka=(0.5,) * 3, kd=(0.5,) * 3, ks=(0.0,) * 3),
                   transform=_translate(0.0, height, 0.0))
    scene.ambient = (1.0,) * 3
    camera = weft.Camera(position=(0.0, 4.0, 4.0), target=(0.0, 0.0, 0.0), fov_y=0.9)
    return scene, camera


def test_ambient_occlusion_under_a_sphere_matches_the_view_factor(make_renderer):
    """A sphere of radius r whose centre is at distance D from a ground point, seen at angle
    theta from the ground's normal and wholly above its horizon, hides (r / D)^2 cos(theta) of
    the sky's cosine-weighted light (its view factor): the ground shows 1 - that."""
    r_s, h = 0.5, 1.0
    scene, camera = sphere_over_ground(r_s, h)
    # measured: within 0.01 at 64 dome lights, 0.033 at 16, 0.054 at the default 8 (the dome's
    # quantisation of the sky)
    for lights, blur, tolerance in ((64, 0.0, 0.02), (16, 4.0, 0.045), (8, 4.0, 0.07)):
        debug = make_renderer(128, 128, ambient_occlusion=lights, ambient_occlusion_blur=blur,
                              bounce=False).render_debug(scene, camera)
        ground = debug["instance"] == 0
        p = debug["position"][ground]
        shown = debug["linear"][..., 0][ground]
        x = np.hypot(p[:, 0], p[:, 2])
        dist = np.hypot(x, h)
        truth = 1.0 - (r_s / dist) ** 2 * (h / dist)
        for lo, hi in ((0.0, 0.15), (0.4, 0.6), (0.9, 1.1), (1.8, 2.2)):
            ring = (x >= lo) & (x < hi)
            assert ring.sum() > 20
            err = abs(shown[ring].mean() - truth[ring].mean())
            assert err < tolerance, (lights, lo, hi, shown[ring].mean(), truth[ring].mean())
    # without the dome the ambient is unoccluded everywhere
    off = make_renderer(128, 128, ambient_occlusion=0, bounce=False).render_debug(scene, camera)
    np.testing.assert_allclose(off["linear"][..., 0][ground], 1.0, atol=1e-5)


def test_ambient_occlusion_is_skipped_where_nothing_needs_it(make_renderer):
    scene, camera = sphere_over_ground()
    r = make_renderer(48, 48, ambient_occlusion=8)
    r.render(scene, camera)
    assert any(p["name"].startswith("dome[") for p in r.stats["passes"])
    scene.ambient = (0.0, 0.0, 0.0)  # no ambient: nothing to occlude
    r.render(scene, camera)
    assert not any(p["name"].startswith("dome") for p in r.stats["passes"])
    with pytest.raises(weft.InvalidArgument, match="multiple of 8"):
        r.ambient_occlusion = 12


def _ground_next_to_and_far_from(debug, radius: float):
    ground = debug["mask"] & (debug["instance"] == 0)
    p = debug["position"]
    r = np.hypot(p[..., 0], p[..., 2])
    lum = debug["linear"][..., :3] @ np.array([0.2126, 0.7152, 0.0722])
    near, far = ground & (r > 1.05 * radius) & (r < 1.5 * radius), ground & (r > 4.0 * radius)
    assert near.sum() > 50 and far.sum() > 50, (near.sum(), far.sum())
    return float(lum[near].mean()), float(lum[far].mean())


@pytest.mark.parametrize("lighting", ["environment", "ambient"])
def test_a_caster_never_brightens_the_ground_by_light_it_hides(make_renderer, lighting):
    """Without a dome nothing occludes the ground's sky, so the light a grey sphere resting on
    it reflects (caster_bounce.glsl) comes with the sky it hides taken away: under a uniform
    sky of radiance 1 the sphere (K_D 0.5) is darker than what it hides, so the ground beside
    it must not be brighter than open ground; the caster's net effect there is a darkening
    (before the net: +9% brighter next to it)."""
    scene = weft.Scene()
    matte = dict(ks=(0.0,) * 3, environment_diffuse=1.0)
    scene.add_mesh(weft.Mesh.plane(40.0, 40.0, 2, 2),
                   weft.Material(ka=(0.5,) * 3, kd=(0.5,) * 3, **matte), cast_shadows=False)
    scene.add_mesh(weft.Mesh.uv_sphere(0.5, 48, 24),
                   weft.Material(ka=(0.5,) * 3, kd=(0.5,) * 3, **matte),
                   transform=_translate(0.0, 0.5, 0.0))
    if lighting == "environment":
        scene.set_environment(weft.ibl.CubeMap(np.ones((6, 16, 16, 3), np.float32)),
                              dome_lights=0)
        scene.ambient = (0.0,) * 3
    else:
        scene.ambient = (1.0,) * 3
    camera = weft.Camera(position=(0.0, 3.5, 3.5), target=(0.0, 0.0, 0.0), fov_y=0.9)
    on = make_renderer(128, 96, bounce=True).render_debug(scene, camera)
    off = make_renderer(128, 96, bounce=False).render_debug(scene, camera)
    near_on, far_on = _ground_next_to_and_far_from(on, 0.5)
    near_off, far_off = _ground_next_to_and_far_from(off, 0.5)
    assert far_on == pytest.approx(far_off, rel=0.01)  # far off, the caster does nothing
    assert near_off == pytest.approx(far_off, rel=0.01)  # no dome, no bounce: uniform
    assert near_on < near_off, (near_on, near_off)  # the sphere (0.5) hides a sky of 1
    assert near_on > 0.5 * near_off, (near_on, near_off)  # ... and reflects some light back
