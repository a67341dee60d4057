"""Point and spot lights (SPEC §1.2): attenuation (eq. 2.3, 2.4), the spot cone and cookie,
many lights per frame, and their shadow maps (spot: one perspective view, point: six views)
against the NumPy oracle of weft.reference, evaluated from the same frame's debug outputs."""

from __future__ import annotations

import math
from typing import Dict, List, Sequence, Tuple

import numpy as np
import pytest
import weft
from weft import reference as ref

LINEAR_TOL = 1e-3
#: Fraction of covered pixels allowed above LINEAR_TOL where a shadow test sits exactly on a
#: tap's depth (float32 GPU vs float64 NumPy) or a cookie texel is filtered in 8-bit steps.
EDGE_FRACTION = 0.01


def translation(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = (x, y, z)
    return m


def stage(lights: Sequence[object], ks: float = 0.3) -> Tuple[weft.Scene, weft.Camera,
                                                                List[weft.Material]]:
    """An untextured ground plane with a floating box and sphere, lit by `lights`."""
    scene = weft.Scene()
    mats = [weft.Material(ka=(1, 1, 1), kd=(0.8, 0.8, 0.8), ks=(ks, ks, ks), shininess=24.0),
            weft.Material(kd=(0.7, 0.3, 0.2), ks=(ks, ks, ks), shininess=40.0),
            weft.Material(kd=(0.2, 0.5, 0.7), ks=(ks, ks, ks), shininess=12.0)]
    scene.add_mesh(weft.Mesh.plane(8.0, 8.0, 4, 4), mats[0])
    scene.add_mesh(weft.Mesh.box((0.6, 0.5, 0.6)), mats[1], translation(0.4, 0.9, 0.2))
    scene.add_mesh(weft.Mesh.uv_sphere(0.35, 32, 16), mats[2], translation(-0.9, 0.6, -0.3))
    for light in lights:
        scene.add_light(light)
    scene.ambient = (0.05, 0.05, 0.05)
    scene.background = (0.0, 0.0, 0.1)
    camera = weft.Camera(position=(0.5, 4.5, 5.0), target=(0.0, 0.0, 0.0), fov_y=0.9)
    return scene, camera, mats


def light_visibility(renderer: weft.Renderer, scene: weft.Scene, debug: Dict[str, np.ndarray],
                     index: int) -> np.ndarray:
    """NumPy PCF visibility of light `index` on every covered pixel (1 elsewhere)."""
    info = renderer.shadow_info(index)
    assert info["active"]
    maps = np.stack([renderer.shadow_map(index, view) for view in range(len(info["views"]))])
    mask = debug["mask"]
    vis = np.ones(mask.shape)
    vis[mask] = ref.pcf_visibility(debug["position"][mask], debug["normal"][mask],
                                   scene.lights[index], maps, info)
    return vis


def oracle_error(renderer: weft.Renderer, scene: weft.Scene, camera: weft.Camera,
                 mats: List[weft.Material], shadows: Sequence[int] = ()) -> Tuple[np.ndarray,
                                                                                Dict]:
    debug = renderer.render_debug(scene, camera)
    visibility = {i: light_visibility(renderer, scene, debug, i) for i in shadows}
    materials = [ref.SurfaceMaterial.from_weft(m) for m in mats]
    oracle = ref.shade_debug_frame(debug, camera.position, scene.lights, scene.ambient,
                                   scene.background, materials, shadow=visibility or None,
                                   frame_albedo=True)
    if not shadows:
        assert np.all(debug["shadow"] == 1.0)
    mask = debug["mask"]
    err = ref.storage_excess(debug["linear"][..., :3], oracle[..., :3]).max(axis=-1)[mask]
    return err, debug


# --------------------------------------------------------------------------------------------
# The oracle's formulas
# --------------------------------------------------------------------------------------------

def test_attenuation_formulas() -> None:
    poly = ref.LightDesc(kind="point", attenuation=(1.0, 0.5, 0.25))
    assert ref.attenuation(poly, 2.0) == pytest.approx(1.0 / (1.0 + 1.0 + 1.0))
    radius = ref.LightDesc(kind="point", radius=4.0)
    assert ref.attenuation(radius, 2.0) == pytest.approx(0.75)
    assert ref.attenuation(radius, 5.0) == 0.0
    light = weft.PointLight(attenuation=(1.0, 0.5, 0.25))
    assert light.attenuation_at(2.0) == pytest.approx(1.0 / 3.0)
    light.radius = 4.0
    assert light.attenuation_at(2.0) == pytest.approx(0.75)


def test_spot_cone_profile_in_numpy() -> None:
    spot = ref.LightDesc(kind="spot", position=(0, 2, 0), direction=(0, -1, 0),
                         inner_angle=0.2, outer_angle=0.4)
    angles = np.array([0.0, 0.19, 0.3, 0.41, 1.0])
    p = np.stack([2.0 * np.tan(angles), np.zeros(5), np.zeros(5)], axis=-1)
    l, radiance = ref.incident(spot, p)
    np.testing.assert_allclose(np.linalg.norm(l, axis=-1), 1.0)
    cone = radiance[:, 0] * (2.0 / np.cos(angles)) ** 0  # attenuation 1 (k_c = 1)
    assert cone[0] == pytest.approx(1.0) and cone[1] == pytest.approx(1.0)
    assert 0.0 < cone[2] < 1.0
    assert cone[3] == 0.0 and cone[4] == 0.0
    t = (math.cos(0.3) - math.cos(0.4)) / (math.cos(0.2) - math.cos(0.4))
    assert cone[2] == pytest.approx(t * t * (3 - 2 * t))


# --------------------------------------------------------------------------------------------
# GPU against the oracle
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("form", ["polynomial", "radius"])
def test_point_light_matches_oracle(make_renderer, form: str) -> None:
    kwargs = dict(attenuation=(0.5, 0.3, 0.2)) if form == "polynomial" else dict(radius=3.5)
    light = weft.PointLight(position=(0.2, 1.8, 0.6), color=(1.0, 0.8, 0.6), intensity=2.5,
                            cast_shadows=False, **kwargs)
    scene, camera, mats = stage([light])
    err, debug = oracle_error(make_renderer(160, 120), scene, camera, mats)
    assert err.max() <= LINEAR_TOL, f"max |GPU - oracle| = {err.max():.3g}"
    lit = debug["linear"][debug["mask"]][:, :3].max(axis=-1)
    if form == "radius":  # beyond the radius the ground gets only the ambient term
        far = np.linalg.norm(debug["position"] - np.array([0.2, 1.8, 0.6]), axis=-1) > 3.5
        assert np.any(far & debug["mask"])
        assert debug["linear"][far & debug["mask"]][:, :3].max() <= 0.05 + 1e-3
    assert lit.max() > 0.5


def test_spot_light_with_cookie_matches_oracle(make_renderer) -> None:
    rng = np.random.default_rng(5)
    cookie = np.zeros((16, 16, 3), np.uint8)
    cookie[..., 0] = np.linspace(40, 255, 16).astype(np.uint8)[None, :]  # red ramp along u
    cookie[..., 1] = np.linspace(255, 40, 16).astype(np.uint8)[:, None]  # green ramp along v
    cookie[..., 2] = rng.integers(100, 255, (16, 16))
    spot = weft.SpotLight(position=(0.3, 3.0, 0.8), direction=(-0.1, -1.0, -0.2),
                          color=(1.0, 1.0, 1.0), intensity=3.0, inner_angle=0.35,
                          outer_angle=0.6, attenuation=(1.0, 0.1, 0.05),
                          cookie=weft.Texture(cookie, srgb=False, mipmaps=False),
                          cast_shadows=False)
    scene, camera, mats = stage([spot])
    err, debug = oracle_error(make_renderer(160, 120), scene, camera, mats)
    # The cookie is filtered by the sampler: lavapipe filters UNORM8 in 8-bit fixed point, so a
    # filtered cookie value may be one 8-bit level off; the radiance is at most 3 (intensity).
    assert err.max() <= 3.0 / 255.0 + LINEAR_TOL and err.mean() < LINEAR_TOL, err.max()
    # the cone leaves most of the ground dark and the cookie tints the lit disc
    ground = debug["mask"] & (np.abs(debug["position"][..., 1]) < 1e-3)
    lit = ground & (debug["linear"][..., :3].max(axis=-1) > 0.2)
    assert 0.02 < lit.sum() / ground.sum() < 0.6
    red = debug["linear"][lit][:, 0]
    x = debug["position"][lit]
    assert np.corrcoef(red, x[:, 0])[0, 1] > 0.5  # red grows along +u (world +X here)


def test_sixteen_mixed_lights_match_oracle(make_renderer) -> None:
    rng = np.random.default_rng(7)
    lights: List[object] = []
    for i in range(16):
        color = tuple(rng.uniform(0.2, 1.0, 3))
        if i % 3 == 0:
            lights.append(weft.DirectionalLight(direction=tuple(rng.normal(size=3) - [0, 2, 0]),
                                                color=color, intensity=0.15, cast_shadows=False))
        elif i % 3 == 1:
            lights.append(weft.PointLight(position=(rng.uniform(-2, 2), rng.uniform(0.5, 2),
                                                    rng.uniform(-2, 2)),
                                          color=color, intensity=0.6, attenuation=(1, 0.2, 0.3),
                                          cast_shadows=False))
        else:
            target = np.array([rng.uniform(-1, 1), 0.0, rng.uniform(-1, 1)])
            pos = np.array([rng.uniform(-2, 2), 2.5, rng.uniform(-2, 2)])
            lights.append(weft.SpotLight(position=tuple(pos), direction=tuple(target - pos),
                                         color=color, intensity=1.0, inner_angle=0.2,
                                         outer_angle=0.45, radius=6.0, cast_shadows=False))
    scene, camera, mats = stage(lights)
    err, _ = oracle_error(make_renderer(128, 96), scene, camera, mats)
    assert err.max() <= LINEAR_TOL, f"max |GPU - oracle| = {err.max():.3g}"


@pytest.mark.parametrize("kind", ["spot", "point"])
def test_spot_and_point_shadows_match_numpy_pcf(make_renderer, kind: str) -> None:
    if kind == "spot":
        light = weft.SpotLight(position=(1.5, 3.0, 1.0), direction=(-0.5, -1.0, -0.3),
                               intensity=2.0, inner_angle=0.5, outer_angle=0.8, radius=9.0)
    else:
        light = weft.PointLight(position=(0.6, 2.2, 0.5), intensity=2.0, radius=9.0)
    scene, camera, mats = stage([light], ks=0.1)
    renderer = make_renderer(160, 120, shadow_map_size=1024, pcf_radius=1)
    err, debug = oracle_error(renderer, scene, camera, mats, shadows=[0])
    info = renderer.shadow_info(0)
    assert info["perspective"] and len(info["views"]) == (6 if kind == "point" else 1)
    names = [p["name"] for p in renderer.stats["passes"]]
    shadow_passes = [n for n in names if n.startswith("shadow[0]")]
    assert len(shadow_passes) == len(info["views"]), names
    mask = debug["mask"]
    vis = light_visibility(renderer, scene, debug, 0)
    taps = 9
    agree = np.abs(vis[mask] - debug["shadow"][mask]) < 0.5 / taps
    assert agree.mean() >= 0.99, f"PCF agrees on {agree.mean():.2%} of pixels"
    ground = mask & (np.abs(debug["position"][..., 1]) < 1e-3)
    assert np.mean(debug["shadow"][ground] == 0.0) > 0.01, "the occluders cast no shadow"
    assert np.mean(err > LINEAR_TOL) <= EDGE_FRACTION, f"max err {err.max():.3g}"


def test_point_light_shadow_faces_cover_all_directions(make_renderer) -> None:
    """A point light among occluders below and on four sides: each shadow falls where the
    view of its direction (-Y, +-X, +-Z) puts it, and the floor between them is lit."""
    light = weft.PointLight(position=(0.0, 1.0, 0.0), intensity=1.0, radius=20.0)
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(12.0, 12.0, 4, 4), weft.Material())
    scene.add_mesh(weft.Mesh.box((0.4, 0.05, 0.4)), weft.Material(), translation(0, 0.6, 0))
    for x, z in ((1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)):
        scene.add_mesh(weft.Mesh.box((0.2, 1.0, 0.2)), weft.Material(), translation(x, 0.5, z))
    scene.add_light(light)
    camera = weft.Camera(position=(0.0, 9.0, 0.01), target=(0.0, 0.0, 0.0), fov_y=1.1)
    renderer = make_renderer(128, 128, shadow_map_size=512, pcf_radius=0)
    debug = renderer.render_debug(scene, camera)
    ground = debug["mask"] & (np.abs(debug["position"][..., 1]) < 1e-3)
    p = debug["position"]
    # the small box's shadow (seen from above around the box): the -Y view
    ring = np.maximum(np.abs(p[..., 0]), np.abs(p[..., 2]))
    below = ground & (ring > 0.3) & (ring < 0.42)
    assert below.sum() > 0 and np.all(debug["shadow"][below] == 0.0)
    vis = light_visibility(renderer, scene, debug, 0)
    assert np.mean(np.abs(vis[ground] - debug["shadow"][ground]) < 0.5) >= 0.99
    # behind each post, along the axis, the floor is shadowed; between them it is lit
    for x, z in ((1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)):
        behind = ground & (np.abs(p[..., 0] - 2.5 * x) < 0.05) & \
            (np.abs(p[..., 2] - 2.5 * z) < 0.05)
        assert behind.sum() > 0 and np.all(debug["shadow"][behind] == 0.0), (x, z)
    diagonal = ground & (np.abs(np.abs(p[..., 0]) - 2.0) < 0.1) & \
        (np.abs(np.abs(p[..., 2]) - 2.0) < 0.1)
    assert diagonal.sum() > 0 and np.all(debug["shadow"][diagonal] == 1.0)


@pytest.mark.parametrize("kind", ["spot", "point"])
def test_no_acne_under_point_and_spot_lights(make_renderer, kind: str) -> None:
    if kind == "spot":
        light = weft.SpotLight(position=(0.0, 2.0, 0.0), direction=(0.3, -1.0, 0.1),
                               inner_angle=0.9, outer_angle=1.3, radius=30.0)
    else:
        light = weft.PointLight(position=(0.0, 0.7, 0.0), radius=30.0)
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(10.0, 10.0, 8, 8), weft.Material())
    scene.add_light(light)
    camera = weft.Camera(position=(0.0, 3.0, 5.0), target=(0.0, 0.0, -1.0), fov_y=1.0)
    renderer = make_renderer(160, 120, shadow_map_size=1024)
    debug = renderer.render_debug(scene, camera)
    lit = debug["mask"] & (debug["linear"][..., :3].max(axis=-1) > 0.02)
    assert lit.mean() > 0.2
    shadowed = float(np.mean(debug["shadow"][lit] < 1.0))
    assert shadowed < 1e-3, f"{shadowed:.3%} of the lit plane is shadowed"


def test_light_validation_and_api() -> None:
    with pytest.raises(ValueError):
        weft.SpotLight(inner_angle=0.6, outer_angle=0.5)
    with pytest.raises(ValueError):
        weft.SpotLight(outer_angle=1.6)
    with pytest.raises(ValueError):
        weft.PointLight(attenuation=(0, 0, 0))
    with pytest.raises(ValueError):
        weft.PointLight(position=(0, math.nan, 0))
    with pytest.raises(ValueError):
        weft.PointLight(radius=-1.0)
    with pytest.raises(ValueError):
        weft.SpotLight(direction=(0, 0, 0))
    light = weft.PointLight()
    with pytest.raises(ValueError):
        light.intensity = -1.0
    assert light.intensity == 1.0
    scene = weft.Scene()
    ids = [scene.add_light(x) for x in (weft.DirectionalLight(), weft.PointLight(),
                                        weft.SpotLight())]
    assert ids == [0, 1, 2]
    kinds = [type(x).__name__ for x in scene.lights]
    assert kinds == ["DirectionalLight", "PointLight", "SpotLight"]
    scene.set_light(0, weft.SpotLight(position=(1, 2, 3)))
    assert isinstance(scene.lights[0], weft.SpotLight)
    assert "SpotLight" in repr(scene.lights[0])


def test_more_cookies_than_slots_is_an_error(make_renderer) -> None:
    scene, camera, _ = stage([])
    for i in range(5):
        img = np.full((4, 4, 3), 50 * i, np.uint8)
        scene.add_light(weft.SpotLight(cookie=weft.Texture(img), cast_shadows=False))
    with pytest.raises(ValueError, match="cookie"):
        make_renderer(32, 24).render(scene, camera)
