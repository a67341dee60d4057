"""Exact irradiance as a Vulkan compute shader (weft.ibl.irradiance_exact_gpu, SPEC §4.3) against
the CPU irradiance_exact, a float64 sum of the same texel table, and analytic results.

Runs on the selected device (lavapipe on CI) with the validation layers on (conftest.py fails a
test on any validation message). Measured on lavapipe, 16^2 output from a 32^2 source (sun + sky,
random smooth): per-texel relative difference to the CPU version ~1e-6 mean, ~3e-6 max; to a
float64 sum of the same table ~1.5e-7 mean, ~5e-7 max, while the CPU's single float running sum is
~1e-6 mean off it (the shader sums per 64-texel tile, then the tiles); from a 64^2 source all
roughly double. The gap grows with the source: at 1024^2 (random radiance, 2^2 output) the
compute result stays within 5e-7 of float64 while the CPU's is 1.6e-3 off. The bounds below leave
10x headroom or more.
"""

from __future__ import annotations

import ibl_envs as envs
import numpy as np
import pytest
import weft
import weft.ibl as ibl


def faces(cube) -> np.ndarray:
    return np.asarray(cube.faces, np.float64)


def rel_diff(got: np.ndarray, want: np.ndarray) -> np.ndarray:
    """Per texel: largest channel difference over the largest channel of `want`."""
    got, want = got.reshape(-1, 3), want.reshape(-1, 3)
    return np.abs(got - want).max(axis=1) / np.abs(want).max(axis=1)


def float64_irradiance(f: np.ndarray, size: int) -> np.ndarray:
    """sum max(0, n.w) L dw in float64 over the texels of `f` (exact solid angles, the texel
    directions weft uses), at the texel directions of a `size` cube."""
    s = f.shape[1]
    d = np.asarray(ibl.cube_texel_directions(s), np.float64).reshape(-1, 3)
    w = np.broadcast_to(np.asarray(ibl.cube_texel_solid_angles(s), np.float64), (6, s, s))
    n = np.asarray(ibl.cube_texel_directions(size), np.float64).reshape(-1, 3)
    return np.maximum(n @ d.T, 0.0) @ (f.reshape(-1, 3).astype(np.float64) * w.reshape(-1, 1))


ENVIRONMENTS = {
    "sun + sky": envs.sun_disc((0.3, 0.8, 0.4), np.radians(2.0), 300.0, envs.sky_gradient()),
    "random smooth": envs.random_smooth(43),
}


@pytest.mark.parametrize("name", list(ENVIRONMENTS))
def test_equals_the_cpu_convolution_and_a_float64_sum(name: str) -> None:
    assert weft.validation_enabled()
    f = envs.to_faces(ENVIRONMENTS[name], 32, supersample=2)
    gpu = faces(ibl.irradiance_exact_gpu(f, 16, 32))
    cpu = faces(ibl.irradiance_exact(f, 16, 32))
    exact = float64_irradiance(f, 16)
    vs_cpu, vs_exact, cpu_exact = rel_diff(gpu, cpu), rel_diff(gpu, exact), rel_diff(cpu, exact)
    print(f"{name}: compute vs CPU mean {vs_cpu.mean():.2e} max {vs_cpu.max():.2e}; "
          f"vs float64 mean {vs_exact.mean():.2e} max {vs_exact.max():.2e} "
          f"(CPU vs float64 mean {cpu_exact.mean():.2e} max {cpu_exact.max():.2e})")
    assert vs_cpu.mean() < 2e-5 and vs_cpu.max() < 1e-4
    assert vs_exact.mean() < 3e-6 and vs_exact.max() < 2e-5


def test_the_source_is_reduced_as_on_the_cpu() -> None:
    # a 64^2 cube with source_size 16 sums its 16^2 mip level; source_size above the cube's size
    # sums the cube itself
    f = envs.to_faces(ENVIRONMENTS["sun + sky"], 64)
    for source in (16, 20, 128):
        gpu = faces(ibl.irradiance_exact_gpu(f, 8, source))
        cpu = faces(ibl.irradiance_exact(f, 8, source))
        assert rel_diff(gpu, cpu).max() < 1e-4, source


@pytest.mark.parametrize("size,source", [(1, 1), (1, 5), (3, 3), (5, 2), (40, 4)])
def test_partial_tiles_and_workgroups(size: int, source: int) -> None:
    # texel counts that are no multiple of the 64-texel tile, outputs that fill no workgroup
    # (512 outputs each) or end in a partial one (6 * 40^2 = 9600)
    f = envs.to_faces(envs.random_smooth(7), source)
    gpu = faces(ibl.irradiance_exact_gpu(f, size, source))
    assert gpu.shape == (6, size, size, 3)
    assert rel_diff(gpu, float64_irradiance(f, size)).max() < 2e-5


@pytest.mark.parametrize("size,source", [(1, 128), (2, 256)])
def test_large_sources_are_summed_to_the_end(size: int, source: int) -> None:
    # 3 and 12 dispatches of 32768 texels each. One dispatch over all of them came out 20-100 %
    # low on lavapipe, which silently ends a shader's loops after 65535 iterations in all.
    f = np.random.default_rng(5).uniform(0.5, 1.5, (6, source, source, 3)).astype(np.float32)
    gpu = faces(ibl.irradiance_exact_gpu(f, size, source))
    cpu = faces(ibl.irradiance_exact(f, size, source))
    assert rel_diff(gpu, cpu).max() < 1e-4


def test_constant_environment_gives_pi_l() -> None:
    level = np.array([0.7, 0.5, 0.3])
    f = envs.to_faces(envs.constant(level), 32)
    out = faces(ibl.irradiance_exact_gpu(f, 8, 32)).reshape(-1, 3)
    err = np.abs(out / (np.pi * level) - 1.0)
    print(f"constant environment: |E / (pi L) - 1| mean {err.mean():.2e}, max {err.max():.2e}")
    np.testing.assert_allclose(out, np.broadcast_to(np.pi * level, out.shape), rtol=2e-4)



def _raised(fn) -> BaseException:
    with pytest.raises(Exception) as info:
        fn()
    return info.value


def test_bad_arguments_raise_as_on_the_cpu() -> None:
    good = np.ones((6, 8, 8, 3), np.float32)
    inf, neg = good.copy(), good.copy()
    inf[1, 2, 3, 0] = np.inf
    neg[0, 0, 0, 0] = -1.0
    cases = {
        "not finite": (inf, 4, 8),
        "negative radiance": (neg, 4, 8),
        "size 0": (good, 0, 8),
        "size too large": (good, 1025, 8),
        "source size 0": (good, 4, 0),
        "source size too large": (good, 4, 1025),
        "too expensive": (good, 1024, 1024),
        "not a cube": (np.ones((6, 8, 8), np.float32), 4, 8),
        "not square": (np.ones((6, 8, 4, 3), np.float32), 4, 8),
        "integer radiance": (np.ones((6, 8, 8, 3), np.uint8), 4, 8),
        "no array": (None, 4, 8),
    }
    for name, (cube, size, source) in cases.items():
        cpu = _raised(lambda: ibl.irradiance_exact(cube, size, source))
        gpu = _raised(lambda: ibl.irradiance_exact_gpu(cube, size, source))
        assert isinstance(cpu, weft.InvalidArgument), (name, cpu)
        assert type(gpu) is type(cpu) and str(gpu) == str(cpu), (name, gpu, cpu)
