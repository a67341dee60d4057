"""BTF linear fit and specular search against NumPy float64 least squares and analytic truth."""

from __future__ import annotations

import numpy as np
import pytest
import weft
from weft import btf
from weft.reference import btf as ref

STD = np.asarray(weft._core.btf_standard_directions(), np.float64)


def frontal_angles() -> np.ndarray:
    return np.column_stack([STD, np.zeros((81, 2))]).astype(np.float32)


def light_dirs() -> np.ndarray:
    t, p = np.radians(STD[:, 0]), np.radians(STD[:, 1])
    return np.column_stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)])


def lambertian(size: int = 16):
    """Noise-free float Lambertian data (no shadows, no specular, n.l > 0 everywhere)."""
    samples, truth = btf.synthesize("wool", size, specular=0.0, shadows=False,
                                    height_scale=0.3)
    assert truth.material.specular is None
    nl = truth.material.normal.reshape(-1, 3) @ light_dirs().T
    assert nl.min() > 0.05  # no clamping anywhere: the linear model is exact
    return samples, truth


def test_linear_solve_equals_lstsq_on_random_data() -> None:
    rng = np.random.default_rng(3)
    values = rng.uniform(0.1, 0.9, (81, 3, 5, 6)).astype(np.float32)
    texture = rng.uniform(0.2, 0.8, (5, 6, 3)).astype(np.float32)
    samples = weft.BtfSamples(values, frontal_angles())
    mine = btf.solve_linear(samples, texture)
    expected = ref.lstsq_texels(values, np.asarray(samples.light_dirs, np.float64), texture)
    got = np.concatenate([mine.normal, mine.ambient], axis=-1).astype(np.float64)
    rel = np.linalg.norm(got - expected, axis=-1) / np.linalg.norm(expected, axis=-1)
    assert rel.max() <= 1e-5, rel.max()


def test_fit_linear_uses_the_mean_and_matches_lstsq() -> None:
    rng = np.random.default_rng(4)
    values = rng.uniform(0.05, 0.95, (81, 3, 4, 4)).astype(np.float32)
    samples = weft.BtfSamples(values, frontal_angles())
    fit = btf.fit_linear(samples)
    mean = values.astype(np.float64).mean(axis=0).transpose(1, 2, 0)
    np.testing.assert_allclose(fit.texture, mean, rtol=1e-6)
    expected = ref.lstsq_texels(values, np.asarray(samples.light_dirs, np.float64), mean)
    got = np.concatenate([fit.normal, fit.ambient], axis=-1)
    rel = np.linalg.norm(got - expected, axis=-1) / np.linalg.norm(expected, axis=-1)
    assert rel.max() <= 1e-5
    batched = ref.batched_normal_equations(values, samples.light_dirs)
    np.testing.assert_allclose(batched, expected, rtol=1e-3, atol=1e-4)


# The fits' own float model is scored here (drawn=False): these tests check the fitting math;
# what is drawn is checked in test_btf_render.py.


def test_noise_free_lambertian_recovers_normals_and_ambient() -> None:
    samples, truth = lambertian()
    fit = btf.fit_linear(samples)
    err = btf.angular_error_deg(fit.normal, truth.material.normal)
    assert err.max() < 0.01, err.max()
    # With T = mean the model's I_A and |n| carry the scale k = a + n.mean(l) (analytic):
    n_true = truth.material.normal.astype(np.float64)
    k = truth.material.ambient + (n_true @ light_dirs().mean(axis=0))[..., None]
    np.testing.assert_allclose(fit.ambient, truth.material.ambient / k, rtol=2e-5)
    material = fit.material(samples)  # a = I_A / |n| and ρ = T |n| undo the scale exactly
    np.testing.assert_allclose(material.ambient, truth.material.ambient, rtol=2e-5)
    np.testing.assert_allclose(material.albedo, truth.material.albedo, rtol=2e-5)
    assert btf.deviation(samples, btf.sample_errors(samples, material, drawn=False))["total"] < 1e-9


def test_dark_texels_are_reported_and_finite() -> None:
    samples, truth = lambertian(8)
    values = samples.values
    values[:, :, :2, :3] = 0.0           # 6 texels black in every channel
    values[:, 1, 5, 5] = 0.0             # one texel without green
    fit = btf.fit_linear(weft.BtfSamples(values, samples.angles))
    assert fit.dark_texels == 6 and fit.dark[:2, :3].all() and fit.dark.sum() == 6
    assert fit.dark_channels == 1
    assert np.all(np.isfinite(fit.normal)) and np.all(np.isfinite(fit.ambient))
    np.testing.assert_array_equal(fit.normal[0, 0], [0, 0, 1])
    assert btf.angular_error_deg(fit.normal[5, 5], truth.material.normal[5, 5]) < 0.01


def numpy_specular_error(samples, linear, exponents, flat: bool) -> np.ndarray:
    """E(e) = Σ (p - P_lin - g^e K)² re-derived in NumPy from the maps."""
    values = samples.values.astype(np.float64)
    l = np.asarray(samples.light_dirs, np.float64)
    v = np.asarray(samples.view_dirs, np.float64)
    n = linear.normal.astype(np.float64)
    nl = np.einsum("hwk,sk->shw", n, l)[..., None]
    lin = linear.texture[None] * (linear.ambient[None] + nl)
    r = values - lin.transpose(0, 3, 1, 2)
    s0 = int(np.flatnonzero((samples.angles[:, 0] == 0) & (samples.angles[:, 2] == 0))[0])
    k = r[s0]
    h = (l + v) / np.linalg.norm(l + v, axis=1, keepdims=True)
    if flat:
        u = np.broadcast_to(h[:, 2][:, None, None], (len(h),) + n.shape[:2])
    else:
        nn = n / np.linalg.norm(n, axis=-1, keepdims=True)
        u = np.maximum(np.einsum("hwk,sk->shw", nn, h), 0)
    return np.array([np.sum((r - (u ** e)[:, None] * k[None]) ** 2) for e in exponents])


@pytest.mark.parametrize("flat", [True, False])
def test_exponent_search_matches_numpy_error(flat: bool) -> None:
    samples, _ = btf.synthesize("granite", 12, noise=0.002)
    linear = btf.fit_linear(samples)
    spec = btf.fit_specular(samples, linear, flat_specular_normal=flat, max_exponent=512)
    exps = [e for e in (1, 7, 50, 128, 511) if np.isfinite(spec.curve[e - 1])]
    exps.append(int(spec.exponent))
    want = numpy_specular_error(samples, linear, exps, flat)
    np.testing.assert_allclose(spec.curve[np.array(exps) - 1], want, rtol=1e-4)
    if flat:  # every integer evaluated: the chosen one is the NumPy minimum over all of them
        full = numpy_specular_error(samples, linear, range(1, 513), flat)
        assert int(spec.exponent) == int(np.argmin(full)) + 1
    total = btf.deviation(samples, btf.sample_errors(samples, spec.material, drawn=False))["total"]
    assert total == pytest.approx(want[-1] / (samples.count * 3 * 144) * 100, rel=1e-4)


def test_flat_specular_normal_reproduces_the_first_group() -> None:
    samples, _ = btf.synthesize("upholstery", 16, noise=0.003)
    linear = btf.fit_linear(samples)
    flat = btf.fit_specular(samples, linear, flat_specular_normal=True)
    dev = btf.deviation(samples, btf.sample_errors(samples, flat.material, drawn=False))
    assert dev["groups"]["0"] < 1e-10
    fitted = btf.fit_specular(samples, linear, flat_specular_normal=False)
    dev_n = btf.deviation(samples, btf.sample_errors(samples, fitted.material, drawn=False))
    assert dev_n["groups"]["0"] > 1e-6  # eq. 4.29 does not (seed table 4.2)
    lin_dev = btf.deviation(samples, btf.sample_errors(samples, linear.material(samples),
                                                       drawn=False))
    assert dev["total"] < lin_dev["total"]


def test_per_texel_exponent_lowers_the_error() -> None:
    samples, _ = btf.synthesize("granite", 16, noise=0.001)
    linear = btf.fit_linear(samples)
    one = btf.fit_specular(samples, linear)
    per = btf.fit_specular(samples, linear, per_texel=True)
    assert per.material.exponent_map is not None
    e1 = btf.sample_errors(samples, one.material, drawn=False).mean()
    e2 = btf.sample_errors(samples, per.material, drawn=False).mean()
    assert e2 < e1


def test_robust_fit_lowers_normal_error_under_cast_shadows() -> None:
    samples, truth = btf.synthesize("corduroy", 48, specular=0.0, shadows=True)
    plain = btf.normal_stats(btf.fit_linear(samples).normal, truth.material.normal)
    robust = btf.normal_stats(btf.fit_linear(samples, robust=True).normal,
                              truth.material.normal)
    assert robust["mean_deg"] < 0.8 * plain["mean_deg"], (plain, robust)


def test_bad_input_is_rejected() -> None:
    angles = frontal_angles()
    ok = np.full((81, 3, 2, 2), 0.5, np.float32)
    bad = ok.copy()
    bad[3, 1, 0, 0] = np.nan
    with pytest.raises(ValueError):
        weft.BtfSamples(bad, angles)
    with pytest.raises(ValueError):
        weft.BtfSamples(ok[:, :2], angles)
    with pytest.raises(ValueError):
        weft.BtfSamples(ok, angles[:, :3])
    with pytest.raises(weft.InvalidArgument):
        weft.BtfSamples(ok[:1], np.array([[95.0, 0, 0, 0]], np.float32))
    flat = np.zeros((5, 4), np.float32)  # five samples all at θ_l = 0: normal undetermined
    with pytest.raises(weft.InvalidArgument, match="coplanar"):
        btf.fit_linear(weft.BtfSamples(np.full((5, 3, 2, 2), 0.5, np.float32), flat))
    samples = weft.BtfSamples(ok, angles)
    linear = btf.fit_linear(samples)
    with pytest.raises(ValueError):
        btf.fit_specular(samples, linear, max_exponent=1)
    with pytest.raises(ValueError):
        btf.solve_linear(samples, np.zeros((3, 2, 3)))
    with pytest.raises(ValueError):
        btf.fit_linear(samples, robust=True, robust_iterations=0)
    with pytest.raises(ValueError):
        btf.synthesize("velvet", 8)
    with pytest.raises(ValueError):
        btf.synthesize("wool", 8, noise=-1.0)
    material = linear.material(samples)
    with pytest.raises(ValueError):
        btf.BtfMaterial(normal=material.normal * 2, albedo=material.albedo,
                        ambient=material.ambient)
    with pytest.raises(ValueError):
        btf.BtfMaterial(normal=material.normal, albedo=material.albedo[:1],
                        ambient=material.ambient)
    with pytest.raises(ValueError):
        btf.fit_blinn_phong(samples, material, solver="magic")
    with pytest.raises(ValueError):
        btf.fit_blinn_phong(samples, material, min_exponent=10, max_exponent=5)
    other = weft.BtfSamples(np.full((81, 3, 3, 3), 0.5, np.float32), angles)
    with pytest.raises(ValueError):
        btf.sample_errors(other, material)
