"""Nonlinear BTF fits against ground truth on materials that are not presets: every texel inside
the physical space (non-negative reflectance, unit normals with n_z > 0, exponents in range),
normals, exponent and specular recovered, the seed's n_s = (0, 0, 1) option, and cast shadows
left out (issue 12)."""

from __future__ import annotations

import numpy as np
import pytest
from weft import btf
from weft.btf import synth
from weft.btf.material import BtfMaterial


def random_truth(seed: int, size: int = 32, ks: float = 0.2, exponent: float = 60.0,
                 flat: bool = False, relief: float = 6.0) -> BtfMaterial:
    """A random material (value-noise relief and colours), not one of the presets."""
    rng = np.random.default_rng(seed)
    height = sum(synth._value_noise(rng, size, c) / c for c in (4, 8)) * relief * size / 32
    albedo = 0.15 + 0.6 * np.stack([synth._value_noise(rng, size, 4) for _ in range(3)], -1)
    ambient = 0.03 + 0.12 * np.stack([synth._value_noise(rng, size, 4) for _ in range(3)], -1)
    specular = np.full((size, size, 3), ks) if ks > 0 else None
    return BtfMaterial(normal=synth._normals(height), albedo=albedo, ambient=ambient,
                       specular=specular, exponent=exponent, flat_specular_normal=flat,
                       clamp_diffuse=True)


def fit(samples, **kwargs):
    spec = btf.fit_specular(samples, btf.fit_linear(samples))
    return spec, btf.fit_blinn_phong(samples, spec.material, **kwargs)


def assert_physical(m: BtfMaterial, min_exponent: float = 1.0,
                    max_exponent: float = 4096.0) -> None:
    assert m.albedo.min() >= 0 and m.ambient.min() >= 0
    assert m.specular is not None and m.specular.min() >= 0
    np.testing.assert_allclose(np.linalg.norm(m.normal, axis=-1), 1.0, atol=1e-4)
    assert m.normal[..., 2].min() > 0
    e = m.exponent_map
    assert e is not None and e.min() >= min_exponent * (1 - 1e-5)
    assert e.max() <= max_exponent * (1 + 1e-5)


SOLVERS = ["builtin"] + (["ceres"] if btf.have_ceres() else [])


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("seed", [1, 2])
def test_every_texel_is_physical(solver: str, seed: int) -> None:
    # specular-free data with cast shadows: the unconstrained fit went negative exactly here
    truth = random_truth(seed, 24, ks=0.0)
    samples, _ = btf.synthesize("granite", 24, noise=0.004, seed=seed, material=truth,
                                shadows=True, height_scale=3)
    _, bp = fit(samples, solver=solver, min_exponent=2.0, max_exponent=500.0)
    assert_physical(bp.material, 2.0, 500.0)
    laf = btf.fit_lafortune(samples, bp.material, lobes=2)
    assert laf.diffuse.min() >= 0 and laf.ambient.min() >= 0 and laf.lobe_albedo.min() >= 0
    assert laf.normal[..., 2].min() > 0 and np.all(laf.lobe_shape[..., 2] > 0)
    assert laf.lobe_shape[..., 3].min() >= 1 - 1e-5 and laf.lobe_shape[..., 3].max() <= 4096.5


@pytest.mark.parametrize("flat", [False, True])
def test_unshadowed_truth_is_recovered(flat: bool) -> None:
    truth = random_truth(7, 32, ks=0.2, exponent=60.0, flat=flat)
    samples, _ = btf.synthesize("granite", 32, noise=0.004, seed=7, material=truth,
                                shadows=False)
    _, bp = fit(samples, flat_specular_normal=flat)
    m = bp.material
    assert_physical(m)
    assert m.flat_specular_normal == flat
    normals = btf.normal_stats(m.normal, truth.normal)
    assert normals["mean_deg"] <= 0.5, normals
    assert abs(np.median(m.exponent_map) / 60.0 - 1) <= 0.10
    assert abs(np.median(m.specular) / 0.2 - 1) <= 0.10
    assert bp.shadowed_fraction < 0.01  # noise is not taken for shadows
    # the fitted model sits at the noise floor: its deviation is the truth's own
    floor = btf.deviation(samples, btf.sample_errors(samples, truth))["total"]
    assert btf.deviation(samples, btf.sample_errors(samples, m))["total"] <= 1.05 * floor


def test_the_highlight_normal_is_chosen_by_error() -> None:
    """On data lit around n_s = (0,0,1) the flat option fits better, and the other way round:
    what the CLI's per-dataset choice relies on."""
    devs = {}
    for truth_flat in (False, True):
        truth = random_truth(3, 24, ks=0.25, exponent=40.0, flat=truth_flat)
        samples, _ = btf.synthesize("granite", 24, noise=0.004, seed=3, material=truth,
                                    shadows=False)
        spec = btf.fit_specular(samples, btf.fit_linear(samples))
        for flat in (False, True):
            m = btf.fit_blinn_phong(samples, spec.material, flat_specular_normal=flat).material
            devs[truth_flat, flat] = btf.deviation(samples, btf.sample_errors(samples, m))["total"]
    assert devs[True, True] < 0.8 * devs[True, False]
    assert devs[False, False] < 0.8 * devs[False, True]


def test_cast_shadows_are_left_out() -> None:
    samples, truth = btf.synthesize("corduroy", 128, noise=0.004, height_scale=3)
    spec = btf.fit_specular(samples, btf.fit_linear(samples))
    with_vis = btf.fit_blinn_phong(samples, spec.material)
    without = btf.fit_blinn_phong(samples, spec.material, visibility=False)
    assert_physical(with_vis.material)
    got = btf.normal_stats(with_vis.material.normal, truth.material.normal)
    assert got["mean_deg"] <= 2.0 and got["p95_deg"] <= 6.0, got
    base = btf.normal_stats(without.material.normal, truth.material.normal)
    assert got["mean_deg"] < 0.7 * base["mean_deg"], (got, base)
    # the generator's shadows: samples at least 0.05 darker than the unshadowed truth
    lit, _ = btf.synthesize("corduroy", 128, noise=0.004, height_scale=3, shadows=False)
    shadowed = ((lit.values - samples.values).sum(axis=1) > 0.05).mean()
    # it leaves out some (shadows at grazing light under a faint diffuse term stay in: they cost
    # little) and never more than there are
    assert 0.05 * shadowed < with_vis.shadowed_fraction < shadowed
    assert without.shadowed_fraction == 0.0


def test_huge_values_raise_or_stay_finite() -> None:
    samples, _ = btf.synthesize("wool", 8, noise=0.0)
    spec = btf.fit_specular(samples, btf.fit_linear(samples))
    for scale in (1e30, 3e37, 1e38):
        huge = type(samples)(samples.values * np.float32(scale), samples.angles)
        try:
            m = btf.fit_blinn_phong(huge, spec.material).material
        except ValueError as exc:  # weft.InvalidArgument: the maps do not fit in floats
            assert "Blinn-Phong" in str(exc)
            continue
        assert_physical(m)
        assert np.all(np.isfinite(m.albedo * m.ambient)) and np.all(np.isfinite(m.specular))
