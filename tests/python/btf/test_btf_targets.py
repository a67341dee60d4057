"""Issue 12's targets on random materials (weft.btf.synth_random, seeds not tuned to), written
as 8-bit files and read back, small sizes: the Blinn-Phong highlight model chosen by deviation as
drawn recovers normals, exponent and k_s; what is drawn deviates as the fit does; cast shadows
leave normals within 2° mean / 6° p95, Lafortune too (with the Blinn-Phong normal); exponents stay
within what the light directions resolve; JPEG normals come better from the luma."""

from __future__ import annotations

import numpy as np
import pytest
import weft
from weft import btf
from weft.btf import scoring, synth
from weft.btf.material import BtfMaterial

NOISE = 0.004
SIZE = 32


def read_back(tmp_path, seed: int, fmt: str = "png", shadows: bool = False):
    samples, truth = synth.synthesize_random(seed, SIZE, shadows=shadows, noise=NOISE)
    folder = str(tmp_path / f"r{seed}{fmt}{int(shadows)}")
    btf.write(folder, samples, fmt=fmt, quality=90)
    return btf.load(folder), truth.material


def chosen_fit(samples, **kwargs):
    """Both highlight models and the one scoring.highlight_choice picks (as the CLI does)."""
    linear = btf.fit_linear(samples)
    fits = {}
    for flat in (False, True):
        seed = btf.fit_specular(samples, linear, flat).material
        fit = btf.fit_blinn_phong(samples, seed, flat_specular_normal=flat, **kwargs)
        fits[flat] = (scoring.score(samples, "bp", fit.material), fit)
    pick = scoring.highlight_choice(samples, {k: (s, f.shadowed_fraction)
                                              for k, (s, f) in fits.items()})
    return list(fits.values()), fits[pick["chosen"]]


def test_resolvable_exponent_follows_the_light_spacing() -> None:
    samples, _ = synth.synthesize_random(0, 8)
    # independently: nearest-neighbour angles between half vectors of the Bonn directions
    a = np.radians(np.asarray(samples.angles, np.float64))
    light = np.stack([np.sin(a[:, 0]) * np.cos(a[:, 1]), np.sin(a[:, 0]) * np.sin(a[:, 1]),
                      np.cos(a[:, 0])], -1)
    h = light + [0, 0, 1]
    h /= np.linalg.norm(h, axis=-1, keepdims=True)
    cos = h @ h.T
    np.fill_diagonal(cos, -1)
    delta = np.median(np.arccos(np.clip(cos.max(1), -1, 1)))
    assert np.degrees(delta) == pytest.approx(7.6, abs=0.1)  # half the 15° ring spacing
    want = np.log(100) / -np.log(np.cos(delta))
    assert btf.resolvable_exponent(samples) == pytest.approx(want, rel=1e-3)
    assert btf.resolvable_exponent(samples, 0.1) == pytest.approx(want / 2, rel=1e-3)
    with pytest.raises(weft.InvalidArgument):
        btf.resolvable_exponent(samples, 1.5)


# Not every random material meets the exponent / k_s targets: where the lobe is weak and near
# the resolvable width (seed 0 at 32²: k_s 0.04, e = 252 of 519, 13% off) or weak and broad
# (seed 2: k_s 0.025, e = 7.6 around (0,0,1), a smooth function of θ_l that the diffuse and
# constant terms absorb: even started at the truth the optimum lies 40% away, at a deviation
# below the truth's), the data do not pin them down at this noise (BENCHMARKS.md, btf).
@pytest.mark.parametrize("seed", [1, 3, 20, 21, 22, 23, 24, 25])
def test_unshadowed_targets(tmp_path, seed: int) -> None:
    samples, truth = read_back(tmp_path, seed)
    floor = scoring.score(samples, "truth", truth).fitted["total"]
    fits, (best, fit) = chosen_fit(samples)
    assert fit.material.flat_specular_normal == truth.flat_specular_normal
    t = scoring.truth_errors(fit.material, truth)
    assert t["mean_deg"] <= 0.5
    assert t["exponent_median_rel_error"] <= 0.10
    assert t["k_s_median_rel_error"] <= 0.10
    assert best.drawn["total"] <= 2.0 * floor
    e_max = btf.resolvable_exponent(samples)
    for s, f in fits:  # both highlight models: drawn as fitted, inside the physical space
        assert s.drawn["total"] <= 1.2 * s.fitted["total"]
        assert scoring.physical_violations(f.material)["texels"] == 0
        assert f.material.exponent_map.max() <= e_max * (1 + 1e-5)


def test_no_needle_lobes_where_the_model_is_wrong(tmp_path) -> None:
    # seed 1's highlight is around (0,0,1): the n_s = n fit used to park k ~ 4000 at e = 4096 in a
    # few texels, and the drawn specular map's one scale then rounded every other k to 0 (48x)
    samples, truth = read_back(tmp_path, 1)
    assert truth.flat_specular_normal
    seed = btf.fit_specular(samples, btf.fit_linear(samples), False).material
    m = btf.fit_blinn_phong(samples, seed, max_exponent=None).material
    assert m.specular.max() < 10
    s = scoring.score(samples, "n", m)
    assert s.drawn["total"] <= 1.2 * s.fitted["total"]


def test_specular_scale_clips_a_lone_needle() -> None:
    rng = np.random.default_rng(5)
    n = 16
    k = rng.uniform(0.05, 0.1, (n, n, 3)).astype(np.float32)
    k[3, 4] = 1000.0
    m = BtfMaterial(normal=np.tile([0, 0, 1.0], (n, n, 1)), albedo=np.full((n, n, 3), 0.3),
                    ambient=np.full((n, n, 3), 0.1), specular=k, exponent=50.0,
                    clamp_diffuse=True)
    drawn = m.as_drawn().specular
    others = np.ones((n, n), bool)
    others[3, 4] = False
    # every other texel within half an 8-bit step of a scale of at most 4x their 99th percentile
    assert np.abs(drawn[others] - k[others]).max() <= 4 * 0.1 / 510 + 1e-6
    assert drawn[3, 4].max() <= 0.4 + 1e-6


@pytest.mark.parametrize("seed", [6, 8])
def test_cast_shadow_targets(tmp_path, seed: int) -> None:
    samples, truth = read_back(tmp_path, seed, shadows=True)
    _, (_, fit) = chosen_fit(samples)
    t = scoring.truth_errors(fit.material, truth)
    assert t["mean_deg"] <= 2.0 and t["p95_deg"] <= 6.0
    laf = btf.fit_lafortune(samples, fit.material, 1, fixed_normal=True)
    np.testing.assert_allclose(laf.normal, fit.material.normal, atol=1e-6)
    lt = scoring.truth_errors(laf, truth)
    assert lt["p95_deg"] <= 6.0


# Seeds used by no other test or benchmark, which missed the cast-shadow p95 before the
# visibility pass started from a Lambert fit with σ bounded by the data's noise and restarted
# dropped lobes (p95 11.7° / 9.8° / 18.9° / 18.3°; now 0.3-0.9°): a broad lobe had absorbed the
# shadows' falloff or stood in for the diffuse term (106, 114), a σ measured on a fit pulled by
# shadows hid them (41), k = 0 from a needle start left the lobe absorbed by a tilted normal
# (103). Over 40 such seeds at 32² (BENCHMARKS.md, btf) none misses now.
@pytest.mark.parametrize("seed", [41, 103, 106, 114])
def test_cast_shadow_targets_on_unseen_seeds(tmp_path, seed: int) -> None:
    samples, truth = read_back(tmp_path, seed, shadows=True)
    _, (_, fit) = chosen_fit(samples, threads=2)
    assert fit.material.flat_specular_normal == truth.flat_specular_normal
    t = scoring.truth_errors(fit.material, truth)
    assert t["mean_deg"] <= 2.0 and t["p95_deg"] <= 6.0
    assert scoring.physical_violations(fit.material)["texels"] == 0


def test_a_needle_start_does_not_drop_a_broad_lobe() -> None:
    # seed 103's lobe is broad (e = 16.2); started at e = 4096 the NNLS gives k = 0, where the
    # cost does not depend on e and the search used to stay, with the lobe absorbed by tilting
    # the normal (12.5° p95); the fit now restarts such texels from a grid of exponents
    samples, truth = synth.synthesize_random(103, SIZE, noise=NOISE)
    seed = btf.fit_specular(samples, btf.fit_linear(samples), False).material
    seed = BtfMaterial(normal=seed.normal, albedo=seed.albedo, ambient=seed.ambient,
                       specular=seed.specular, exponent=4096.0, clamp_diffuse=True)
    m = btf.fit_blinn_phong(samples, seed, visibility=False, threads=2).material
    t = scoring.truth_errors(m, truth.material)
    assert t["p95_deg"] <= 1.0
    assert t["exponent_median_rel_error"] <= 0.10


def test_the_shadow_noise_level_is_the_datasets(tmp_path) -> None:
    # the cast-shadow test's σ is bounded by the data's noise, estimated over the whole image;
    # a band of rows fitted with the whole dataset's noise is exactly those rows of the whole fit
    samples, _ = read_back(tmp_path, 41, shadows=True)
    seed = btf.fit_specular(samples, btf.fit_linear(samples), False).material
    whole = btf.fit_blinn_phong(samples, seed, threads=2)
    sigma = btf.shadow_noise(samples, seed, threads=1)
    assert whole.noise == sigma
    # the generator's noise, 0.004 per channel, 8-bit quantised, summed over 3 channels: 0.0071
    # (the median texel's residuals are a little smaller for the fitted parameters, a little
    # larger for the model's error; 0.0081 here)
    assert 0.8 * 0.0071 <= sigma <= 1.5 * 0.0071
    rows = slice(8, 20)
    band = weft.BtfSamples(np.ascontiguousarray(samples.values[:, :, rows]), samples.angles)
    band_seed = BtfMaterial(normal=seed.normal[rows], albedo=seed.albedo[rows],
                            ambient=seed.ambient[rows], specular=seed.specular[rows],
                            exponent=seed.exponent, clamp_diffuse=True)
    part = btf.fit_blinn_phong(band, band_seed, threads=2, noise=sigma)
    np.testing.assert_array_equal(part.material.normal, whole.material.normal[rows])
    assert btf.fit_blinn_phong(samples, seed, visibility=False).noise == 0.0
    for bad in (-1.0, 0.0, float("nan"), float("inf"), True):
        with pytest.raises(weft.InvalidArgument):
            btf.fit_blinn_phong(samples, seed, noise=bad)


def test_jpeg_normals_from_the_luma(tmp_path) -> None:
    samples, truth = read_back(tmp_path, 1, fmt="jpg")
    linear = btf.fit_linear(samples)
    seed = btf.fit_specular(samples, linear, True).material
    err = {}
    for luma in (False, True):
        m = btf.fit_blinn_phong(samples, seed, flat_specular_normal=True,
                                luminance_normals=luma).material
        assert scoring.physical_violations(m)["texels"] == 0
        err[luma] = scoring.truth_errors(m, truth)["mean_deg"]
    assert err[True] < 0.8 * err[False]



# The speed target (Blinn-Phong >= 150 k texels/s on 2 cores, cast shadows included) is measured
# by `python -m weft.bench btf` from CPU time; wall clock on the shared test machine is no basis
# for a test. Most of the gain is per cost evaluation (NNLS inverses shared by the channels, the
# shadow terms and log h_z from the SIMD kernel); what a test can see without a clock is the LM
# stopping at the Gauss-Newton decrement: seed 8 took 13.3 / 14.4 iterations per texel before
# (n_s = n / (0,0,1)), 11.5 / 12.2 now, with the cast-shadow normal targets still met.
@pytest.mark.parametrize("seed", [8, 42])
def test_cast_shadow_fit_iterations(seed: int) -> None:
    samples, truth = synth.synthesize_random(seed, SIZE, shadows=True, noise=NOISE)
    linear = btf.fit_linear(samples)
    for flat in (False, True):
        seed_material = btf.fit_specular(samples, linear, flat).material
        fit = btf.fit_blinn_phong(samples, seed_material, flat_specular_normal=flat)
        assert fit.mean_iterations <= 12.5
        if flat == truth.material.flat_specular_normal:
            t = scoring.truth_errors(fit.material, truth.material)
            assert t["mean_deg"] <= 2.0 and t["p95_deg"] <= 6.0


def test_seed_sweep_reports_each_seed_and_all_texels(capsys) -> None:
    from weft.btf import seed_sweep

    assert seed_sweep.parse_seeds(["3", "5-7"]) == [3, 5, 6, 7]
    for bad in ("x", "7-5", "-1", "2-"):
        with pytest.raises(weft.InvalidArgument):
            seed_sweep.parse_seeds([bad])
    assert seed_sweep.main(["--seeds", "6", "8", "--size", "16"]) == 0
    out = capsys.readouterr().out
    assert "| 6 |" in out and "| 8 |" in out and "all texels: mean" in out
    assert "missing 2° mean:" in out and "missing 6° p95:" in out
    r = seed_sweep.fit_seed(6, 16)
    assert r["errors"].shape == (16, 16)
    assert r["mean_deg"] == pytest.approx(float(r["errors"].mean()))
    # the recommended pipeline on unshadowed JPEG: every unshadowed target judged
    assert seed_sweep.main(["--seeds", "1", "--size", "16", "--format", "jpg", "--no-shadows",
                            "--pooled"]) == 0
    out = capsys.readouterr().out
    assert all(f"missing {t}:" in out for t in ("0.5° mean", "exponent 10%", "k_s 10%"))
    r = seed_sweep.fit_seed(1, 16, shadows=False, pooled=True)
    assert 0 <= r["exponent_rel"] < 1 and 0 <= r["k_s_rel"] < 1
    for bad in (["--seeds", "x"], ["--seeds", "1", "--size", "2"]):
        with pytest.raises(SystemExit) as exit_:
            seed_sweep.main(bad)
        assert exit_.value.code == 2
        assert "error:" in capsys.readouterr().err
