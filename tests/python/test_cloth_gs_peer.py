"""The benchmark's natural-order Gauss-Seidel peer (issue 17 item 8).

The peer is a plain serial loop written apart from weft's solver, so the only thing that may
differ from weft is the order of the projections: given weft's own (colour-batched) order it
must reproduce weft's positions exactly; in natural order it is another solver, checked
against the converged truth of a chain."""

from __future__ import annotations

import numpy as np
import pytest

from weft.bench.cloth import Setting, WeftEngine
import weft.bench.cloth_peer_gs as gs


@pytest.mark.parametrize("setting", [Setting("sub2", 1, 2), Setting("tethers-it2", 2, 1, tethers=True),
                                     Setting("xpbd", 2, 2, (0.0, 1e-2, 1.0))])
def test_peer_in_weft_order_reproduces_weft(setting: Setting) -> None:
    peer = gs.NaturalGsCloth(16, setting, order="weft")
    cloth = WeftEngine(threads=1).make(16, setting)
    for _ in range(30):
        peer.step(1 / 60)
        cloth.step(1 / 60)
    np.testing.assert_allclose(peer.positions, np.asarray(cloth.positions), atol=2e-6)


def test_peer_orders_constraints_naturally() -> None:
    peer = gs.NaturalGsEngine().make(8, Setting("seed"))
    key = peer.a * 64 + peer.b
    assert np.all(np.diff(key) > 0) and np.all(peer.a < peer.b)


def test_peer_rejects_an_order_that_is_not_a_permutation() -> None:
    with pytest.raises(ValueError):
        gs.NaturalGsCloth(4, Setting("seed"), order=[0, 0, 1])
    with pytest.raises(ValueError):
        gs.NaturalGsCloth(4, Setting("seed"), order="backwards")
