"""The natural-order Gauss-Seidel peer of the cloth benchmark (issue 17 item 8).

Plain serial position-based dynamics: every distance constraint of the 12-neighbour pattern
projected one after the other in natural order (by the lower particle index, then the
higher), then the tethers, per sweep: what a straightforward implementation does, and the
most accurate sweep order for this scene (the pinned top row is row 0, so one sweep carries
the pins' correction down the whole cloth). Its loop is C++ (``weft._core._NaturalGsPeer``,
scalar float32, one thread, written apart from weft's solver): Numba was not installed, and a
constraint-by-constraint loop in NumPy is ~1000x slower. The constraint list, rest lengths
and pins come from a ``weft.Cloth`` of the same scene; tethers (one per free particle and
pinned anchor, at the rest distance) are built here.
"""

from __future__ import annotations

from typing import Any, Dict, Tuple

import numpy as np

from weft.bench.cloth import Engine, Setting, WeftEngine


class NaturalGsCloth:
    """A stepping cloth with the interface the benchmark's engines use."""

    def __init__(self, n: int, setting: Setting, order: Any = "natural") -> None:
        """``order``: "natural", "weft" (weft's colour-batched order, which the peer then
        reproduces), or a permutation of weft's constraint list (to measure other orders)."""
        from weft import _core

        template = WeftEngine(threads=1).make(n, setting)
        c = template.constraints()
        a, b = c["a"].astype(np.int64), c["b"].astype(np.int64)
        lo, hi = np.minimum(a, b), np.maximum(a, b)
        if isinstance(order, str):
            if order not in ("natural", "weft"):
                raise ValueError(f"order must be 'natural', 'weft' or a permutation, got {order!r}")
            # natural order: by the lower index, then the higher
            order = np.lexsort((hi, lo)) if order == "natural" else np.arange(len(a))
        order = np.asarray(order, dtype=np.int64)
        if sorted(order.tolist()) != list(range(len(a))):
            raise ValueError("order must be a permutation of the constraint list")
        self.a, self.b = lo[order], hi[order]
        self.rest = np.asarray(c["rest"], dtype=np.float64)[order]
        compliance = np.asarray(setting.compliance, dtype=np.float64)[c["family"][order]]
        x0 = np.asarray(template.positions, dtype=np.float64)
        w = np.asarray(template.inverse_masses, dtype=np.float32).copy()
        tp = np.zeros(0, np.int64)
        ta = np.zeros(0, np.int64)
        tl = np.zeros(0, np.float64)
        if setting.tethers:
            anchors = np.flatnonzero(w == 0.0)
            free = np.flatnonzero(w != 0.0)
            dist = np.linalg.norm(x0[free][:, None, :] - x0[anchors][None, :, :], axis=2)
            near = np.argsort(dist, axis=1, kind="stable")  # nearest anchor first
            tp = np.repeat(free, len(anchors))
            ta = anchors[near].ravel()
            tl = np.take_along_axis(dist, near, axis=1).ravel()
        self.mass = 1.0 / len(x0)
        self.peer = _core._NaturalGsPeer(
            x0, w, self.a, self.b, self.rest, compliance, tp, ta, tl,
            tuple(template.gravity), float(template.damping), setting.iterations,
            setting.substeps)

    def step(self, dt: float) -> None:
        self.peer.step(dt)

    @property
    def positions(self) -> np.ndarray:
        return np.asarray(self.peer.positions)

    def stats(self) -> Dict[str, float]:
        x = np.asarray(self.peer.positions, dtype=np.float64)
        s = np.abs(np.linalg.norm(x[self.b] - x[self.a], axis=1) - self.rest) / self.rest
        return {"mean_strain": float(s.mean()), "max_strain": float(s.max())}

    def kinetic_energy(self) -> float:
        return float(self.peer.kinetic_energy(self.mass))


class NaturalGsEngine(Engine):
    name = "gs-natural"

    def make(self, n: int, setting: Setting) -> Any:
        return NaturalGsCloth(n, setting)


def strain_of(engine: Engine, n: int, setting: Setting, steps: int) -> Tuple[float, float]:
    cloth = engine.make(n, setting)
    for _ in range(steps):
        cloth.step(1.0 / 60.0)
    s = cloth.stats()
    return s["mean_strain"], s["max_strain"]
