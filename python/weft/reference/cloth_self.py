"""Self-collision of the NumPy cloth (brute force over all pairs; the algorithm of weft's
``ClothSelfCollision.cpp``, for small cloths and tests).

A pair (p, q) of solid particles farther apart than T at rest interacts in two ways, judged
from the positions at the start of the substep (``start``, with their grid normals) and now:

- **crossed**: their rest distance exceeds ``LAYER_REST`` T (they cannot be neighbours in one
  smooth sheet), p was strictly on one side of q's start tangent plane and is now on the other
  (or in it), and the straight relative path met that plane within T of q (through the cloth
  around q). p goes back to its side, T from the plane: ``n_q s (T - s (x_p - x_q).n_q)``.
- otherwise, closer than T now: pushed apart along their separation to T.

Each correction is weighted ``w_p / (w_p + w_q)``, except that a particle resting on a collider
(``grounded``) gives way to none that is not (it takes 0, the other 1); a particle moves by the
mean of its corrections, all computed from the same positions (Jacobi).
"""

from __future__ import annotations

import numpy as np

#: Passes per substep (each resolves a deep contact among shallow ones only partly).
SELF_COLLISION_PASSES = 3
#: Rest distance (in T) below which two particles may lie in one smooth sheet.
LAYER_REST = 2.0
#: A particle closer to a collider than its thickness plus this fraction of T rests on it.
GROUND_SLACK = 0.01


def self_collide_pass(x: np.ndarray, start: np.ndarray, start_normals: np.ndarray,
                      rest: np.ndarray, w: np.ndarray, hole: np.ndarray, grounded: np.ndarray,
                      t: float) -> None:
    """One Jacobi pass over all pairs; moves ``x`` in place."""
    idx = np.flatnonzero(~np.asarray(hole, dtype=bool))
    if len(idx) < 2:
        return
    p_x, s_x, n_q, r_x = x[idx], start[idx], start_normals[idx], rest[idx]
    wp, g = w[idx], np.asarray(grounded, dtype=bool)[idx]
    r0 = s_x[:, None, :] - s_x[None, :, :]  # [p, q]
    r1 = p_x[:, None, :] - p_x[None, :, :]
    rest_d = np.linalg.norm(r_x[:, None, :] - r_x[None, :, :], axis=2)
    cand = (rest_d > t) & (wp[:, None] > 0.0)
    np.fill_diagonal(cand, False)
    share = wp[:, None] / np.where(cand, wp[:, None] + wp[None, :], 1.0)
    differ = g[:, None] != g[None, :]
    share = np.where(differ, np.where(g[:, None], 0.0, 1.0), share)
    side0 = np.einsum("pqk,qk->pq", r0, n_q)
    side1 = np.einsum("pqk,qk->pq", r1, n_q)
    crossing = (cand & (rest_d > LAYER_REST * t) & (side0 != 0.0)
                & ((side0 > 0.0) != (side1 > 0.0)))
    tc = np.where(crossing, side0 / np.where(crossing, side0 - side1, 1.0), 0.0)
    at = r0 + tc[:, :, None] * (r1 - r0)
    crossed = crossing & (np.einsum("pqk,pqk->pq", at, at) < t * t)
    sign = np.sign(side0)
    cross_corr = (sign * (t - sign * side1) * share)[:, :, None] * n_q[None, :, :]
    len2 = np.einsum("pqk,pqk->pq", r1, r1)
    radial = cand & ~crossed & (len2 < t * t) & (len2 >= 1e-24)
    length = np.sqrt(np.where(radial, len2, 1.0))
    radial_corr = ((t - length) / length * share)[:, :, None] * r1
    total = (np.where(crossed[:, :, None], cross_corr, 0.0)
             + np.where(radial[:, :, None], radial_corr, 0.0)).sum(axis=1)
    count = (crossed | radial).sum(axis=1)
    x[idx] += total / np.maximum(count, 1)[:, None]
