"""References for the renderer's hair passes to come: deep opacity maps (SPEC §5.3) against
hand-computed layers and the analytic transmittance of a uniform slab, and weighted blended OIT
(SPEC §5.4) against hand-computed composites and exact depth-sorted "over"."""

from __future__ import annotations

import numpy as np
import pytest
from weft.reference import hair_oit as O
from weft.reference import hair_shadow as D


def test_layers_accumulate_into_all_layers_behind() -> None:
    pixel = np.array([0, 0, 0])
    depth = np.array([1.0, 1.5, 3.5])
    alpha = np.array([0.1, 0.2, 0.4])
    z0 = D.depth_pass(pixel, depth, 1)
    assert z0[0] == 1.0
    bounds = D.layer_bounds(1.0, 3, "linear")
    np.testing.assert_allclose(bounds, [0, 1, 2, 3])
    op = D.opacity_layers(pixel, depth, alpha, z0, bounds)
    np.testing.assert_allclose(op[0], [0.3, 0.3, 0.7])
    q = D.occlusion_at(op, z0, bounds, np.zeros(5, int), np.array([0.5, 1.5, 2.5, 3.5, 11.0]))
    np.testing.assert_allclose(q, [0.0, 0.15, 0.3, 0.5, 0.7])
    np.testing.assert_allclose(D.layer_bounds(1.0, 3, "log"), [0, 1, 3, 7])
    op_log = D.opacity_layers(pixel, depth, alpha, z0, D.layer_bounds(1.0, 3, "log"))
    np.testing.assert_allclose(op_log[0], [0.3, 0.7, 0.7])
    exact = D.exact_occlusion(pixel, depth, alpha, np.zeros(3, int), np.array([1.2, 3.0, 4.0]))
    np.testing.assert_allclose(exact, [0.1, 0.3, 0.7])


def test_uniform_slab_matches_exp_minus_k_depth() -> None:
    exact_err, dom_err, vs64, err64 = D.slab_errors(3, "linear")
    assert exact_err < 0.02  # the fragments themselves reproduce exp(-k z)
    assert dom_err < 0.02 and vs64 < 0.02 and err64 < 0.02
    _, log_err, _, _ = D.slab_errors(3, "log")
    assert log_err < 0.05


def test_rasterizer_one_fragment_per_pixel_per_segment() -> None:
    grid = D.LightGrid(direction=(0, -1, 0), center=(0, 0, 0), extent=1.0, resolution=10)
    pts = np.array([[-0.45, 0.0, 0.05], [0.45, -0.5, 0.05]])
    pix, dep, alp = D.rasterize_segments(pts, np.array([0, 2]), np.array([0.2, 0.4]), grid)
    assert len(np.unique(pix)) == len(pix) == 10  # crosses all 10 pixels of one row
    assert np.all(np.diff(dep) > 0) and np.allclose(alp, 0.3)


def test_wboit_single_layer_and_equal_colours_are_exact() -> None:
    rng = np.random.default_rng(1)
    for weight in O.WEIGHTS:
        c = rng.random((50, 1, 3))
        a = rng.random((50, 1))
        z = rng.uniform(0.1, 50, (50, 1))
        bg = rng.random((50, 3))
        np.testing.assert_allclose(O.wboit_composite(c, a, z, z / 60, bg, weight),
                                   O.sorted_over(c, a, z, bg), atol=1e-12)
        same = np.repeat(c, 4, axis=1)
        a4, z4 = rng.random((50, 4)), rng.uniform(0.1, 50, (50, 4))
        np.testing.assert_allclose(O.wboit_composite(same, a4, z4, z4 / 60, bg, weight),
                                   O.sorted_over(same, a4, z4, bg), atol=1e-12)


def test_wboit_hand_computed_two_layers() -> None:
    color = np.array([[1.0, 0, 0], [0, 0, 1.0]])
    alpha = np.array([0.5, 0.5])
    z = np.array([1.0, 2.0])
    bg = np.array([0.0, 1.0, 0.0])
    w1 = 0.5 * 10 / (1e-5 + 0.2 ** 2 + (1 / 200) ** 6)
    w2 = 0.5 * 10 / (1e-5 + 0.4 ** 2 + (2 / 200) ** 6)
    red = w1 / (w1 + w2)
    expected = 0.75 * np.array([red, 0.0, 1.0 - red]) + 0.25 * bg
    np.testing.assert_allclose(O.wboit_composite(color, alpha, z, z / 10, bg, "eq7"), expected)
    assert red == pytest.approx(0.8, abs=1e-3)
    np.testing.assert_allclose(O.sorted_over(color, alpha, z, bg), [0.5, 0.25, 0.25])
    # eq. 10 uses the depth-buffer value: w = alpha * max(1e-2, 3e3 (1 - z_ndc)^3)
    zn = np.array([0.5, 0.9])
    w = 0.5 * np.maximum(1e-2, 3e3 * (1 - zn) ** 3)
    np.testing.assert_allclose(O.wboit_composite(color, alpha, z, zn, bg, "eq10")[0],
                               0.75 * w[0] / w.sum())


def test_wboit_is_order_independent_and_close_to_sorted() -> None:
    rng = np.random.default_rng(3)
    c, a, z = rng.random((10, 6, 3)), rng.random((10, 6)), rng.uniform(1, 30, (10, 6))
    bg = rng.random((10, 3))
    perm = rng.permutation(6)
    for name in O.WEIGHTS:
        np.testing.assert_allclose(O.wboit_composite(c, a, z, z / 40, bg, name),
                                   O.wboit_composite(c[:, perm], a[:, perm], z[:, perm],
                                                     z[:, perm] / 40, bg, name))
    errors = O.random_stack_errors(500)
    for name, (mean, worst) in errors.items():
        assert 0.0 < mean < 0.15 and worst < 0.6, (name, mean, worst)
