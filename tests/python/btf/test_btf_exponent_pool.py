"""Blinn-Phong exponents pooled over the material (fit_blinn_phong(exponent="pooled")), checked
against the generator's truth: one exponent where the material has one, the texels' own where
the material's exponents differ, and error bars that match the fits' real errors."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import weft
from weft import btf
from weft.btf import exponent_pool, scoring, synth
from weft.btf.synth_random import random_truth

SIZE = 32
NOISE = 0.004


def rendered(seed: int, exponent_map=None):
    """A random material (seed) with noise 0.004, optionally with its own exponent map."""
    material, height = random_truth(seed, SIZE, flat_specular_normal=False)
    material = dataclasses.replace(material, exponent_map=exponent_map)
    samples = synth.render_truth(material, height, shadows=False, noise=NOISE,
                                 noise_seed=seed + 7)
    return samples, material


def fits(samples):
    seed = btf.fit_specular(samples, btf.fit_linear(samples), False).material
    return {mode: btf.fit_blinn_phong(samples, seed, "builtin", exponent=mode)
            for mode in ("per_texel", "pooled")}


def exponent_error(fit, truth) -> float:
    return scoring.truth_errors(fit.material, truth)["exponent_median_rel_error"]


@pytest.mark.parametrize("seed", [31, 33])
def test_one_exponent_where_the_material_has_one(seed) -> None:
    samples, truth = rendered(seed)
    f = fits(samples)
    per_texel, pooled = exponent_error(f["per_texel"], truth), exponent_error(f["pooled"], truth)
    assert pooled < 0.05 and pooled < 0.5 * per_texel, (per_texel, pooled)
    assert f["pooled"].exponent_pool["spread"] < 0.15
    assert f["pooled"].exponent_pool["mean"] == pytest.approx(truth.exponent, rel=0.05)
    assert scoring.physical_violations(f["pooled"].material)["texels"] == 0
    # what is drawn fits as well: the pooled material's deviation within 2% of the per-texel's
    dev = {k: btf.deviation(samples, btf.sample_errors(samples, v.material))["total"]
           for k, v in f.items()}
    assert dev["pooled"] < 1.02 * dev["per_texel"]


def test_exponents_that_differ_are_kept() -> None:
    # two fibres: e x 3 and e / 3 in a random pattern
    material, _ = random_truth(32, SIZE, flat_specular_normal=False)
    region = synth._value_noise(np.random.default_rng(5), SIZE, 4) > 0.5
    e_map = np.where(region, material.exponent * 3, material.exponent / 3).astype(np.float32)
    samples, truth = rendered(32, e_map)
    f = fits(samples)
    assert f["pooled"].exponent_pool["spread"] > 0.5
    assert exponent_error(f["pooled"], truth) <= 1.2 * exponent_error(f["per_texel"], truth) + 0.01
    fitted = f["pooled"].material.exponent_map
    for inside in (region, ~region):
        assert np.median(fitted[inside]) == pytest.approx(np.median(e_map[inside]), rel=0.15)


def test_error_bars_match_the_errors() -> None:
    # Gaussian noise: (fitted η - true η) / its standard error should be ~N(0, 1) over texels
    samples, truth = rendered(34)
    fit = fits(samples)["per_texel"]
    var = exponent_pool.eta_variance(samples, fit.material)
    ok = np.isfinite(var) & (fit.material.specular.mean(-1) > 0.01)
    assert ok.mean() > 0.5
    z = (np.log(fit.material.exponent_map[ok]) - np.log(truth.exponent)) / np.sqrt(var[ok])
    spread = (np.percentile(z, 84) - np.percentile(z, 16)) / 2
    assert 0.75 < spread < 1.3, spread
    assert abs(np.median(z)) < 0.3
    # and the neighbours' differences agree: nothing to widen
    assert exponent_pool.error_scale(np.log(fit.material.exponent_map), var) < 1.15


def test_error_scale_from_neighbours() -> None:
    rng = np.random.default_rng(3)
    var = rng.uniform(0.01, 0.04, (48, 48))
    noise = rng.standard_normal((48, 48)) * np.sqrt(var)
    assert exponent_pool.error_scale(4.0 + noise, var) == pytest.approx(1.0, abs=0.12)
    # errors twice what the variances say: the variances are 4x too small
    assert exponent_pool.error_scale(4.0 + 2 * noise, var) == pytest.approx(4.0, rel=0.12)
    # two regions of different exponents: the pairs across their edge do not count
    regions = np.where(np.arange(48)[None, :] < 24, 3.0, 5.0) * np.ones((48, 1))
    assert exponent_pool.error_scale(regions + 2 * noise, var) == pytest.approx(4.0, rel=0.15)
    assert exponent_pool.error_scale(np.zeros((4, 4)), np.full((4, 4), np.inf)) == 1.0


def test_fixed_exponent_keeps_the_seeds() -> None:
    samples, _ = rendered(31)
    seed = btf.fit_specular(samples, btf.fit_linear(samples), False).material
    e_map = np.linspace(10, 200, SIZE * SIZE, dtype=np.float32).reshape(SIZE, SIZE)
    start = dataclasses.replace(seed, exponent_map=e_map)
    solvers = ["builtin"] + (["ceres"] if btf.have_ceres() else [])
    for solver in solvers:
        got = btf.fit_blinn_phong(samples, start, solver, exponent="fixed").material
        np.testing.assert_allclose(got.exponent_map, e_map, rtol=1e-5)


def test_exponent_mode_is_checked() -> None:
    samples, _ = rendered(31)
    seed = btf.fit_specular(samples, btf.fit_linear(samples), False).material
    with pytest.raises(weft.InvalidArgument, match="exponent must be"):
        btf.fit_blinn_phong(samples, seed, exponent="shared")


def test_pool_without_highlights_is_refused() -> None:
    with pytest.raises(ValueError, match="no texel"):
        exponent_pool.pool(np.zeros(4), np.full(4, np.inf))


@pytest.mark.parametrize("seed", [31, 33, 37])
def test_jpeg_cells_unbias_the_pooled_exponent(seed, tmp_path) -> None:
    # JPEG q90 broadens highlights alike in every texel: the decoded values' pooled exponent is
    # low; pooled from the fit refined against the files' cells it comes closer to the truth
    material, height = random_truth(seed, 64, flat_specular_normal=False)
    samples = synth.render_truth(material, height, shadows=False, noise=NOISE,
                                 noise_seed=seed + 7)
    btf.write(str(tmp_path), samples, fmt="jpg", quality=90)
    data = btf.load(str(tmp_path), jpeg_cells=True)
    start = btf.fit_specular(data, btf.fit_linear(data), False).material
    means = {cells: btf.fit_blinn_phong(data, start, luminance_normals=True, exponent="pooled",
                                        jpeg_cells=cells).exponent_pool["mean"]
             for cells in (False, True)}
    off = {k: abs(np.log(v / material.exponent)) for k, v in means.items()}
    assert off[True] < off[False], means
    assert off[True] < np.log(1.1), (means, material.exponent)
