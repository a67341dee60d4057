"""Nonlinear Blinn-Phong fits: better than the linear + specular pipeline, Ceres and the built-in
Levenberg-Marquardt agree, and several views are fitted with one model."""

from __future__ import annotations

import numpy as np
import pytest
from weft import btf


def total(samples, material) -> float:
    return btf.deviation(samples, btf.sample_errors(samples, material))["total"]


@pytest.fixture(scope="module")
def wool():
    samples, truth = btf.synthesize("wool", 24, noise=0.002)
    linear = btf.fit_linear(samples)
    spec = btf.fit_specular(samples, linear)
    return samples, truth, linear, spec


def test_blinn_phong_beats_linear_plus_specular(wool) -> None:
    samples, truth, linear, spec = wool
    bp = btf.fit_blinn_phong(samples, spec.material, solver="builtin")
    assert bp.solver == "builtin"
    assert total(samples, bp.material) < 0.7 * total(samples, spec.material)
    # the model fits the truth's family: normals closer to the truth than the linear fit's
    lin = btf.normal_stats(linear.normal, truth.material.normal)["mean_deg"]
    assert btf.normal_stats(bp.material.normal, truth.material.normal)["mean_deg"] < lin
    assert bp.material.exponent_map is not None and bp.material.clamp_diffuse


def test_noise_free_blinn_phong_recovers_the_truth() -> None:
    samples, truth = btf.synthesize("granite", 10, noise=0.0)
    spec = btf.fit_specular(samples, btf.fit_linear(samples))
    bp = btf.fit_blinn_phong(samples, spec.material, solver="builtin", max_iterations=60)
    err = btf.angular_error_deg(bp.material.normal, truth.material.normal)
    assert np.percentile(err, 90) < 0.01
    exps = bp.material.exponent_map / truth.material.exponent
    assert np.percentile(np.abs(exps - 1), 90) < 1e-3


@pytest.mark.skipif(not btf.have_ceres(), reason="weft built without Ceres Solver")
def test_ceres_and_builtin_agree(wool) -> None:
    samples, _, _, spec = wool
    small = samples  # 24 x 24: Ceres builds one problem per texel
    builtin = btf.fit_blinn_phong(small, spec.material, solver="builtin", max_iterations=60)
    ceres = btf.fit_blinn_phong(small, spec.material, solver="ceres", max_iterations=60)
    assert ceres.solver == "ceres"
    e_b = btf.sample_errors(small, builtin.material).mean()
    e_c = btf.sample_errors(small, ceres.material).mean()
    assert e_b == pytest.approx(e_c, rel=0.02)
    angle = btf.angular_error_deg(builtin.material.normal, ceres.material.normal)
    assert np.median(angle) < 0.05


def test_ceres_missing_is_a_clear_error(wool) -> None:
    samples, _, _, spec = wool
    if btf.have_ceres():
        pytest.skip("weft built with Ceres Solver")
    with pytest.raises(ValueError, match="Ceres"):
        btf.fit_blinn_phong(samples, spec.material, solver="ceres")


def test_all_views_share_one_model() -> None:
    samples, truth = btf.synthesize("polyacrylic", 12, views=4, noise=0.001)
    assert samples.count == 4 * 81
    linear = btf.fit_linear(samples)
    spec = btf.fit_specular(samples, linear)
    bp = btf.fit_blinn_phong(samples, spec.material, solver="builtin")
    dev = btf.deviation(samples, btf.sample_errors(samples, bp.material))
    assert set(dev["views"]) == {"tv000_pv000", "tv015_pv000", "tv015_pv060", "tv015_pv120"}
    assert max(dev["views"].values()) < total(samples, spec.material)
    frontal, _ = btf.synthesize("polyacrylic", 12, views=1, noise=0.001)
    one = btf.normal_stats(btf.fit_linear(frontal).normal, truth.material.normal)
    many = btf.normal_stats(linear.normal, truth.material.normal)
    assert many["mean_deg"] < 2 * one["mean_deg"] + 0.5  # more views never derail the normal


def test_lafortune_lobes_beat_linear_plus_specular(wool) -> None:
    samples, truth, _, spec = wool
    two = btf.fit_lafortune(samples, spec.material, lobes=2)
    assert two.lobe_shape.shape == (24, 24, 2, 4) and "2 lobe" in repr(two)
    assert btf.deviation(samples, two.errors(samples))["total"] < total(samples, spec.material)
    one = btf.fit_lafortune(samples, spec.material, lobes=1)
    assert two.errors(samples).mean() < one.errors(samples).mean()
    with pytest.raises(ValueError):
        btf.fit_lafortune(samples, spec.material, lobes=3)


def test_lafortune_uses_the_view_directions() -> None:
    samples, _ = btf.synthesize("wool", 12, views=4, noise=0.001)
    spec = btf.fit_specular(samples, btf.fit_linear(samples))
    one = btf.fit_lafortune(samples, spec.material, lobes=1)
    assert btf.deviation(samples, one.errors(samples))["total"] < total(samples, spec.material)
    # with oblique views C_x, C_y move from their start (-1) towards the mirror lobe's values
    assert np.any(np.abs(one.lobe_shape[..., 0] + 1) > 1e-4)


def test_auto_solver_is_the_builtin(wool) -> None:
    samples, _, _, spec = wool
    assert btf.fit_blinn_phong(samples, spec.material).solver == "builtin"


def test_simd_paths_agree() -> None:
    """The kernels picked at run time (AVX-512VL or AVX2, 8 lanes) and the 4-lane generic ones
    fit the same model; the AVX-512VL copy is the AVX2 code with more registers: the same bits."""
    import json
    import os
    import subprocess
    import sys

    code = ("import json; from weft import btf; s, _ = btf.synthesize('corduroy', 16, "
            "noise=0.002); sp = btf.fit_specular(s, btf.fit_linear(s)); "
            "f = btf.fit_blinn_phong(s, sp.material); "
            "print(json.dumps([f.material.normal.tolist(), f.material.exponent_map.tolist(), "
            "float(btf.sample_errors(s, f.material).mean())]))")
    runs = []
    for simd in ("", "avx2", "generic"):
        env = dict(os.environ, WEFT_BTF_SIMD=simd)
        out = subprocess.run([sys.executable, "-c", code], env=env, check=True,
                             capture_output=True, text=True).stdout
        runs.append(json.loads(out))
    assert runs[0] == runs[1]
    (n_a, e_a, err_a), _, (n_b, e_b, err_b) = runs
    assert err_a == pytest.approx(err_b, rel=0.01)
    angle = btf.angular_error_deg(np.asarray(n_a, np.float32), np.asarray(n_b, np.float32))
    assert np.median(angle) < 0.01
    assert np.median(np.abs(np.asarray(e_a) / np.asarray(e_b) - 1)) < 1e-3
