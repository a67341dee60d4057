"""Light extraction, median cut and the dome of shadow lights (SPEC §4.5)."""

from __future__ import annotations

import ibl_envs as envs
import numpy as np
import pytest
import weft
import weft.ibl as ibl
from weft.reference import ibl as ref


def angle_deg(a, b) -> float:
    a = np.asarray(a, np.float64) / np.linalg.norm(a)
    b = np.asarray(b, np.float64) / np.linalg.norm(b)
    return float(np.degrees(np.arccos(np.clip(a @ b, -1, 1))))


def dim_sky():
    return lambda d: 0.3 + 0.2 * np.maximum(d[:, 1:2], 0) * np.array([[0.6, 0.8, 1.0]])


@pytest.mark.parametrize("sun", [(0.35, 0.8, -0.45), (1.0, 1.0, 1.0), (1.0, 0.02, 0.3)])
def test_planted_sun_is_found_within_2_degrees_and_5_percent(sun) -> None:
    # face interior, a cube corner and a face edge near the horizon
    radius, radiance = np.radians(1.5), 2.0e4
    env = envs.sun_disc(sun, radius, radiance, dim_sky())
    cube = ibl.CubeMap(envs.to_faces(env, 128, supersample=3))
    lights = ibl.extract_lights(cube)
    assert lights, "no light found"
    main = lights[0]
    power = envs.sun_power(radius, radiance)
    assert angle_deg(main.direction, sun) < 2.0
    np.testing.assert_allclose(main.colour, power, rtol=0.05)
    assert main.solid_angle == pytest.approx(2 * np.pi * (1 - np.cos(radius)), rel=0.1)
    assert len(lights) == 1  # the sky stays below the threshold, the disc is one component


def test_two_suns_are_two_lights_strongest_first() -> None:
    sky = dim_sky()
    env = envs.sun_disc((0.2, 0.9, 0.1), np.radians(2), 5e3,
                        envs.sun_disc((-0.7, 0.3, 0.6), np.radians(2), 1.5e4, sky))
    lights = ibl.extract_lights(ibl.CubeMap(envs.to_faces(env, 96, 2)))
    assert len(lights) == 2
    assert angle_deg(lights[0].direction, (-0.7, 0.3, 0.6)) < 2.0
    assert angle_deg(lights[1].direction, (0.2, 0.9, 0.1)) < 2.0
    assert lights[0].power > lights[1].power


def test_median_cut_conserves_energy_and_finds_the_sun() -> None:
    sun = (0.3, 0.7, -0.5)
    env = envs.sun_disc(sun, np.radians(2), 1e4, dim_sky())
    faces = envs.to_faces(env, 64, 2)
    lights = ibl.median_cut(ibl.CubeMap(faces), 16)
    assert len(lights) == 16
    total = np.einsum("fijc,ij->c", faces.astype(np.float64),
                      ref.texel_solid_angles(64))
    np.testing.assert_allclose(np.sum([l.colour for l in lights], axis=0), total, rtol=0.01)
    assert sum(l.solid_angle for l in lights) == pytest.approx(4 * np.pi, rel=1e-3)
    assert angle_deg(lights[0].direction, sun) < 3.0
    with pytest.raises(weft.InvalidArgument, match="power of two"):
        ibl.median_cut(ibl.CubeMap(faces), 12)


def test_dome_layouts() -> None:
    for layout in ("fibonacci", "rings"):
        for n in (8, 16, 64, 256):
            d = ibl.ShadowDome.layout_directions(n, layout)
            assert d.shape == (n, 3)
            np.testing.assert_allclose(np.linalg.norm(d, axis=1), 1.0, atol=1e-6)
            assert np.all(d[:, 1] > 0)
    rings = ibl.ShadowDome.layout_directions(16, "rings")
    assert len(np.unique(np.round(rings[:, 1], 5))) == 2  # two rings of 8
    for bad in (0, 12, 4100):
        with pytest.raises(weft.InvalidArgument, match="multiple of 8"):
            ibl.ShadowDome.layout_directions(bad)
    with pytest.raises(weft.InvalidArgument, match="layout"):
        ibl.ShadowDome.layout_directions(16, "spiral")


def test_dome_reproduces_the_irradiance_from_above() -> None:
    level = np.array([0.5, 0.6, 0.7])
    cube = ibl.CubeMap(envs.to_faces(envs.constant(level), 64))
    for n in (16, 64, 256):
        dome = ibl.ShadowDome(cube, n)
        assert dome.count == n
        np.testing.assert_allclose(dome.intensities.sum(axis=0), 2 * np.pi * level, rtol=1e-3)
        np.testing.assert_allclose(dome.solid_angles.sum(), 2 * np.pi, rtol=1e-3)
        up = dome.diffuse_visible((0, 1, 0), np.ones(n, bool))
        np.testing.assert_allclose(up, np.pi * level, rtol=0.05 if n == 16 else 0.015)


def test_dome_equations_2_22_and_2_23_agree() -> None:
    cube = ibl.CubeMap(envs.to_faces(envs.sky_gradient(), 32))
    dome = ibl.ShadowDome(cube, 64)
    rng = np.random.default_rng(3)
    visible = rng.random(64) < 0.6
    n = np.array([0.2, 0.9, 0.1])
    all_lights = np.array(dome.diffuse_visible(n, np.ones(64, bool)))
    d22 = np.array(dome.diffuse_visible(n, visible))
    d23 = np.array(dome.diffuse_subtract(n, all_lights, visible))
    np.testing.assert_allclose(d22, d23, rtol=1e-5)
    # eq. 2.21 by hand: H = T max(0, N.V)
    nn = n / np.linalg.norm(n)
    h = dome.intensities * np.maximum(dome.directions @ nn, 0)[:, None]
    np.testing.assert_allclose(d22, h[visible].sum(axis=0), rtol=1e-5)
    with pytest.raises(weft.InvalidArgument, match="entries"):
        dome.diffuse_visible(n, np.ones(63, bool))


def test_dome_visibility_converges_to_the_ray_cast_reference() -> None:
    # a sphere occluder (centre (0, 1, 0), radius 0.6) above the ground plane y = 0, lit by a
    # smooth sky; ground points around and under the sphere
    sky = envs.sky_gradient()
    faces = envs.to_faces(sky, 32)
    cube = ibl.CubeMap(faces)
    centre, radius = np.array([0.0, 1.0, 0.0]), 0.6
    up = np.array([0.0, 1.0, 0.0])
    points = [np.array([x, 0.0, z]) for x in (-1.2, -0.4, 0.0, 0.5, 1.5) for z in (-0.8, 0.0, 0.7)]
    exact = np.array([ref.visible_irradiance(faces, p, up, centre, radius, sub=2) for p in points])
    errors = []
    for n in (16, 64, 256):
        dome = ibl.ShadowDome(cube, n)
        est = []
        for p in points:
            visible = ~ref.ray_hits_sphere(p, dome.directions.astype(np.float64), centre, radius)
            est.append(dome.diffuse_visible(up, visible))
        err = np.abs(np.array(est) - exact).mean() / exact.mean()
        errors.append(err)
    print("dome visibility-weighted irradiance error, 16/64/256 lights:",
          ", ".join(f"{e:.4f}" for e in errors))
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 0.03


def test_round_robin_refresh_covers_every_light() -> None:
    dome = ibl.ShadowDome(np.ones((6, 4, 4, 3), np.float32), 64)
    seen = []
    for frame in range(8):
        s = dome.refresh_set(frame, 8)
        assert len(s) == 8
        seen.extend(s)
    assert sorted(seen) == list(range(64))
    assert dome.refresh_set(8, 8) == dome.refresh_set(0, 8)
    assert dome.refresh_set(3, 100) == list(range(64))
    assert len(dome.refresh_set(2, 5)) == 5 and dome.refresh_set(12, 5) == [60, 61, 62, 63]
    with pytest.raises(weft.InvalidArgument):
        dome.refresh_set(0, 0)


def test_light_extraction_rejects_bad_input() -> None:
    good = np.ones((6, 8, 8, 3), np.float32)
    bad = good.copy()
    bad[0, 0, 0, 0] = np.nan
    with pytest.raises(weft.InvalidArgument, match="finite"):
        ibl.extract_lights(bad)
    with pytest.raises(weft.InvalidArgument, match="downsample"):
        ibl.extract_lights(good, downsample=0)
    with pytest.raises(weft.InvalidArgument, match="threshold"):
        ibl.extract_lights(good, relative_threshold=0.0)
    with pytest.raises(weft.InvalidArgument, match="finite"):
        ibl.ShadowDome(bad, 16)


def test_sun_split_off_makes_sh9_accurate_for_a_strong_sun() -> None:
    sun = np.array([0.35, 0.8, -0.45]) / np.linalg.norm([0.35, 0.8, -0.45])
    env = envs.sun_disc(sun, np.radians(2.0), 5000.0, envs.sky_gradient())
    faces = envs.to_faces(env, 64, 2)
    normals = ref.texel_directions(8).reshape(-1, 3)
    exact = ref.irradiance(faces, normals) @ np.array([0.2126, 0.7152, 0.0722])
    lights, residual = ibl.split_lights(ibl.CubeMap(faces))
    assert len(lights) == 1
    sky_only = envs.to_faces(envs.sky_gradient(), 64, 2)
    assert np.asarray(residual.faces).max() < 2.0 * sky_only.max()  # the sun is gone
    sh_only = ibl.sh_irradiance(ibl.project_sh9(faces), normals.astype(np.float32))
    split = ibl.sh_irradiance(ibl.project_sh9(residual), normals.astype(np.float32)) + sum(
        np.outer(np.maximum(normals @ np.asarray(l.direction), 0.0), l.colour) for l in lights)

    def norm_err(e: np.ndarray) -> float:
        lum = e @ np.array([0.2126, 0.7152, 0.0722])
        return float(np.abs(lum - exact).mean() / exact.mean())

    print(f"sun 5000x sky: SH9 alone {norm_err(sh_only):.4f}, SH9 of residual + sun "
          f"{norm_err(split):.4f}")
    assert norm_err(split) < 0.02 < norm_err(sh_only)
