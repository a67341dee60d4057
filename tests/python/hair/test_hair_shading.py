"""The GLSL hair shading models (glsl/common/hair_shading.glsl through a compute shader) against
the independent NumPy reference (weft.reference.hair) and analytic properties."""

from __future__ import annotations

import numpy as np
import pytest
import weft
from weft.reference import hair as R


def _random_dirs(n: int, seed: int):
    rng = np.random.default_rng(seed)
    return [rng.normal(size=(n, 3)) for _ in range(3)] + [rng.integers(0, 2 ** 32, n)]


def _rel_err(gpu: np.ndarray, ref: np.ndarray) -> np.ndarray:
    return (np.abs(gpu - ref) / np.maximum(np.abs(ref), 1e-3 * np.abs(ref).max())).max(axis=1)


@pytest.mark.parametrize("model", ["kajiya_kay", "sadeghi"])
def test_glsl_matches_numpy(model: str) -> None:
    t, l, v, ids = _random_dirs(3000, 1)
    mat = weft.HairMaterial(model, diffuse=(0.1, 0.2, 0.3), shininess=40.0, glint_intensity=2.0)
    gpu = weft.hair_shade_eval(mat, t, l, v, ids)
    ref = R.shade(R.HairParams.from_material(mat), t, l, v, ids)
    assert gpu.shape == (3000, 3) and gpu.dtype == np.float32
    assert _rel_err(gpu, ref).max() < 1e-4


def test_marschner_glsl_matches_numpy() -> None:
    t, l, v, ids = _random_dirs(3000, 2)
    mat = weft.HairMaterial("marschner", eta=1.6, absorption=(0.1, 0.4, 0.9))
    gpu = weft.hair_shade_eval(mat, t, l, v, ids)
    ref = R.shade(R.HairParams.from_material(mat), t, l, v, ids)
    err = _rel_err(gpu, ref)
    # Roots next to a TRT caustic are square-root conditioned: float32 loses digits there.
    assert np.quantile(err, 0.995) < 1e-4 and err.max() < 2e-2


def _sweep_theta_h(mat: "weft.HairMaterial", lobe: int):
    """theta_i = theta_o = theta_h (theta_d = 0), phi chosen where the lobe is non-zero."""
    th = np.radians(np.linspace(-30, 30, 601))
    phi = np.full_like(th, np.pi if lobe == 1 else 0.0)
    t, l, v = R.directions_for(th, th, phi)
    return th, weft.hair_shade_eval(mat, t, l, v)[:, 0], \
        R.shade(R.HairParams.from_material(mat), t, l, v)[:, 0]


@pytest.mark.parametrize("lobe", [0, 1, 2])
def test_sadeghi_lobes_peak_at_their_shifts(lobe: int) -> None:
    alpha_r = np.radians(-6.0)
    shifts = (alpha_r, -alpha_r / 2, -3 * alpha_r / 2)
    intensity = [0.0, 0.0, 0.0]
    intensity[lobe] = 1.0
    mat = weft.HairMaterial("sadeghi", shift=shifts, intensity=intensity, glint_intensity=0.0)
    th, gpu, ref = _sweep_theta_h(mat, lobe)
    step = th[1] - th[0]
    assert abs(th[np.argmax(ref)] - shifts[lobe]) <= step
    assert abs(th[np.argmax(gpu)] - shifts[lobe]) <= step


def test_default_shifts_follow_marschner_relations() -> None:
    a = weft.HairMaterial().shift
    assert (a[1] == pytest.approx(-a[0] / 2, rel=1e-5)
            and a[2] == pytest.approx(-1.5 * a[0], rel=1e-5))


def test_kajiya_kay_special_cases() -> None:
    mat = weft.HairMaterial("kajiya_kay", diffuse=(0.5, 0.5, 0.5), specular=(1, 1, 1), shininess=8)
    theta_o = np.radians(np.array([0.0, 20.0, 45.0, 70.0]))
    t, l, v = R.directions_for(np.zeros(4), theta_o, np.full(4, 1.0))
    f = weft.hair_shade_eval(mat, t, l, v)[:, 0]
    # light in the normal plane: diffuse = 0.5, specular = cos^m(angle of v from that plane)
    np.testing.assert_allclose(f, 0.5 + np.cos(theta_o) ** 8, rtol=1e-5)
    # light along the fibre: no diffuse; the specular cone degenerates to the -t direction
    f = weft.hair_shade_eval(mat, [[1, 0, 0]] * 2, [[1, 0, 0]] * 2, [[-1, 0, 0], [0, 1, 0]])
    np.testing.assert_allclose(f[:, 0], [1.0, 0.0], atol=1e-5)
    # mirror configuration theta_o = -theta_i is the specular peak whatever phi is
    t, l, v = R.directions_for(np.full(3, 0.4), np.full(3, -0.4), np.array([0.1, 1.5, 3.0]))
    np.testing.assert_allclose(weft.hair_shade_eval(mat, t, l, v)[:, 0],
                               0.5 * np.cos(0.4) + 1.0, rtol=1e-5)


@pytest.mark.parametrize("model", R.MODELS)
def test_degenerate_directions_are_finite_and_positive(model: str) -> None:
    t = np.array([[1, 0, 0]] * 6, float)
    l = np.array([[1, 0, 0], [0, 1, 0], [0, 1, 0], [0, 1, 0], [-1, 0, 0], [0.6, 0.8, 0]])
    v = np.array([[0, 1, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [1, 0, 0], [-0.6, 0.8, 0]])
    mat = weft.HairMaterial(model, diffuse=(0.2, 0.2, 0.2))
    f = weft.hair_shade_eval(mat, t, l, v, np.arange(6))
    assert np.all(np.isfinite(f)) and np.all(f >= 0)
    ref = R.shade(R.HairParams.from_material(mat), t, l, v, np.arange(6))
    np.testing.assert_allclose(f, ref, rtol=1e-4, atol=1e-5)


def test_marschner_azimuthal_energy_is_conserved() -> None:
    """Without absorption the azimuthal functions integrate to the fraction of light the three
    paths carry: int N_R + N_TT + N_TRT dphi = mean over h of F + (1-F)^2 + (1-F)^2 F <= 1."""
    p = R.HairParams(model="marschner", absorption=(0.0, 0.0, 0.0), caustic_width=0.02)
    phi = np.linspace(0.0, np.pi, 20001)
    eta = np.full_like(phi, p.eta)
    n_r = R.fresnel(eta, phi / 2) * np.cos(phi / 2) / 4
    total = n_r + R.marschner_n(p, 1, phi, eta, np.ones_like(phi))[:, 0] + \
        R.marschner_n(p, 2, phi, eta, np.ones_like(phi))[:, 0]
    integral = 2.0 * np.sum(0.5 * (total[1:] + total[:-1])) * (phi[1] - phi[0])
    h = np.linspace(-1, 1, 200001)
    f = R.fresnel(np.full_like(h, p.eta), np.arcsin(h))
    expected = np.mean(f + (1 - f) ** 2 + (1 - f) ** 2 * f)
    assert expected < 1.0
    assert integral == pytest.approx(expected, rel=0.03)


def test_material_validation_and_repr() -> None:
    m = weft.HairMaterial("marschner", eta=1.4)
    assert m.model == "marschner" and m.eta == pytest.approx(1.4)
    assert "marschner" in repr(m) and "eta=1.4" in repr(m)
    m.model = "kajiya_kay"
    with pytest.raises(weft.InvalidArgument):
        m.model = "phong"
    for name, value in [("eta", 0.9), ("shininess", -1.0), ("width", (0.1, 0.0, 0.1)),
                        ("diffuse", (0, float("nan"), 0)), ("glint_angle_min", 2.0),
                        ("shift", (1.0, 0, 0))]:
        with pytest.raises(weft.InvalidArgument):
            setattr(m, name, value)
    assert m.eta == pytest.approx(1.4)  # a rejected value leaves the material unchanged
    with pytest.raises(weft.InvalidArgument):
        weft.HairMaterial("sadeghi", tt_azimuthal_width=0.0)
    with pytest.raises(weft.InvalidArgument):
        weft.hair_shade_eval(weft.HairMaterial(), [[0, 0, 0]], [[0, 1, 0]], [[0, 1, 0]])
    with pytest.raises(weft.InvalidArgument):
        weft.hair_shade_eval(weft.HairMaterial(), [[1, 0, 0]], [[0, 1, 0]], [[0, 1, 0]] * 2)
