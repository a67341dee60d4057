"""Cube maps and capture conversion against the NumPy reference (SPEC §4.1, §4.2)."""

from __future__ import annotations

import ibl_envs as envs
import numpy as np
import pytest
import weft
import weft.ibl as ibl
from weft.reference import ibl as ref


def rotation_y(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    m = np.eye(4)
    m[0, 0], m[0, 2], m[2, 0], m[2, 2] = c, s, -s, c
    return m


def unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def test_texel_directions_follow_the_vulkan_convention() -> None:
    for size in (1, 2, 7):
        np.testing.assert_allclose(ibl.cube_texel_directions(size), ref.texel_directions(size),
                                   atol=2e-7)
    # major axis -> face: the centre of each face is its axis
    d = ibl.cube_texel_directions(1)[:, 0, 0]
    np.testing.assert_allclose(d, np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0],
                                            [0, 0, 1], [0, 0, -1]]), atol=1e-7)


def test_cube_coords_match_the_major_axis_rule() -> None:
    d = unit(np.random.default_rng(1).normal(size=(2000, 3)))
    face, uv = ibl.cube_coords(d.astype(np.float32))
    rf, ru, rv = ref.direction_to_face(d)
    np.testing.assert_array_equal(face, rf)
    np.testing.assert_allclose(uv, np.stack([ru, rv], 1), atol=2e-6)


def test_texel_solid_angles_match_quadrature_and_sum_to_4pi() -> None:
    for size in (1, 5, 32):
        w = ibl.cube_texel_solid_angles(size)
        np.testing.assert_allclose(w, ref.texel_solid_angles(size, sub=max(4, 256 // size)),
                                   rtol=5e-5)
        assert abs(6 * w.sum() - 4 * np.pi) < 1e-9


def test_sampling_hits_texel_centres_and_is_seamless() -> None:
    env = envs.random_smooth(3)
    size = 16
    cube = ibl.CubeMap(envs.to_faces(env, size))
    d = ibl.cube_texel_directions(size).reshape(-1, 3)
    np.testing.assert_allclose(cube.sample(d), np.asarray(cube.faces).reshape(-1, 3), rtol=1e-5)
    # directions straddling every edge and corner: both sides read nearly the same value
    rng = np.random.default_rng(4)
    t = rng.uniform(-1, 1, 500)
    eps = 1e-4
    for axis_pair in ((0, 2), (1, 0), (2, 1)):
        a, b = axis_pair
        p = np.zeros((500, 3))
        p[:, a] = 1.0
        p[:, b] = 1.0
        p[:, 3 - a - b] = t
        left, right = p.copy(), p.copy()
        left[:, a] += eps
        right[:, b] += eps
        np.testing.assert_allclose(cube.sample(left), cube.sample(right), rtol=2e-3)
    # and bilinear reconstruction of the smooth field is close everywhere, corners included
    q = unit(rng.normal(size=(3000, 3)))
    truth = env(q)
    assert np.max(np.abs(cube.sample(q) - truth) / truth) < 0.05


def test_mips_conserve_the_integral() -> None:
    size = 32
    faces = envs.to_faces(envs.random_smooth(5), size)
    cube = ibl.CubeMap(faces)
    cube.build_mips()
    assert cube.levels == 6

    def integral(level_faces: np.ndarray) -> np.ndarray:
        s = level_faces.shape[1]
        return np.einsum("fijc,ij->c", level_faces.astype(np.float64),
                         ref.texel_solid_angles(s, sub=max(4, 256 // s)))

    base = integral(faces)
    for level in range(cube.levels):
        np.testing.assert_allclose(integral(cube.level(level)), base, rtol=2e-3)


def mirror_ball(env, size: int, world_to_sphere: np.ndarray) -> np.ndarray:
    """A 360 degree sphere map rendered as a physical mirror ball seen along -Z: pixel normal N,
    reflected eye ray R = 2 (N.A) N - A, A = (0, 0, 1); R is in sphere space."""
    c = 2.0 * (np.arange(size) + 0.5) / size - 1.0
    x, y = np.meshgrid(c, -c, indexing="xy")
    r2 = np.minimum(x * x + y * y, 1.0)
    n = np.stack([x, y, np.sqrt(1.0 - r2)], -1).reshape(-1, 3)
    n = unit(n)
    refl = 2.0 * n[:, 2:3] * n - np.array([0.0, 0.0, 1.0])
    world = refl @ world_to_sphere[:3, :3]  # inverse rotation (orthonormal)
    return env(unit(world)).reshape(size, size, 3).astype(np.float32)


@pytest.mark.parametrize("angle", [0.0, 0.7])
def test_mirror_ball_to_cube_matches_the_environment(angle: float) -> None:
    env = envs.random_smooth(7)
    m = rotation_y(angle)
    sphere = mirror_ball(env, 512, m)
    cube, valid = ibl.sphere_to_cube(sphere, 32, world_to_sphere=m, wrap=1.0)
    assert valid.all()
    d = ref.texel_directions(32).reshape(-1, 3)
    truth = env(d)
    err = np.abs(np.asarray(cube.faces).reshape(-1, 3) - truth) / truth
    back = (d @ m[:3, :3].T)[:, 2] < -0.9  # the pole behind the ball is a single point
    assert np.median(err[~back]) < 0.01 and np.max(err[~back]) < 0.1


@pytest.mark.parametrize("wrap", [1.0, 0.8, 0.5])
def test_wrap_value_maps_directions_as_in_the_spec(wrap: float) -> None:
    # a sphere map whose pixels hold their own disc coordinates (x, y): linear, so bilinear
    # reads are exact and the cube shows where each texel was read
    size = 256
    c = 2.0 * (np.arange(size) + 0.5) / size - 1.0
    x, y = np.meshgrid(c, -c, indexing="xy")
    img = np.stack([x, y, np.zeros_like(x)], -1).astype(np.float32)
    m = rotation_y(0.3)
    cube, valid = ibl.sphere_to_cube(img, 16, world_to_sphere=m, wrap=wrap, supersample=1)
    d = ref.texel_directions(16).reshape(-1, 3)
    expected = ref.sphere_map_coords(d, m, wrap)
    got = np.asarray(cube.faces).reshape(-1, 3)[:, :2]
    np.testing.assert_allclose(got, expected, atol=1.0 / size + 1e-4)
    vz = unit(d @ m[:3, :3].T)[:, 2]
    np.testing.assert_array_equal(valid.reshape(-1), wrap + vz > 1e-4)
    # clamped directions land on the rim
    rim = ~valid.reshape(-1)
    if rim.any():
        np.testing.assert_allclose(np.linalg.norm(got[rim], axis=1), 1.0, atol=2.0 / size)


def test_sphere_cube_sphere_round_trip() -> None:
    env = envs.random_smooth(11)
    sphere = mirror_ball(env, 256, np.eye(4))
    cube, _ = ibl.sphere_to_cube(sphere, 64)
    back = ibl.cube_to_sphere(cube, 256)
    c = 2.0 * (np.arange(256) + 0.5) / 256 - 1.0
    x, y = np.meshgrid(c, -c, indexing="xy")
    inner = x * x + y * y < 0.85 ** 2
    rel = np.abs(back - sphere)[inner] / sphere[inner]
    assert np.mean(rel) < 0.005 and np.max(rel) < 0.05


def test_equirect_mapping_and_round_trip() -> None:
    w, h = 512, 256
    u = (np.arange(w) + 0.5) / w
    v = (np.arange(h) + 0.5) / h
    uu, vv = np.meshgrid(u, v, indexing="xy")
    img = np.stack([uu, vv, np.zeros_like(uu)], -1).astype(np.float32)
    cube = ibl.equirect_to_cube(img, 16, supersample=1)
    d = ref.texel_directions(16).reshape(-1, 3)
    expected = ref.equirect_coords(d)
    got = np.asarray(cube.faces).reshape(-1, 3)[:, :2]
    away = (np.abs(expected[:, 0] - 0.0) > 2 / w) & (np.abs(expected[:, 0] - 1.0) > 2 / w)
    np.testing.assert_allclose(got[away], expected[away], atol=1.0 / h)
    env = envs.random_smooth(13)
    cube = ibl.CubeMap(envs.to_faces(env, 64))
    eq = ibl.cube_to_equirect(cube, 256, 128)
    theta = np.pi * (np.arange(128) + 0.5) / 128
    phi = 2 * np.pi * ((np.arange(256) + 0.5) / 256 - 0.5)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    dirs = np.stack([np.sin(t) * np.sin(p), np.cos(t), -np.sin(t) * np.cos(p)], -1).reshape(-1, 3)
    truth = env(dirs).reshape(128, 256, 3)
    assert np.max(np.abs(eq - truth) / truth) < 0.03
    again = ibl.equirect_to_cube(eq, 64)
    assert np.mean(np.abs(np.asarray(again.faces) - np.asarray(cube.faces)) /
                   np.asarray(cube.faces)) < 0.01


@pytest.mark.parametrize("layout", ["horizontal", "vertical"])
def test_cube_cross_round_trip_and_continuity(layout: str) -> None:
    faces = envs.to_faces(envs.random_smooth(17), 16)
    cross = ibl.cube_to_cross(faces, layout)
    assert cross.shape == ((48, 64, 3) if layout == "horizontal" else (64, 48, 3))
    np.testing.assert_array_equal(np.asarray(ibl.cross_to_cube(cross).faces), faces)
    # neighbouring cells of the cross continue each other (+Z | +X, +Y above +Z, -Y above -Z)
    s = 16
    lum = cross @ np.array([0.2126, 0.7152, 0.0722])
    pairs = [((slice(s, 2 * s), 2 * s - 1), (slice(s, 2 * s), 2 * s)),       # +Z | +X
             ((s - 1, slice(s, 2 * s)), (s, slice(s, 2 * s)))]                 # +Y / +Z
    if layout == "vertical":
        pairs.append(((3 * s - 1, slice(s, 2 * s)), (3 * s, slice(s, 2 * s))))  # -Y / -Z
    for a, b in pairs:
        step = np.abs(lum[a] - lum[b])
        assert np.max(step) < 0.1 * np.mean(lum[a])


def test_fisheye_is_equidistant_and_masks_the_unseen_half() -> None:
    size = 256
    c = 2.0 * (np.arange(size) + 0.5) / size - 1.0
    x, y = np.meshgrid(c, -c, indexing="xy")
    img = np.stack([x, y, np.zeros_like(x)], -1).astype(np.float32)
    cam = np.eye(4)
    cam[:3, :3] = np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]])  # world +Y -> camera +Z
    cube, valid = ibl.fisheye_to_cube(img, 16, np.pi, world_to_camera=cam, supersample=1)
    d = ref.texel_directions(16).reshape(-1, 3)
    vc = d @ cam[:3, :3].T
    theta = np.arccos(np.clip(vc[:, 2], -1, 1))
    np.testing.assert_array_equal(valid.reshape(-1), theta <= np.pi / 2)
    seen = valid.reshape(-1)
    rad = theta / (np.pi / 2)
    expected = rad[:, None] * unit(vc[:, :2])
    got = np.asarray(cube.faces).reshape(-1, 3)[:, :2]
    np.testing.assert_allclose(got[seen], expected[seen], atol=1.5 / size)


def test_fill_unseen_keeps_seen_texels_and_fills_smoothly() -> None:
    env = envs.random_smooth(19)
    size = 32
    faces = envs.to_faces(env, size)
    d = ref.texel_directions(size)
    valid = d[..., 1] > -0.2  # the capture saw only the upper part
    holes = faces.copy()
    holes[~valid] = 0.0
    filled = np.asarray(ibl.fill_unseen(holes, valid).faces)
    np.testing.assert_array_equal(filled[valid], faces[valid])
    lo, hi = faces[valid].min(axis=0), faces[valid].max(axis=0)
    assert np.all(filled[~valid] >= lo - 1e-5) and np.all(filled[~valid] <= hi + 1e-5)
    assert envs.seam_violations(filled) == 0


def test_seam_check_detects_a_seam() -> None:
    faces = envs.to_faces(envs.random_smooth(23), 16)
    assert envs.seam_violations(faces) == 0
    broken = faces.copy()
    broken[4] *= 1.08
    assert envs.seam_violations(broken) > 0


def test_conversion_rejects_bad_input() -> None:
    img = np.ones((32, 32, 3), np.float32)
    with pytest.raises(weft.InvalidArgument, match="wrap"):
        ibl.sphere_to_cube(img, 8, wrap=0.0)
    with pytest.raises(weft.InvalidArgument, match="wrap"):
        ibl.sphere_to_cube(img, 8, wrap=-1.0)
    with pytest.raises(weft.InvalidArgument, match="size"):
        ibl.sphere_to_cube(img, 0)
    bad = img.copy()
    bad[3, 3, 1] = np.nan
    with pytest.raises(weft.InvalidArgument, match="finite"):
        ibl.sphere_to_cube(bad, 8)
    with pytest.raises(weft.InvalidArgument, match="float"):
        ibl.equirect_to_cube(np.ones((8, 16, 3), np.uint8), 8)
    with pytest.raises(weft.InvalidArgument):
        ibl.equirect_to_cube(np.ones((0, 16, 3), np.float32), 8)
    with pytest.raises(weft.InvalidArgument, match="4x4"):
        ibl.sphere_to_cube(img, 8, world_to_sphere=np.eye(3))
    with pytest.raises(weft.InvalidArgument, match="field of view"):
        ibl.fisheye_to_cube(img, 8, 0.0)
    with pytest.raises(weft.InvalidArgument, match="6, S, S, 3"):
        ibl.CubeMap(np.ones((6, 4, 5, 3), np.float32))
    with pytest.raises(weft.InvalidArgument, match="entries"):
        ibl.fill_unseen(np.ones((6, 4, 4, 3), np.float32), np.ones((6, 4, 3), bool))
    with pytest.raises(weft.InvalidArgument, match="no texel"):
        ibl.fill_unseen(np.ones((6, 4, 4, 3), np.float32), np.zeros((6, 4, 4), bool))
    with pytest.raises(weft.InvalidArgument, match="non-zero"):
        ibl.CubeMap(4).sample(np.zeros((1, 3), np.float32))
    with pytest.raises(weft.InvalidArgument, match="4:3"):
        ibl.cross_to_cube(np.ones((10, 10, 3), np.float32))


def test_srgb_decoding_matches_the_reference() -> None:
    x = np.arange(256, dtype=np.uint8).reshape(16, 16, 1).repeat(3, axis=2)
    np.testing.assert_allclose(ibl.srgb_to_linear(x), ref.srgb_to_linear(x / 255.0), atol=1e-6)


def test_one_camera_setup_cuts_out_the_ball() -> None:
    # camera at the origin looking down -Z, marker 1 m ahead, ball 0.1 m right of the marker
    f = 1.0 / np.tan(np.radians(30))
    proj = np.array([[f, 0, 0, 0], [0, f, 0, 0], [0, 0, -1.02, -0.202], [0, 0, -1, 0]])
    marker = np.eye(4)
    marker[2, 3] = -1.0
    rect = ibl.sphere_rect(marker, (0.1, 0.0, 0.0), 0.05, proj, 640, 640)
    cx = (0.1 * f / 1.0 * 0.5 + 0.5) * 640
    half = 0.05 * f * 0.5 * 640
    np.testing.assert_allclose(rect, (cx - half, 320 - half, cx + half, 320 + half), rtol=1e-9)
    # a frame with a sphere map pasted into that rectangle gives the sphere map back
    sphere = mirror_ball(envs.random_smooth(29), 64, np.eye(4))
    frame = np.zeros((640, 640, 3), np.float32)
    x0, y0 = int(round(rect[0])), int(round(rect[1]))
    n = int(round(rect[2] - rect[0]))
    yy, xx = np.meshgrid((np.arange(n) + 0.5) / n * 64, (np.arange(n) + 0.5) / n * 64,
                         indexing="ij")
    frame[y0:y0 + n, x0:x0 + n] = sphere[yy.astype(int), xx.astype(int)]
    cut = ibl.cut_out_sphere(frame, (x0, y0, x0 + n, y0 + n), 64)
    assert np.mean(np.abs(cut - sphere)) < 0.02 * np.mean(sphere)
    cubes = list(ibl.environments_from_frames([frame, frame, frame], 16, sphere_size=64,
                                              marker_to_camera=[marker] * 3, centre=(0.1, 0, 0),
                                              radius=0.05, projection=proj, wrap=0.9))
    assert len(cubes) == 3 and all(c.size == 16 for c in cubes)
    assert np.all(np.isfinite(np.asarray(cubes[0].faces)))
