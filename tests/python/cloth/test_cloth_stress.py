"""Stability stress of weft.Cloth (SPEC §2.5, not timed): time steps from 1/1000 to 1/15 s,
wind strength 1e3, a grab target teleported 10 m, all particles starting at one point; 10,000
steps each, after which (and at every step) every position is finite and inside a bounded box
(finite only when tearing can set pieces free). A small 8x8 cloth keeps it quick.
"""

from __future__ import annotations

from typing import Any, Callable, Dict

import numpy as np
import pytest
import weft

STEPS = 10_000
BOX = 50.0  # metres around the origin; the cloth is 1 m, the farthest grab target 10 m
N = 8


def _hanging(**settings: Any) -> "weft.Cloth":
    cloth = weft.Cloth(nx=N, ny=N, origin=(-0.5, 1.5, 0.0), axis_v=(0, -1, 0), **settings)
    cloth.pin([0, N - 1])
    return cloth


def _wind(cloth: "weft.Cloth") -> None:
    cloth.wind = weft.Wind(direction=(0.3, 0.2, 1.0), strength=1e3)


def _teleport(cloth: "weft.Cloth") -> None:
    corner = N * N - 1
    cloth.grab([corner], [[0.5, 0.5, 0.0]])
    for _ in range(5):
        cloth.step(1.0 / 60.0)
    cloth.move_grab([[10.5, -9.5, 10.0]])  # 10 m jumps in every direction at once


def _one_point(cloth: "weft.Cloth") -> None:
    cloth.set_positions(np.zeros((N * N, 3)))
    cloth.wind = weft.Wind(direction=(0.0, 0.0, 1.0), strength=50.0)


SCENARIOS: Dict[str, Callable[["weft.Cloth"], None]] = {
    "wind_1e3": _wind,
    "grab_teleported_10m": _teleport,
    "all_at_one_point": _one_point,
}

SETTINGS = {
    "seed": {},
    "accurate": dict(iterations=4, substeps=2, tethers=True, compliance_bend=1e-4),
    "features": dict(iterations=2, self_collision=True, thickness=0.01),
}
DTS = [1.0 / 1000.0, 1.0 / 60.0, 1.0 / 15.0]
DT_IDS = ["dt1000", "dt60", "dt15"]


def _add_colliders(cloth: "weft.Cloth") -> None:
    cloth.add_collider(weft.Collider.sphere((0.0, 0.6, 0.1), 0.3, friction=0.2))
    cloth.add_collider(weft.Collider.plane((0, -2.0, 0), (0, 1, 0)))


@pytest.mark.parametrize("dt", DTS, ids=DT_IDS)
@pytest.mark.parametrize("setting", sorted(SETTINGS))
@pytest.mark.parametrize("scenario", sorted(SCENARIOS))
def test_stays_finite_and_bounded(scenario: str, setting: str, dt: float) -> None:
    cloth = _hanging(**SETTINGS[setting])
    if setting == "features":
        _add_colliders(cloth)
    SCENARIOS[scenario](cloth)
    positions = cloth.positions  # a live view
    for k in range(STEPS):
        cloth.step(dt)
        if not (np.isfinite(positions).all() and np.abs(positions).max() <= BOX):
            worst = np.abs(np.nan_to_num(positions, nan=np.inf)).max()
            pytest.fail(f"step {k}: positions left the box or are not finite (max |x| {worst})")
    s = cloth.stats()
    assert np.isfinite(s["mean_strain"]) and np.isfinite(s["max_strain"])
    assert np.isfinite(cloth.kinetic_energy())
    mesh = cloth.mesh()
    for key in ("positions", "normals", "tangents"):
        assert np.isfinite(mesh[key]).all(), key


@pytest.mark.parametrize("dt", DTS, ids=DT_IDS)
@pytest.mark.parametrize("scenario", sorted(SCENARIOS))
def test_tearing_stays_finite(scenario: str, dt: float) -> None:
    """With tearing, pieces come off: a torn-off particle in a 1e3 m/s^2 wind or flung by a
    teleported grab flies on as physics says, so only finiteness is required here."""
    cloth = _hanging(iterations=2, self_collision=True, tear_strain=2.0, thickness=0.01)
    _add_colliders(cloth)
    SCENARIOS[scenario](cloth)
    positions = cloth.positions
    for k in range(STEPS):
        cloth.step(dt)
        if not np.isfinite(positions).all():
            pytest.fail(f"step {k}: positions are not finite")
    assert np.isfinite(cloth.mesh()["normals"]).all()
    assert np.isfinite(cloth.kinetic_energy())


def test_rejects_non_finite_inputs_mid_run() -> None:
    """NaN/inf never enter the state: every rejected call leaves the cloth as it was."""
    cloth = _hanging()
    for _ in range(10):
        cloth.step(1.0 / 60.0)
    before = np.array(cloth.positions)
    nan = float("nan")
    for call in (lambda: cloth.set_positions(np.full((N * N, 3), nan)),
                 lambda: cloth.set_velocities(np.full((N * N, 3), np.inf)),
                 lambda: cloth.grab([3], [[0.0, nan, 0.0]]),
                 lambda: cloth.step(nan),
                 lambda: setattr(cloth, "gravity", (nan, 0, 0)),
                 lambda: setattr(cloth, "compliance_stretch", nan),
                 lambda: setattr(cloth, "wind", weft.Wind(direction=(1, 0, 0), strength=nan)),
                 lambda: cloth.add_collider(weft.Collider.sphere((0, 0, nan), 0.2))):
        with pytest.raises(ValueError):
            call()
    np.testing.assert_array_equal(cloth.positions, before)
    cloth.step(1.0 / 60.0)
    assert np.isfinite(cloth.positions).all()
