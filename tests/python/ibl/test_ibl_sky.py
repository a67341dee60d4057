"""The analytic daylight sky (weft.ibl.sky / SkyModel / sun_light) against Preetham, Shirley &
Smits 1999, "A Practical Analytic Model for Daylight": numbers evaluated by hand from the paper's
formulas (written out below), the Perez normalisation, the properties the paper's figures show,
and the sun against daylighting facts."""

import math

import numpy as np
import pytest
import weft
import weft.ibl as ibl

# Rec. 709 / sRGB (D65) RGB -> XYZ (IEC 61966-2-1): the inverse of what the sky converts with.
RGB_TO_XYZ = np.array([[0.4124, 0.3576, 0.1805],
                       [0.2126, 0.7152, 0.0722],
                       [0.0193, 0.1192, 0.9505]])


def sun_at(elevation_deg, azimuth_deg=0.0):
    e, a = math.radians(elevation_deg), math.radians(azimuth_deg)
    return (math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a))


def view(theta_deg, phi_deg):
    """Unit direction at zenith angle theta and azimuth phi (phi = 0 towards +X)."""
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return [math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p)]


def xyY_of(rgb):
    X, Y, Z = RGB_TO_XYZ @ np.asarray(rgb, np.float64)
    return X / (X + Y + Z), Y / (X + Y + Z), Y


def luminance(rgb):
    return float(RGB_TO_XYZ[1] @ np.asarray(rgb, np.float64))


def test_zenith_luminance_and_chromaticity_are_the_papers():
    # T = 2, theta_s = 60 deg = 1.0471976 rad:
    #   chi = (4/9 - 2/120)(pi - 2 pi/3) = 0.4277778 * 1.0471976 = 0.4479678, tan chi = 0.4805512
    #   Y_z = (4.0453*2 - 4.9710) * 0.4805512 - 0.2155*2 + 2.4192 = 3.1196 * 0.4805512 + 1.9882
    #       = 3.48733 kcd/m^2
    #   theta_s^3, ^2, ^1 = 1.1483806, 1.0966227, 1.0471976
    #   x_z = 4 (0.00166*1.1483806 - 0.00375*1.0966227 + 0.00209*1.0471976)
    #       + 2 (-0.02903*1.1483806 + 0.06377*1.0966227 - 0.03202*1.0471976 + 0.00394)
    #       + (0.11693*1.1483806 - 0.21196*1.0966227 + 0.06052*1.0471976 + 0.25886)
    #       = 4 (-0.0000174) + 2 (0.0070029) + 0.2240764 = 0.2380126
    #   y_z = 4 (-0.0002117) + 2 (0.0116442) + 0.2195462 = 0.2419876
    sky = ibl.SkyModel(sun_at(30.0), turbidity=2.0)
    x_z, y_z, Y_z = sky.zenith
    assert Y_z == pytest.approx(3.48733, rel=2e-4)
    assert x_z == pytest.approx(0.2380126, abs=2e-5)
    assert y_z == pytest.approx(0.2419876, abs=2e-5)
    # T = 6, theta_s = 30 deg: chi = (4/9 - 6/120)(pi - pi/3) = 0.3944444 * 2.0943951 = 0.8261225,
    # tan chi = 1.0849554, Y_z = (24.2718 - 4.9710) * 1.0849554 - 1.293 + 2.4192 = 22.06671
    assert ibl.SkyModel(sun_at(60.0), turbidity=6.0).zenith[2] == pytest.approx(22.06671, rel=2e-4)


@pytest.mark.parametrize("turbidity, elevation", [(2.0, 30.0), (3.0, 45.0), (6.0, 60.0),
                                                  (9.5, 12.0)])
def test_the_zenith_takes_the_zenith_values(turbidity, elevation):
    # Y = Y_z F(theta, gamma) / F(0, theta_s): at the zenith (theta = 0, gamma = theta_s) the
    # ratio is 1, for Y, x and y alike; the RGB radiance carries the same xyY.
    sky = ibl.SkyModel(sun_at(elevation, 40.0), turbidity=turbidity)
    x_z, y_z, Y_z = sky.zenith
    x, y, Y = sky.xyY(np.array([[0.0, 1.0, 0.0]], np.float32))[0]
    assert (x, y, Y) == pytest.approx((x_z, y_z, Y_z), rel=1e-5)
    rx, ry, rY = xyY_of(sky.radiance(np.array([[0.0, 1.0, 0.0]], np.float32))[0])
    assert rY == pytest.approx(Y_z, rel=1e-3)
    assert (rx, ry) == pytest.approx((x_z, y_z), abs=1e-3)


def test_perez_distribution_by_hand():
    # T = 3: A = 0.1787*3 - 1.4630 = -0.9269, B = -0.3554*3 + 0.4275 = -0.6387,
    # C = -0.0227*3 + 5.3251 = 5.2570, D = 0.1206*3 - 2.5771 = -2.2153, E = -0.0670*3 + 0.3703
    # = 0.1693. Sun at theta_s = 45 deg, view at theta = 60 deg on the far side (gamma = 105 deg):
    #   F(60, 105) = (1 - 0.9269 e^(-0.6387/0.5)) (1 + 5.257 e^(-2.2153*1.8325957)
    #                + 0.1693 cos^2 105) = 0.7416163 * 1.1020418 = 0.8172921
    #   F(0, 45)  = (1 - 0.9269 e^-0.6387) (1 + 5.257 e^(-2.2153*0.7853982) + 0.1693 * 0.5)
    #             = 0.5106169 * 2.0074599 = 1.0250429
    #   Y / Y_z = 0.7973248, Y_z(T=3, theta_s=45) = 7.320358 kcd/m^2
    sky = ibl.SkyModel(sun_at(45.0, 0.0), turbidity=3.0)
    x, y, Y = sky.xyY(np.array([view(60.0, 180.0)], np.float32))[0]
    assert sky.zenith[2] == pytest.approx(7.320358, rel=2e-4)
    assert Y / sky.zenith[2] == pytest.approx(0.7973248, rel=1e-4)


def test_symmetric_about_the_solar_meridian():
    sky = ibl.SkyModel(sun_at(25.0, 0.0), turbidity=4.0)  # the sun in the x-y plane
    dirs = np.array([view(t, p) for t in (10, 45, 80, 89) for p in (20, 75, 130, 170)],
                    np.float32)
    mirrored = dirs * np.array([1.0, 1.0, -1.0], np.float32)
    np.testing.assert_allclose(sky.radiance(dirs), sky.radiance(mirrored), rtol=1e-5)


@pytest.mark.parametrize("elevation", [20.0, 45.0, 70.0])
def test_bluer_at_the_zenith_than_at_the_horizon(elevation):
    sky = ibl.SkyModel(sun_at(elevation), turbidity=3.0)
    zenith, horizon = sky.radiance(np.array([view(0, 0), view(85, 90)], np.float32))
    assert zenith[2] / zenith[0] > 1.3 * horizon[2] / horizon[0]
    assert zenith[2] > zenith[0]  # a blue sky overhead


def test_brighter_towards_the_sun():
    # Along the sun's almucantar (theta = theta_s) the angle to the sun falls from 90 to 3 deg.
    sky = ibl.SkyModel(sun_at(30.0, 0.0), turbidity=3.0)
    lum = [luminance(c) for c in sky.radiance(
        np.array([view(60.0, p) for p in (100, 80, 60, 40, 20, 10, 5, 3)], np.float32))]
    assert all(b > a for a, b in zip(lum, lum[1:])), lum
    assert lum[-1] > 4.0 * lum[0]


def test_turbidity_brightens_and_whitens_the_sky_and_dims_the_sun():
    # The paper's figures: hazier skies are brighter and less saturated; aerosols dim the sun.
    zen, sat, sun = [], [], []
    for t in (2.0, 3.0, 5.0, 8.0):
        sky = ibl.SkyModel(sun_at(40.0), turbidity=t)
        c = sky.radiance(np.array([view(0, 0), view(70, 180)], np.float32))
        zen.append(luminance(c[0]))
        sat.append(float(c[1].max() / c[1].min()))
        sun.append(luminance(sky.sun_irradiance))
    assert all(b > a for a, b in zip(zen, zen[1:])), zen
    assert all(b < a for a, b in zip(sat, sat[1:])), sat
    assert all(b < a for a, b in zip(sun, sun[1:])), sun


def test_sun_irradiance_is_daylight_sized_and_sets_red():
    # Clear-sky direct normal illuminance at high sun is about 100 klx (the luminous solar
    # constant 133.8 klx less ~25% extinction); the setting sun dims and reddens.
    high = ibl.SkyModel(sun_at(70.0), turbidity=2.5).sun_irradiance
    assert 85.0 < luminance(high) < 115.0
    e = [np.asarray(ibl.SkyModel(sun_at(el), turbidity=3.0).sun_irradiance)
         for el in (60.0, 20.0, 8.0, 3.0)]
    lum = [luminance(v) for v in e]
    red = [v[0] / max(v[2], 1e-9) for v in e]
    assert all(b < a for a, b in zip(lum, lum[1:])), lum
    assert all(b > a for a, b in zip(red, red[1:])), red
    # a disc (radius 0.2666 deg) centred on the horizon shows its upper half only: well under a
    # disc just above it; below the horizon the sun is gone
    assert luminance(ibl.SkyModel(sun_at(0.0), 3.0).sun_irradiance) < \
        0.75 * luminance(ibl.SkyModel(sun_at(0.3), 3.0).sun_irradiance)
    assert ibl.SkyModel(sun_at(-0.3), 3.0).sun_irradiance == (0.0, 0.0, 0.0)


def test_sun_light_matches_the_environment_convention():
    sky = ibl.SkyModel(sun_at(35.0, 70.0), turbidity=3.0, scale=0.01)
    light = ibl.sun_light(sun_at(35.0, 70.0), turbidity=3.0, scale=0.01)
    assert isinstance(light, weft.DirectionalLight)
    np.testing.assert_allclose(np.asarray(light.color) * light.intensity * math.pi,
                               sky.sun_irradiance, rtol=1e-5)
    assert max(light.color) == pytest.approx(1.0)
    np.testing.assert_allclose(light.direction, -np.asarray(sun_at(35.0, 70.0)), atol=1e-6)
    assert light.cast_shadows
    night = ibl.sun_light(sun_at(-5.0), turbidity=3.0)
    assert night.intensity == 0.0 and not night.cast_shadows


def test_cube_holds_the_sky_and_the_sun_disc():
    # Sun at the zenith: the centre of the +Y face, where a 512 texel spans 0.224 deg.
    size = 512
    with_sun = np.asarray(ibl.sky(sun_at(90.0), 3.0, size=size).faces)
    without = np.asarray(ibl.sky(sun_at(90.0), 3.0, size=size, sun=False).faces)
    dw = np.asarray(ibl.cube_texel_solid_angles(size))[None, :, :, None]
    sun_part = (with_sun - without) * dw
    e_sun = np.asarray(ibl.SkyModel(sun_at(90.0), 3.0).sun_irradiance)
    np.testing.assert_allclose(sun_part.sum(axis=(0, 1, 2)), e_sun, rtol=1e-4)
    # the disc: every texel holding sun lies within the sun's radius plus half a texel diagonal
    lit = sun_part.sum(axis=3) > 0.0
    dirs = np.asarray(ibl.cube_texel_directions(size))[lit]
    angles = np.degrees(np.arccos(np.clip(dirs[:, 1], -1.0, 1.0)))
    texel = math.degrees(2.0 / size)
    assert angles.max() <= 0.2666 + 0.71 * texel
    assert angles.max() >= 0.2666 - 0.71 * texel
    assert lit.sum() >= 4
    # away from the sun the cube is the model
    sky = ibl.SkyModel(sun_at(90.0), 3.0)
    d = np.asarray(ibl.cube_texel_directions(size))[2, 0, 0][None, :]
    np.testing.assert_allclose(with_sun[2, 0, 0], sky.radiance(d.astype(np.float32))[0],
                               rtol=1e-5)


@pytest.mark.parametrize("albedo", [0.3, (0.1, 0.3, 0.5)])
def test_ground_is_lambertian_under_sky_and_sun(albedo):
    size, elevation = 48, 40.0
    sky = ibl.sky(sun_at(elevation), 3.0, size=size, ground_albedo=albedo, sun=False)
    faces = np.asarray(sky.faces, np.float64)
    dirs = np.asarray(ibl.cube_texel_directions(size), np.float64)
    dw = np.broadcast_to(np.asarray(ibl.cube_texel_solid_angles(size))[None], faces.shape[:3])
    up = dirs[..., 1] > 0.0
    # irradiance of the upper hemisphere on the ground, integrated over the cube independently
    e_sky = (faces[up] * (dirs[up][:, 1] * dw[up])[:, None]).sum(axis=0)
    model = ibl.SkyModel(sun_at(elevation), 3.0, ground_albedo=albedo)
    e_sun = np.asarray(model.sun_irradiance) * math.sin(math.radians(elevation))
    expected = np.asarray(albedo) * (e_sky + e_sun) / math.pi  # grey or per channel
    np.testing.assert_allclose(faces[3, size // 2, size // 2], expected, rtol=0.02)
    np.testing.assert_allclose(model.sky_horizontal_irradiance, e_sky, rtol=0.02)


def test_twilight_fades_to_the_night_sky():
    night = (1e-4, 2e-4, 3e-4)
    z = np.array([[0.0, 1.0, 0.0]], np.float32)
    lum = [luminance(ibl.SkyModel(sun_at(el), 3.0, night_radiance=night).radiance(z)[0])
           for el in (5.0, 0.0, -3.0, -6.0, -12.0, -40.0)]
    assert all(b < a for a, b in zip(lum, lum[1:])), lum
    # about 2.4 decades from sunset to the end of civil twilight (-6 deg), as measured
    assert 100.0 < lum[1] / lum[3] < 1000.0
    np.testing.assert_allclose(
        ibl.SkyModel(sun_at(-40.0), 3.0, night_radiance=night).radiance(z)[0], night,
        rtol=1e-3)
    # the default night is dark: ~1e-7 kcd/m^2 (natural night sky, 174 ucd/m^2)
    dark = luminance(ibl.SkyModel(sun_at(-40.0), 3.0).radiance(z)[0])
    assert 1e-7 < dark < 3e-7


def test_scale_is_linear():
    d = np.array([view(30, 10), view(100, 40)], np.float32)
    a = ibl.SkyModel(sun_at(20.0), 4.0).radiance(d)
    b = ibl.SkyModel(sun_at(20.0), 4.0, scale=0.25).radiance(d)
    np.testing.assert_allclose(b, 0.25 * a, rtol=1e-6)


@pytest.mark.parametrize("kwargs", [
    dict(sun_direction=(float("nan"), 1.0, 0.0)),
    dict(sun_direction=(0.0, 0.0, 0.0)),
    dict(sun_direction=(0.0, float("inf"), 0.0)),
    dict(sun_direction=(0.0, 1.0, 0.0), turbidity=1.5),
    dict(sun_direction=(0.0, 1.0, 0.0), turbidity=10.5),
    dict(sun_direction=(0.0, 1.0, 0.0), turbidity=float("nan")),
    dict(sun_direction=(0.0, 1.0, 0.0), size=0),
    dict(sun_direction=(0.0, 1.0, 0.0), size=4096),
    dict(sun_direction=(0.0, 1.0, 0.0), ground_albedo=-0.1),
    dict(sun_direction=(0.0, 1.0, 0.0), ground_albedo=1.5),
    dict(sun_direction=(0.0, 1.0, 0.0), ground_albedo=(0.2, 0.2, float("nan"))),
    dict(sun_direction=(0.0, 1.0, 0.0), ground_albedo=(0.2, 0.2)),
    dict(sun_direction=(0.0, 1.0, 0.0), scale=-1.0),
    dict(sun_direction=(0.0, 1.0, 0.0), night_radiance=(0.0, -1.0, 0.0)),
])
def test_bad_input_is_rejected(kwargs):
    with pytest.raises(weft.InvalidArgument):
        ibl.sky(**kwargs)


def test_bad_directions_and_light_input_are_rejected():
    sky = ibl.SkyModel(sun_at(30.0))
    with pytest.raises(weft.InvalidArgument):
        sky.radiance(np.zeros((1, 3), np.float32))
    with pytest.raises(weft.InvalidArgument):
        sky.radiance(np.full((1, 3), np.nan, np.float32))
    with pytest.raises(weft.InvalidArgument):
        sky.radiance(np.ones((2, 2), np.float32))
    with pytest.raises(weft.InvalidArgument):
        ibl.sun_light((0.0, 0.0, 0.0))
    with pytest.raises(weft.InvalidArgument):
        ibl.sun_light((0.0, 1.0, 0.0), turbidity=20.0)
