"""The random material generator (independent data for the fits): deterministic per seed, a
valid truth, varied across seeds, and rendered like the presets."""

from __future__ import annotations

import numpy as np
import pytest
import weft
from weft.btf import synth, synth_random


def test_same_seed_same_data_other_seed_other_material() -> None:
    a, ta = synth.synthesize_random(3, 32)
    b, tb = synth.synthesize_random(3, 32)
    np.testing.assert_array_equal(a.values, b.values)
    np.testing.assert_array_equal(ta.material.normal, tb.material.normal)
    assert ta.material.exponent == tb.material.exponent
    c, tc = synth.synthesize_random(4, 32)
    assert not np.allclose(ta.material.albedo, tc.material.albedo)
    assert not np.allclose(ta.material.normal, tc.material.normal)
    assert not np.array_equal(a.values, c.values)


@pytest.mark.parametrize("seed", range(12))
def test_truth_is_a_valid_material(seed: int) -> None:
    m, height = synth_random.random_truth(seed, 40)
    assert height.shape == (40, 40) and np.all(np.isfinite(height))
    assert np.allclose(np.linalg.norm(m.normal, axis=-1), 1, atol=1e-5)
    assert np.all(m.normal[..., 2] > 0)
    assert np.all(m.albedo > 0) and np.all(m.ambient > 0) and m.clamp_diffuse
    lo, hi = synth_random.EXPONENT_RANGE
    assert lo <= m.exponent <= hi
    k = m.specular.max(axis=-1)
    assert np.all(k >= 0) and k.max() <= synth_random.K_S_RANGE[1] + 1e-6
    assert k.max() >= 0.7 * 0.85 * synth_random.K_S_RANGE[0]
    # the brightest possible sample stays below the 8-bit ceiling
    assert np.max(m.albedo * (1 + m.ambient) + m.specular) <= synth_random.PEAK + 1e-5
    tilt = np.degrees(np.arccos(m.normal[..., 2]))
    assert 5 < np.percentile(tilt, 90) < 50


def test_seeds_cover_the_ranges() -> None:
    mats = [synth_random.random_truth(s, 24)[0] for s in range(40)]
    exps = np.array([m.exponent for m in mats])
    assert exps.min() < 20 and exps.max() > 200  # log-uniform in [5, 500]
    flats = [m.flat_specular_normal for m in mats]
    assert 5 < sum(flats) < 35  # both highlights occur when not asked for
    colours = np.array([np.median(m.albedo.reshape(-1, 3), axis=0) for m in mats])
    assert np.ptp(colours, axis=0).min() > 0.2


def test_options_are_honoured() -> None:
    _, flat = synth.synthesize_random(1, 16, flat_specular_normal=True, noise=0)
    _, around_n = synth.synthesize_random(1, 16, flat_specular_normal=False, noise=0)
    assert flat.material.flat_specular_normal and not around_n.material.flat_specular_normal
    _, diffuse = synth.synthesize_random(1, 16, specular=False)
    assert diffuse.material.specular is None
    np.testing.assert_array_equal(diffuse.material.normal, flat.material.normal)


def test_rendering_matches_the_truth_and_shadows_darken() -> None:
    clean, truth = synth.synthesize_random(2, 24, noise=0.0)
    assert clean.count == 81 and clean.width == 24
    assert clean.values.max() <= synth_random.PEAK + 1e-5 and clean.values.min() >= 0
    # noise is what was asked for: the difference to the noise-free rendering
    noisy, _ = synth.synthesize_random(2, 24, noise=0.004)
    assert np.std(noisy.values - clean.values) == pytest.approx(0.004, rel=0.05)
    shadowed, st = synth.synthesize_random(2, 24, noise=0.0, shadows=True)
    assert st.shadows
    assert np.all(shadowed.values <= clean.values + 1e-6)
    grazing = np.asarray(clean.angles)[:, 0] == 75
    assert shadowed.values[grazing].mean() < 0.97 * clean.values[grazing].mean()
    # the "random" preset name is the same generator
    again, _ = synth.synthesize("random", 24, seed=2, noise=0.0)
    np.testing.assert_array_equal(again.values, clean.values)


@pytest.mark.parametrize("bad", [-1, 1.5, "3", True])
def test_bad_seed_is_a_clear_error(bad) -> None:
    with pytest.raises(weft.InvalidArgument, match="seed"):
        synth_random.random_truth(bad, 16)


def test_bad_size_is_a_clear_error() -> None:
    with pytest.raises(weft.InvalidArgument, match="size"):
        synth_random.random_truth(0, 2)
