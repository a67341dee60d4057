"""The blocked, vectorised linear fit against float64 ``np.linalg.lstsq`` per texel, on shapes
that exercise what the small fixtures of test_btf_fit.py do not: several 1024-texel blocks with a
tail that is not a multiple of the SIMD width, a sample count that is not a multiple of four
(two views), dark channels mixed into vectorised blocks, a given texture, and thread counts."""

from __future__ import annotations

import numpy as np
import pytest
import weft
from weft import btf
from weft.reference import btf as ref

H, W = 37, 41  # 1517 texels: one full block and a tail of 493


def angles(views: int) -> np.ndarray:
    lights = np.asarray(weft._core.btf_standard_directions(), np.float32)
    view_dirs = [(0.0, 0.0), (30.0, 90.0)][:views]
    return np.concatenate([np.column_stack([lights, np.tile(v, (81, 1))]) for v in view_dirs])


def random_samples(views: int, seed: int) -> "weft.BtfSamples":
    rng = np.random.default_rng(seed)
    values = rng.uniform(0.05, 0.95, (81 * views, 3, H, W)).astype(np.float32)
    values[:, 0, 3, 5:9] = 0.0       # red dark in four texels of the vectorised part
    values[:, :, 30, 40] = 0.0       # one texel dark in every channel, in the tail
    return weft.BtfSamples(values, angles(views))


def angle_deg(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    a, b = np.asarray(a, np.float64), np.asarray(b, np.float64)  # arccos near 1 needs float64
    a = a / np.linalg.norm(a, axis=-1, keepdims=True)
    b = b / np.linalg.norm(b, axis=-1, keepdims=True)
    return np.degrees(np.arccos(np.clip(np.sum(a * b, axis=-1), -1.0, 1.0)))


def lit_mask() -> np.ndarray:
    mask = np.ones((H, W), bool)
    mask[3, 5:9] = False  # no red equations: I_A,r is copied, not solved
    mask[30, 40] = False
    return mask


@pytest.mark.parametrize("views,threads", [(1, 1), (2, 0), (2, 3)])
def test_fit_linear_equals_float64_lstsq(views: int, threads: int) -> None:
    samples = random_samples(views, seed=views * 10 + threads)
    fit = btf.fit_linear(samples, threads=threads)
    values = samples.values.astype(np.float64)
    mean = values.mean(axis=0).transpose(1, 2, 0)
    np.testing.assert_allclose(fit.texture, mean, rtol=2e-6, atol=1e-7)
    expected = ref.lstsq_texels(values, np.asarray(samples.light_dirs, np.float64), mean)
    lit = lit_mask()
    assert angle_deg(fit.normal[lit], expected[lit][:, :3]).max() < 1e-3
    got = np.concatenate([fit.normal, fit.ambient], axis=-1).astype(np.float64)[lit]
    rel = np.linalg.norm(got - expected[lit], axis=-1) / np.linalg.norm(expected[lit], axis=-1)
    assert rel.max() <= 2e-6, rel.max()
    assert fit.dark_texels == 1 and fit.dark[30, 40] and fit.dark.sum() == 1
    assert fit.dark_channels == 4
    np.testing.assert_array_equal(fit.normal[30, 40], [0, 0, 1])
    # Dark red: the normal still comes from green and blue.
    for x in range(5, 9):
        assert angle_deg(fit.normal[3, x], expected[3, x, :3]) < 0.5


def test_normals_of_material_data_agree_with_float64_lstsq_to_1e3_degrees() -> None:
    samples, _ = btf.synthesize("corduroy", 40, noise=0.004, seed=5)
    fit = btf.fit_linear(samples)
    values = samples.values.astype(np.float64)
    mean = values.mean(axis=0).transpose(1, 2, 0)
    expected = ref.lstsq_texels(values, np.asarray(samples.light_dirs, np.float64), mean)
    assert angle_deg(fit.normal, expected[..., :3]).max() < 1e-3


def test_solve_linear_with_texture_equals_float64_lstsq() -> None:
    samples = random_samples(2, seed=7)
    rng = np.random.default_rng(8)
    texture = rng.uniform(0.2, 0.8, (H, W, 3)).astype(np.float32)
    fit = btf.solve_linear(samples, texture)
    expected = ref.lstsq_texels(samples.values, np.asarray(samples.light_dirs, np.float64),
                                texture.astype(np.float64))
    got = np.concatenate([fit.normal, fit.ambient], axis=-1).astype(np.float64)
    lit = lit_mask()
    rel = np.linalg.norm(got[lit] - expected[lit], axis=-1) / np.linalg.norm(expected[lit], axis=-1)
    assert rel.max() <= 2e-6, rel.max()


def test_non_finite_sample_is_named_by_the_fused_check() -> None:
    samples = random_samples(1, seed=3)
    values = samples.values
    values[57, 2, 36, 40] = np.nan  # the last texel of the tail
    with pytest.raises(weft.InvalidArgument, match="sample 57 holds a NaN"):
        btf.fit_linear(weft.BtfSamples(values, samples.angles))
    values[57, 2, 36, 40] = np.inf
    with pytest.raises(weft.InvalidArgument, match="sample 57 holds a NaN or infinite"):
        btf.fit_linear(weft.BtfSamples(values, samples.angles), robust=True)
