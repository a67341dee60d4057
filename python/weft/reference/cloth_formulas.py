"""Literal formulas the cloth tests compare against (SPEC §2): one distance-constraint
projection (eq. 3.3/3.4), free fall and the pendulum period. Re-exported by
:mod:`weft.reference.cloth`."""

from __future__ import annotations

import math
from typing import Sequence, Tuple, Union

import numpy as np

from weft.reference.cloth_colliders import _EPS

ArrayLike = Union[np.ndarray, Sequence[float], float]


def project_distance(xa: ArrayLike, xb: ArrayLike, wa: float, wb: float,
                     rest: float) -> Tuple[np.ndarray, np.ndarray]:
    """One distance-constraint projection, eq. 3.3/3.4 of the seed (SPEC §2.1), literally::

        d   = (|x_b - x_a| - l) (x_b - x_a) / |x_b - x_a|
        x_a += w_a / (w_a + w_b) d
        x_b -= w_b / (w_a + w_b) d

    ``w`` are inverse masses (0 pins). Returns the new ``(x_a, x_b)``; unchanged when both are
    pinned or the points coincide (the direction is undefined).
    """
    a = np.asarray(xa, dtype=np.float64)
    b = np.asarray(xb, dtype=np.float64)
    delta = b - a
    length = float(np.linalg.norm(delta))
    if wa + wb <= 0.0 or length <= _EPS:
        return a.copy(), b.copy()
    d = (length - rest) * delta / length
    return a + wa / (wa + wb) * d, b - wb / (wa + wb) * d


def free_fall(x0: ArrayLike, v0: ArrayLike, gravity: ArrayLike, t: float) -> np.ndarray:
    """Free fall ``x0 + v0 t + g t^2 / 2`` (Position Verlet is exact for it, SPEC §2.3)."""
    return (np.asarray(x0, dtype=np.float64) + np.asarray(v0, dtype=np.float64) * t
            + 0.5 * np.asarray(gravity, dtype=np.float64) * t * t)


def pendulum_period(length: float, g: float = 9.81, amplitude: float = 0.0) -> float:
    """Period of a simple pendulum, ``2 pi sqrt(L/g)`` for small angles; with ``amplitude``
    (radians) the series ``1 + theta^2/16 + 11 theta^4/3072`` corrects for finite swing."""
    t0 = 2.0 * math.pi * math.sqrt(length / g)
    th2 = amplitude * amplitude
    return t0 * (1.0 + th2 / 16.0 + 11.0 * th2 * th2 / 3072.0)
