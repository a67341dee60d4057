"""Scoring helpers of the BTF report and benchmark: physical-space counts, truth errors, the
Lafortune reconstruction the figures use, and non-black previews."""

from __future__ import annotations

import numpy as np
import pytest
from weft import btf
from weft.btf import report, scoring, synth


def test_physical_violations_count_texels() -> None:
    _, truth = synth.synthesize_random(0, 8, noise=0)
    m = truth.material
    assert scoring.physical_violations(m)["texels"] == 0
    albedo = m.albedo.copy()
    albedo[0, 0, 1] = -0.1
    spec = m.specular.copy()
    spec[0, 0] = -1
    spec[1, 1, 2] = -1e-3
    emap = np.full(m.shape, 50.0, np.float32)
    emap[2, 3] = 0.5
    bad = btf.BtfMaterial(normal=m.normal, albedo=albedo, ambient=m.ambient, specular=spec,
                          exponent_map=emap, exponent=50)
    v = scoring.physical_violations(bad)
    assert (v["albedo"], v["specular"], v["exponent"], v["texels"]) == (1, 2, 1, 3)
    n = m.normal.copy()
    n[4, 4] = (0.6, 0.8, 0.0)
    v = scoring.physical_violations(btf.BtfMaterial(normal=n, albedo=m.albedo,
                                                    ambient=m.ambient))
    assert v["normal"] == 1 and v["texels"] == 1


def test_truth_errors_of_the_truth_are_zero_and_grow_with_error() -> None:
    _, truth = synth.synthesize_random(1, 16, noise=0)
    m = truth.material
    t = scoring.truth_errors(m, m)
    assert t["mean_deg"] < 1e-3 and t["albedo_abs_error"] == 0
    assert t["k_s_median_rel_error"] == 0 and t["exponent_median_rel_error"] == 0
    worse = btf.BtfMaterial(normal=m.normal, albedo=m.albedo, ambient=m.ambient,
                            specular=m.specular * 1.2, exponent=m.exponent * 0.5)
    t = scoring.truth_errors(worse, m)
    assert t["k_s_median_rel_error"] == pytest.approx(0.2, rel=1e-4)
    assert t["exponent_median_rel_error"] == pytest.approx(0.5, rel=1e-4)


def test_lafortune_reconstruction_matches_its_errors() -> None:
    samples, _ = synth.synthesize("wool", 12, noise=0.002)
    seed = btf.fit_specular(samples, btf.fit_linear(samples)).material
    for lobes in (1, 2):
        fit = btf.fit_lafortune(samples, seed, lobes)
        recon = scoring.lafortune_reconstruction(fit, samples)
        mine = ((recon - samples.values) ** 2).mean(axis=(1, 2, 3))
        np.testing.assert_allclose(mine, fit.errors(samples), rtol=1e-3, atol=1e-9)


def test_best_of_prefers_drawable_models() -> None:
    samples, truth = synth.synthesize_random(2, 12, noise=0.004)
    linear = btf.fit_linear(samples)
    seed = btf.fit_specular(samples, linear).material
    scored = [scoring.score(samples, "linear", linear.material(samples)),
              scoring.score(samples, "spec", seed),
              scoring.score(samples, "laf", btf.fit_lafortune(samples, seed, 2))]
    assert not scored[2].drawable and scored[2].label == "laf (not drawn)"
    best = scoring.best_of(scored)
    assert best.drawable and best.deviation == min(s.deviation for s in scored[:2])
    assert scoring.best_of(scored, drawable_only=False).deviation == min(
        s.deviation for s in scored)


def test_preview_of_a_dark_map_with_an_outlier_is_not_black() -> None:
    value = np.full((16, 16, 3), 0.01, np.float32)
    value[3, 3] = 1000.0
    img, how = report.preview("specular", value)
    assert np.median(img) > 200 and "0.01" in how
    img, how = report.preview("normal", np.dstack([np.zeros((4, 4, 2)), np.ones((4, 4))]))
    assert img[0, 0].tolist() == [128, 128, 255] and how == "(n + 1) / 2"
