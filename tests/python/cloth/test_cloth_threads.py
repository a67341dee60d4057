"""Issue 17 item 6: concurrent calls on one cloth serialise, never hang.

Two Python threads stepping one cloth used to deadlock inside the shared worker pool, and so did
stepping while another thread set ``threads``. Every call now takes the cloth's lock. The
threads here are daemons joined with a timeout, so a regression fails the test instead of
hanging the suite.
"""

from __future__ import annotations

import threading
import time
from typing import Callable, List

import numpy as np
import weft

DT = 1.0 / 60.0
TIMEOUT = 60.0  # s; the work below takes well under a second per thread on 2 cores


def _cloth(n: int = 128, **kw) -> "weft.Cloth":
    cloth = weft.Cloth(n, n, origin=(-0.5, 1.5, 0.0), axis_v=(0, -1, 0), threads=2, **kw)
    cloth.pin([0, n - 1])
    return cloth


def _run(workers: List[Callable[[], None]]) -> None:
    errors: List[BaseException] = []

    def guard(fn: Callable[[], None]) -> Callable[[], None]:
        def body() -> None:
            try:
                fn()
            except BaseException as e:  # reported below
                errors.append(e)
        return body

    threads = [threading.Thread(target=guard(w), daemon=True) for w in workers]
    for t in threads:
        t.start()
    deadline = time.monotonic() + TIMEOUT
    for t in threads:
        t.join(max(0.0, deadline - time.monotonic()))
    hung = [t for t in threads if t.is_alive()]
    assert not hung, f"{len(hung)} thread(s) still running after {TIMEOUT} s: deadlock"
    assert not errors, errors


def test_two_threads_stepping_one_cloth_serialise() -> None:
    steps = 20
    cloth = _cloth()
    _run([lambda: [cloth.step(DT) for _ in range(steps)]] * 2)
    assert cloth.step_count == 2 * steps
    assert np.isfinite(np.asarray(cloth.positions)).all()
    # serialised: the same state as 40 steps on one thread (the solver is deterministic)
    alone = _cloth()
    for _ in range(2 * steps):
        alone.step(DT)
    np.testing.assert_array_equal(np.asarray(cloth.positions), np.asarray(alone.positions))


def test_changing_threads_while_stepping() -> None:
    cloth = _cloth(tethers=True)
    stop = threading.Event()

    def stepper() -> None:
        for _ in range(30):
            cloth.step(DT)
        stop.set()

    def tuner() -> None:
        k = 0
        while not stop.is_set():
            cloth.threads = 1 + k % 3
            cloth.iterations = 1 + k % 2
            k += 1

    _run([stepper, tuner])
    assert cloth.step_count == 30
    assert np.isfinite(np.asarray(cloth.positions)).all()


def test_readers_and_editors_while_stepping() -> None:
    """stats, mesh, advance, grab and wind from other threads while one steps."""
    n = 96
    cloth = _cloth(n, self_collision=True)
    stop = threading.Event()

    def stepper() -> None:
        for _ in range(15):
            cloth.step(DT)
        stop.set()

    def reader() -> None:
        while not stop.is_set():
            s = cloth.stats()
            assert np.isfinite(s["mean_strain"])
            assert len(cloth.mesh()["indices"]) > 0

    def editor() -> None:
        k = 0
        while not stop.is_set():
            cloth.wind = weft.Wind((0, 0, 1), float(k % 5))
            cloth.advance(1.0 / 60.0)
            cloth.grab([n * n - 1], [(0.5, 0.5 + 0.01 * (k % 3), 0.0)])
            cloth.release()
            k += 1

    _run([stepper, reader, editor])
    assert np.isfinite(np.asarray(cloth.positions)).all()


def test_separate_cloths_step_in_parallel() -> None:
    """Different cloths do not share a lock or a pool: both finish, each as if alone."""
    a, b = _cloth(64), _cloth(64)
    _run([lambda: [a.step(DT) for _ in range(20)], lambda: [b.step(DT) for _ in range(20)]])
    np.testing.assert_array_equal(np.asarray(a.positions), np.asarray(b.positions))
