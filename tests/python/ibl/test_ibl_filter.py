"""Irradiance and glossy filtering against analytic results and the NumPy reference (SPEC §4.3)."""

from __future__ import annotations

import ibl_envs as envs
import numpy as np
import pytest
import weft
import weft.ibl as ibl
from weft.reference import ibl as ref


def faces(cube) -> np.ndarray:
    return np.asarray(cube.faces, np.float64)


def rel_errors(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    la = a @ np.array([0.2126, 0.7152, 0.0722])
    lb = b @ np.array([0.2126, 0.7152, 0.0722])
    return np.abs(la - lb) / np.maximum(lb, 1e-12)


def test_constant_environment_gives_pi_l_for_every_method() -> None:
    level = np.array([0.7, 0.5, 0.3])
    cube = ibl.CubeMap(envs.to_faces(envs.constant(level), 32))
    expected = np.pi * level
    np.testing.assert_allclose(faces(ibl.irradiance_exact(cube, 8, 32)).reshape(-1, 3),
                               np.broadcast_to(expected, (6 * 64, 3)), rtol=2e-4)
    sh = ibl.project_sh9(cube)
    np.testing.assert_allclose(faces(ibl.irradiance_from_sh(sh, 8)).reshape(-1, 3),
                               np.broadcast_to(expected, (6 * 64, 3)), rtol=2e-4)
    for blurred in (ibl.irradiance_box_blur(cube, 8), ibl.irradiance_rotational_blur(cube, 8)):
        np.testing.assert_allclose(faces(blurred).reshape(-1, 3),
                                   np.broadcast_to(expected, (6 * 64, 3)), rtol=2e-3)


@pytest.mark.parametrize("exact", [ibl.irradiance_exact, ibl.irradiance_exact_gpu],
                         ids=["cpu", "compute"])
def test_single_bright_texel_gives_the_clamped_cosine_lobe(exact) -> None:
    size = 16
    f = np.zeros((6, size, size, 3), np.float32)
    f[4, 7, 9] = (100.0, 50.0, 25.0)
    d_t = ref.texel_directions(size)[4, 7, 9]
    w_t = ibl.cube_texel_solid_angles(size)[7, 9]
    out = faces(exact(f, 8, size)).reshape(-1, 3)
    normals = ref.texel_directions(8).reshape(-1, 3)
    expected = np.maximum(normals @ d_t, 0.0)[:, None] * w_t * np.array([100.0, 50.0, 25.0])
    np.testing.assert_allclose(out, expected, rtol=1e-4, atol=1e-6)
    assert (out[normals @ d_t <= 0.0] == 0.0).all()  # nothing leaks past the horizon


def test_exact_irradiance_matches_the_reference() -> None:
    f = envs.to_faces(envs.random_smooth(31), 12)
    out = faces(ibl.irradiance_exact(f, 6, 12)).reshape(-1, 3)
    np.testing.assert_allclose(out, ref.irradiance(f, ref.texel_directions(6).reshape(-1, 3)),
                               rtol=5e-5)


def test_sh9_projection_and_evaluation_match_the_reference() -> None:
    f = envs.to_faces(envs.random_smooth(37), 24)
    sh = ibl.project_sh9(f)
    coeffs = ref.project_sh9(f)
    np.testing.assert_allclose(sh, coeffs, rtol=1e-4, atol=1e-5 * np.abs(coeffs).max())
    n = ref.texel_directions(5).reshape(-1, 3)
    np.testing.assert_allclose(ibl.sh_irradiance(sh, n.astype(np.float32)),
                               np.maximum(ref.sh_irradiance(coeffs, n), 0.0), rtol=2e-4)


ENVIRONMENTS = {
    "sky gradient": envs.sky_gradient(),
    "sun + sky": envs.sun_disc((0.3, 0.8, 0.4), np.radians(2.0), 300.0, envs.sky_gradient()),
    "random smooth": envs.random_smooth(41),
}


@pytest.mark.parametrize("name", list(ENVIRONMENTS))
def test_sh9_irradiance_is_within_the_ramamoorthi_hanrahan_bound(name: str) -> None:
    cube = ibl.CubeMap(envs.to_faces(ENVIRONMENTS[name], 64, supersample=2))
    exact = faces(ibl.irradiance_exact(cube, 16, 64))
    sh = faces(ibl.irradiance_from_sh(ibl.project_sh9(cube), 16))
    err = rel_errors(sh.reshape(-1, 3), exact.reshape(-1, 3))
    print(f"SH9 vs exact, {name}: mean {err.mean():.4f}, max {err.max():.4f}")
    assert err.mean() < 0.03
    assert err.max() < 0.25


def test_seed_blurs_report_their_error() -> None:
    cube = ibl.CubeMap(envs.to_faces(ENVIRONMENTS["sky gradient"], 64))
    exact = faces(ibl.irradiance_exact(cube, 16, 64)).reshape(-1, 3)
    errs = {}
    for name, out in (("box", ibl.irradiance_box_blur(cube, 16)),
                      ("rotational", ibl.irradiance_rotational_blur(cube, 16))):
        errs[name] = rel_errors(faces(out).reshape(-1, 3), exact).mean()
    print("seed blur mean relative errors:", errs)
    sh = faces(ibl.irradiance_from_sh(ibl.project_sh9(cube), 16)).reshape(-1, 3)
    # the approximations are approximations: worse than SH9 but in the right range
    assert all(rel_errors(sh, exact).mean() < e < 0.5 for e in errs.values())


def test_filtered_maps_have_no_seams() -> None:
    cube = ibl.CubeMap(envs.to_faces(ENVIRONMENTS["sun + sky"], 64, supersample=2))
    assert envs.seam_violations(faces(ibl.irradiance_exact(cube, 16, 32))) == 0
    assert envs.seam_violations(faces(ibl.irradiance_from_sh(ibl.project_sh9(cube), 16))) == 0
    chain = ibl.prefilter_ggx(cube, 32, levels=4, samples=64)
    for level in range(1, 4):
        assert envs.seam_violations(np.asarray(chain.level(level), np.float64)) == 0, level


def test_phong_exact_matches_the_reference() -> None:
    f = envs.to_faces(envs.random_smooth(43), 10)
    out = faces(ibl.phong_exact(f, 12.0, 5, 10)).reshape(-1, 3)
    np.testing.assert_allclose(out, ref.phong(f, 12.0, ref.texel_directions(5).reshape(-1, 3)),
                               rtol=1e-4)


@pytest.mark.parametrize("shininess", [4.0, 64.0])
def test_phong_sampled_converges_to_exact(shininess: float) -> None:
    cube = ibl.CubeMap(envs.to_faces(envs.random_smooth(47), 64))
    exact = faces(ibl.phong_exact(cube, shininess, 8, 64)).reshape(-1, 3)
    err = [rel_errors(faces(ibl.phong_sampled(cube, shininess, 8, n)).reshape(-1, 3), exact).mean()
           for n in (16, 256)]
    print(f"Phong s={shininess}: mean error 16 samples {err[0]:.4f}, 256 samples {err[1]:.4f}")
    assert err[1] < 0.02 and err[1] <= err[0] + 1e-4


def test_ggx_chain_matches_the_reference_lobe() -> None:
    f = envs.to_faces(envs.random_smooth(53), 32)
    chain = ibl.prefilter_ggx(f, 8, levels=4, samples=512)
    assert chain.levels == 4 and chain.size == 8
    for level in (1, 2, 3):
        s = 8 >> level
        rough = level / 3
        got = np.asarray(chain.level(level), np.float64).reshape(-1, 3)
        want = ref.ggx_prefilter(f, rough, ref.texel_directions(s).reshape(-1, 3))
        err = rel_errors(got, want)
        assert err.mean() < 0.03, (level, err.mean())


def test_tiny_bright_sun_gives_no_fireflies_and_keeps_its_energy() -> None:
    size = 128
    sky = envs.constant((0.2, 0.25, 0.3))
    f = envs.to_faces(sky, size)
    f[2, 40, 70] = (2.0e5, 1.9e5, 1.7e5)  # one texel: a sun 1e6 times brighter than the sky
    cube = ibl.CubeMap(f)
    w = ref.texel_solid_angles(16)

    def energy(x: np.ndarray) -> float:
        return float(np.einsum("fijc,ij->", x @ np.diag([0.2126, 0.7152, 0.0722]), w))

    exact = faces(ibl.phong_exact(cube, 20.0, 16, 128))
    sampled = faces(ibl.phong_sampled(cube, 20.0, 16, 32))
    lum = sampled @ np.array([0.2126, 0.7152, 0.0722])
    lum_exact = exact @ np.array([0.2126, 0.7152, 0.0722])
    print("max/mean sampled", lum.max() / lum.mean(), "exact", lum_exact.max() / lum_exact.mean())
    assert lum.max() / lum.mean() < 2.0 * lum_exact.max() / lum_exact.mean()
    assert abs(energy(sampled) - energy(exact)) < 0.05 * energy(exact)
    # the GGX chain (roughness 0.5 and 0.75 at 8^2 and 4^2) against the exact GGX lobe over the
    # source reduced to 32^2 in NumPy
    chain = ibl.prefilter_ggx(cube, 32, levels=5, samples=32)
    src = ref.reduce_faces(f, 4)
    for level in (2, 3):
        got = np.asarray(chain.level(level), np.float64)
        s = got.shape[1]
        want = ref.ggx_prefilter(src, level / 4, ref.texel_directions(s).reshape(-1, 3))
        lg = got.reshape(-1, 3) @ np.array([0.2126, 0.7152, 0.0722])
        lw = want @ np.array([0.2126, 0.7152, 0.0722])
        ws = np.broadcast_to(ref.texel_solid_angles(s, 16), (6, s, s)).reshape(-1)
        print(f"GGX level {level}: max/mean {lg.max() / lg.mean():.2f} (exact "
              f"{lw.max() / lw.mean():.2f}), energy ratio {(lg @ ws) / (lw @ ws):.4f}")
        assert lg.max() / lg.mean() < 2.0 * lw.max() / lw.mean()
        assert abs((lg @ ws) / (lw @ ws) - 1.0) < 0.05


def test_dfg_lut_matches_quadrature() -> None:
    lut = ibl.dfg_lut(16, 1024)
    assert lut.shape == (16, 16, 2)
    assert np.all(lut >= 0) and np.all(lut.sum(axis=2) <= 1.0 + 1e-3)
    for j, i in ((6, 3), (10, 8), (15, 12), (8, 15)):
        rough, nv = (j + 0.5) / 16, (i + 0.5) / 16
        np.testing.assert_allclose(lut[j, i], ref.dfg(nv, rough), atol=0.015)


def test_environment_refilters_only_when_its_radiance_changes() -> None:
    cube = ibl.CubeMap(envs.to_faces(envs.random_smooth(59), 16))
    env = ibl.Environment(cube)
    assert env.version == 1
    a = env.irradiance_sh()
    assert env.stats["filter_runs"] == 1 and env.stats["last_refiltered"]
    b = env.irradiance_sh()
    np.testing.assert_array_equal(a, b)
    assert env.stats["filter_runs"] == 1 and not env.stats["last_refiltered"]
    env.irradiance_map(8)
    env.irradiance_map(8)
    assert env.stats["filter_runs"] == 2 and not env.stats["last_refiltered"]
    env.specular_chain(8, 3, 16)
    env.specular_chain(8, 3, 16)
    assert env.stats["filter_runs"] == 3 and env.stats["cache_hits"] == 4
    dome = env.shadow_dome(16)
    np.testing.assert_array_equal(env.shadow_dome(16).intensities, dome.intensities)
    assert env.stats["filter_runs"] == 4 and env.stats["cache_hits"] == 5
    env.set_radiance(ibl.CubeMap(envs.to_faces(envs.constant((1, 1, 1)), 16)))
    assert env.version == 2
    c = env.irradiance_sh()
    assert env.stats["last_refiltered"] and not np.allclose(a, c)
    assert not np.allclose(env.shadow_dome(16).intensities, dome.intensities)


def test_filters_reject_bad_input() -> None:
    good = np.ones((6, 8, 8, 3), np.float32)
    bad = good.copy()
    bad[1, 2, 3, 0] = np.inf
    for fn in (lambda c: ibl.project_sh9(c), lambda c: ibl.irradiance_exact(c, 4),
               lambda c: ibl.prefilter_ggx(c, 8), lambda c: ibl.Environment(c)):
        with pytest.raises(weft.InvalidArgument, match="finite"):
            fn(bad)
    neg = good.copy()
    neg[0, 0, 0, 0] = -1.0
    with pytest.raises(weft.InvalidArgument, match=">= 0"):
        ibl.irradiance_exact(neg, 4)
    with pytest.raises(weft.InvalidArgument, match="levels"):
        ibl.prefilter_ggx(good, 8, levels=9)
    with pytest.raises(weft.InvalidArgument, match="shininess"):
        ibl.phong_sampled(good, -1.0)
    with pytest.raises(weft.InvalidArgument, match="sample"):
        ibl.phong_sampled(good, 10.0, 8, 0)
    with pytest.raises(weft.InvalidArgument, match="size"):
        ibl.irradiance_exact(good, 0)
    with pytest.raises(weft.InvalidArgument, match="too expensive"):
        ibl.irradiance_exact(good, 1024, 1024)
    with pytest.raises(weft.InvalidArgument, match="too expensive"):
        ibl.prefilter_ggx(good, 4096, 5, 1 << 20)
    with pytest.raises(weft.InvalidArgument, match=r"\(9, 3\)"):
        ibl.irradiance_from_sh(np.ones((4, 3), np.float32), 8)
    with pytest.raises(weft.InvalidArgument, match="6, S, S, 3"):
        ibl.project_sh9(np.ones((6, 8, 8), np.float32))


@pytest.mark.parametrize("source,size,levels,samples", [
    (32, 16, 4, 32),  # level 0 copied from source level 1
    (48, 32, 3, 16),  # level 0 read at a fractional lod (source size not a power-of-two multiple)
    (16, 32, 3, 8),   # level 0 magnified
    (32, 32, 1, 4),   # level 0 only: no dispatch
    (8, 8, 4, 256),   # many samples: high-roughness samples dropped below the horizon
])
def test_gpu_ggx_chain_equals_the_cpu_chain(source: int, size: int, levels: int,
                                            samples: int) -> None:
    # Vulkan compute on the selected device (lavapipe on CI); validation layers are on
    cube = ibl.CubeMap(envs.to_faces(ENVIRONMENTS["sun + sky"], source, supersample=2))
    gpu, ms = ibl.prefilter_ggx_gpu(cube, size, levels=levels, samples=samples)
    cpu = ibl.prefilter_ggx(cube, size, levels=levels, samples=samples)
    assert gpu.levels == cpu.levels == levels and ms > 0
    for level in range(levels):
        a, b = np.asarray(gpu.level(level)), np.asarray(cpu.level(level))
        np.testing.assert_allclose(a, b, rtol=1e-4, atol=1e-5 * float(b.max()))


def test_gpu_ggx_mirror_level_is_the_source_level() -> None:
    # a bilinear read at texel centres rounds into the neighbours: next to a 5000x sun that was
    # a 10% error; when the output size is a source level, level 0 is that level exactly
    faces = envs.to_faces(ENVIRONMENTS["sun + sky"], 64, supersample=2)
    cube = ibl.CubeMap(faces)
    assert np.array_equal(np.asarray(ibl.prefilter_ggx_gpu(cube, 64, 3, 8)[0].level(0)), faces)
    half = np.asarray(ibl.prefilter_ggx(cube, 32, 2, 4).level(0))  # ~ source level 1
    np.testing.assert_allclose(np.asarray(ibl.prefilter_ggx_gpu(cube, 32, 2, 4)[0].level(0)),
                               half, rtol=1e-5)


def test_gpu_ggx_chain_rejects_bad_arguments() -> None:
    cube = ibl.CubeMap(envs.to_faces(ENVIRONMENTS["sun + sky"], 32, supersample=2))
    with pytest.raises(weft.InvalidArgument, match="levels"):
        ibl.prefilter_ggx_gpu(cube, 16, levels=6)
    # more samples than a shader loop may run on lavapipe: refused, not silently truncated
    with pytest.raises(weft.InvalidArgument, match="at most 16384 samples"):
        ibl.prefilter_ggx_gpu(cube, 8, levels=2, samples=16385)
