"""Issue 17 items 3-5: no NaN from accepted input.

A cloth far from the world origin must behave like one near it (the solver works relative to
the cloth's origin, rest lengths in double); parameters outside the documented physical ranges
(``weft.Cloth`` docstring, ``cloth_limits`` in Cloth.h) are rejected with weft.InvalidArgument;
``stats()`` never hides NaN; the wind is a value whose setters validate; ``advance()`` has a
bounded catch-up and cannot overflow.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import weft

DT = 1.0 / 60.0
FAR = np.array([3e5, 0.0, 0.0])


def _drape(origin: np.ndarray, n: int = 64, steps: int = 30) -> np.ndarray:
    cloth = weft.Cloth(n, n, origin=tuple(origin), axis_v=(0, -1, 0), iterations=2, threads=1)
    cloth.pin([0, n - 1])
    for _ in range(steps):
        cloth.step(DT)
    return cloth


def test_far_from_the_origin_behaves_like_near_it() -> None:
    """The issue's case: at (3e5, 0, 0) float32 rest lengths collapsed to 0 and the first step
    gave NaN. Truth: the same cloth at the world origin (translation invariance of the
    physics); the far one may differ only by the float32 spacing of its world coordinates."""
    near = _drape(np.zeros(3))
    far = _drape(FAR)
    c = far.constraints()
    assert np.all(c["rest"] > 0)
    np.testing.assert_allclose(c["rest"], near.constraints()["rest"], rtol=1e-6)
    x_far = np.asarray(far.positions, dtype=np.float64)
    assert np.isfinite(x_far).all()
    ulp = float(np.spacing(np.float32(3e5)))  # 1/32 m: what float32 world output can resolve
    np.testing.assert_allclose(x_far - FAR, np.asarray(near.positions, dtype=np.float64),
                               atol=ulp)
    # strain is measured in the local frame: the same as near the origin
    assert far.stats()["mean_strain"] == pytest.approx(near.stats()["mean_strain"], rel=1e-6)
    mesh = far.mesh()
    assert np.isfinite(mesh["positions"]).all() and np.isfinite(mesh["normals"]).all()


def test_far_cloth_collides_and_grabs_in_world_space() -> None:
    """Colliders, grabs and picking take world coordinates for a far cloth too."""
    for origin in (np.zeros(3), FAR):
        cloth = weft.Cloth(8, 8, origin=tuple(origin + [-0.5, 0.3, -0.5]), threads=1)
        cloth.add_collider(weft.Collider.plane(tuple(origin), (0, 1, 0)))
        for _ in range(60):
            cloth.step(DT)
        y = np.asarray(cloth.positions, dtype=np.float64)[:, 1] - origin[1]
        assert y.min() > 0.005 - 1e-3  # resting on the plane at the thickness
        k = 3 * 8 + 4
        p = np.asarray(cloth.positions[k], dtype=np.float64)
        assert cloth.pick(tuple(p + [0, 1, 0]), (0, -1, 0)) == k
        cloth.grab([k], [tuple(p + [0, 0.2, 0])])
        cloth.step(DT)
        np.testing.assert_allclose(np.asarray(cloth.positions[k], dtype=np.float64),
                                   p + [0, 0.2, 0], atol=float(np.spacing(np.float32(p[0]))) + 1e-6)


@pytest.mark.parametrize("kwargs", [
    dict(size=(1e-15, 1e-15)), dict(size=(1e30, 1e30)), dict(mass=1e-38), dict(mass=1e30),
    dict(origin=(1e30, 0, 0)), dict(gravity=(0, -1e30, 0)), dict(compliance_bend=1e30),
    dict(thickness=1e30), dict(self_thickness=1e30), dict(tear_strain=1e30),
    dict(sleep_threshold=1e30),
])
def test_out_of_range_parameters_rejected(kwargs: dict) -> None:
    """The issue's accepted-then-NaN inputs (and their kin) are rejected with a clear error."""
    with pytest.raises(weft.InvalidArgument):
        weft.Cloth(8, 8, **kwargs)


@pytest.mark.parametrize("kwargs", [dict(size=(1e-3, 1e-3)), dict(size=(1e3, 1e3)),
                                    dict(mass=1e-6), dict(mass=1e6)])
def test_range_ends_stay_finite(kwargs: dict) -> None:
    """The ends of the documented ranges are accepted and stay finite."""
    cloth = weft.Cloth(16, 16, axis_v=(0, -1, 0), threads=1, **kwargs)
    cloth.pin([0, 15])
    cloth.wind = weft.Wind((0.2, 0.1, 1.0), 1e4)
    for _ in range(20):
        cloth.step(DT)
    assert np.isfinite(np.asarray(cloth.positions)).all()
    s = cloth.stats()
    assert math.isfinite(s["mean_strain"]) and math.isfinite(s["max_strain"])


def test_wind_strength_range() -> None:
    cloth = weft.Cloth(8, 8)
    with pytest.raises(weft.InvalidArgument):
        cloth.wind = weft.Wind((1, 0, 0), 1e30)
    with pytest.raises(weft.InvalidArgument):
        weft.Wind((1, 0, 0), 1e30)
    with pytest.raises(weft.InvalidArgument):
        weft.Wind((0, 0, 0), 1.0)


def test_wind_is_a_value_with_validated_setters() -> None:
    """Issue item 4: ``c.wind.strength = nan`` or ``c.wind.direction = (0, 0, 0)`` reached the
    solver through a live reference and gave NaN."""
    cloth = weft.Cloth(8, 8, threads=1)
    cloth.wind = weft.Wind((0, 0, 1), 2.0)
    w = cloth.wind
    with pytest.raises(weft.InvalidArgument):
        w.strength = float("nan")
    with pytest.raises(weft.InvalidArgument):
        w.direction = (0, 0, 0)
    with pytest.raises(weft.InvalidArgument):
        w.direction = (0, float("inf"), 0)
    with pytest.raises(weft.InvalidArgument):
        cloth.wind.strength = float("nan")
    assert w.strength == 2.0 and w.direction == pytest.approx((0, 0, 1))  # unchanged
    # a copy: editing it changes the cloth only when assigned back
    w.strength = 5.0
    assert cloth.wind.strength == 2.0
    cloth.wind = w
    assert cloth.wind.strength == 5.0
    for _ in range(5):
        cloth.step(DT)
    assert np.isfinite(np.asarray(cloth.positions)).all()


def test_advance_huge_backlog_is_bounded() -> None:
    """Issue item 5: advance(1e10) returned -2147483648 and every later advance() ran no step."""
    cloth = weft.Cloth(4, 4, threads=1)
    assert cloth.advance(1e10) == 8  # the default max_steps; the backlog is dropped
    assert cloth.advance(1e30, rate=10000, max_steps=1000) == 1000
    assert cloth.advance(1.0 / 60.0 + 1e-6) == 1  # normal again
    assert cloth.advance(2.0 / 60.0 + 1e-6) == 2
    with pytest.raises(weft.InvalidArgument):
        cloth.advance(1.0, max_steps=1001)  # beyond the documented maximum catch-up
    with pytest.raises(weft.InvalidArgument):
        cloth.advance(float("inf"))
    assert cloth.step_count == 8 + 1000 + 1 + 2
