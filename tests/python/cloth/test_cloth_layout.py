"""The structure-of-arrays relaxation (CPUs with AVX-512) against the record layout.

On such CPUs weft relaxes a cloth without colliders in a structure-of-arrays copy of the
particles (``cpp/src/sim/cloth/ClothKernels.h``, ``SoaParticles``); ``WEFT_CLOTH_AOS=1`` at
construction keeps the record layout, whose SIMD kernels the C++ tests hold bit-identical to
the scalar projection. Both must give bit-identical positions for every feature that reaches
the relaxation: batches of every offset (bend distance 2, 4, 6, extra axial), grids whose width
is no multiple of the vector width, tethers (few and many anchors), XPBD, holes, tearing,
grabs, pins changed mid-run, wind, and any thread count. On CPUs without AVX-512 both runs would
take the record layout, so the module is skipped there.
"""

from __future__ import annotations

from typing import Any, Callable, Dict, Optional

import numpy as np
import pytest
import weft

pytestmark = pytest.mark.skipif(not weft.Cloth.soa_kernels_available(),
                                reason="no AVX-512: the record layout is the only path")

DT = 1.0 / 60.0


def run(monkeypatch: pytest.MonkeyPatch, aos: bool, n: int, m: int, steps: int,
        setup: Optional[Callable[[Any], None]] = None,
        during: Optional[Callable[[Any, int], None]] = None,
        **settings: Any) -> np.ndarray:
    if aos:
        monkeypatch.setenv("WEFT_CLOTH_AOS", "1")
    else:
        monkeypatch.delenv("WEFT_CLOTH_AOS", raising=False)
    kw: Dict[str, Any] = dict(nx=n, ny=m, origin=(-0.5, 1.5, 0.0), axis_u=(1, 0, 0),
                              axis_v=(0, -1, 0))
    kw.update(settings)
    cloth = weft.Cloth(**kw)
    cloth.pin([0, n - 1])
    if setup:
        setup(cloth)
    for s in range(steps):
        if during:
            during(cloth, s)
        cloth.step(DT)
    return np.array(cloth.positions, copy=True)


def holes(cloth: Any) -> None:
    mask = np.zeros((cloth.ny, cloth.nx), dtype=np.uint8)
    mask[cloth.ny // 3: cloth.ny // 2, cloth.nx // 4: cloth.nx // 2] = 1
    cloth.set_holes(mask)


def many_anchors(cloth: Any) -> None:
    cloth.pin(list(range(0, cloth.nx, 2)))  # more than 16 anchors: the gather path


def grab_and_pin(cloth: Any, s: int) -> None:
    if s == 5:
        cloth.grab([cloth.nx * (cloth.ny - 1)], [(-0.9, 0.2, 0.4)])
    if s == 12:
        cloth.release()
        cloth.pin([cloth.nx // 2])


CASES = {
    "seed-k2": dict(),
    "k4-axial-xpbd": dict(bend_distance=4, extra_axial=True, iterations=2,
                          compliance_stretch=1e-4, compliance_shear=1e-2, compliance_bend=1.0),
    "k6-tethers-sub2": dict(bend_distance=6, tethers=True, substeps=2),
    "tethers-it2-tear": dict(tethers=True, iterations=2, tear_strain=0.05),
    "wind-sub3": dict(substeps=3, tethers=True),
}


@pytest.mark.parametrize("size", [(17, 11), (32, 32), (45, 38)])
@pytest.mark.parametrize("case", sorted(CASES))
def test_soa_matches_records(monkeypatch: pytest.MonkeyPatch, case: str, size: Any) -> None:
    n, m = size
    settings = dict(CASES[case])
    during = None
    if case == "wind-sub3":
        during = lambda c, s: setattr(c, "wind", weft.Wind(direction=(0, 0.2, 1), strength=6.0))
    if case == "tethers-it2-tear":
        during = grab_and_pin
    base = run(monkeypatch, True, n, m, 30, during=during, threads=1, **settings)
    for threads in (1, 2, 3):
        got = run(monkeypatch, False, n, m, 30, during=during, threads=threads, **settings)
        np.testing.assert_array_equal(got, base, err_msg=f"{case} {size} threads={threads}")


@pytest.mark.parametrize("setup", [holes, many_anchors])
def test_soa_matches_records_holes_and_anchors(monkeypatch: pytest.MonkeyPatch,
                                               setup: Callable[[Any], None]) -> None:
    settings = dict(tethers=True, iterations=2, substeps=2, threads=2)
    base = run(monkeypatch, True, 40, 33, 40, setup=setup, **settings)
    got = run(monkeypatch, False, 40, 33, 40, setup=setup, **settings)
    np.testing.assert_array_equal(got, base)
    assert np.all(np.isfinite(got))


def test_soa_matches_records_in_parallel(monkeypatch: pytest.MonkeyPatch) -> None:
    """A grid large enough that batches, tethers, integration and copies split across
    threads (the small grids above run on one)."""
    settings = dict(tethers=True, substeps=2, compliance_shear=1e-3, tear_strain=0.3)
    base = run(monkeypatch, True, 150, 97, 12, threads=1, **settings)
    for threads in (2, 3):
        got = run(monkeypatch, False, 150, 97, 12, threads=threads, **settings)
        np.testing.assert_array_equal(got, base, err_msg=f"threads={threads}")
