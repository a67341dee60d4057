"""NumPy reference of weft's position-based cloth (SPEC §2, seed chapter 3), in float64.

:class:`ClothReference` is an independent, plainly vectorised implementation of the algorithm
``weft.Cloth`` runs in C++: the same grid, the same 12(+4)-neighbour constraint pattern sorted
into the same conflict-free batches (graph colouring of the grid), Position Verlet with damping
(eq. 3.12), gravity and wind (eq. 3.5, normals eq. 3.6), distance constraints (eq. 3.3/3.4) with
XPBD compliance per family, long-range tethers, collisions by projection (sphere eq. 3.7, plane,
box, capsule, height field), grabbing, holes, tearing and sleeping. Within a batch no two
constraints share a particle, so one batch is projected at once with fancy indexing and the
result equals a sequential Gauss-Seidel sweep over the batches. It is what a user without weft
would write; tests use it as the oracle and ``python -m weft.bench cloth`` as a peer.

The module also has the literal formulas the tests compare against: :func:`project_distance`
(eq. 3.3/3.4), signed distances of the collider shapes, free fall and the pendulum period.
The formulas live in :mod:`weft.reference.cloth_formulas`, the collider shapes in
:mod:`weft.reference.cloth_colliders`, the grid (positions, constraint pattern, normals,
triangles, strain) in :mod:`weft.reference.cloth_grid` -- all re-exported here -- what a user
does between steps (pins, grabs, holes, wind, colliders) in
:mod:`weft.reference.cloth_interaction` and self-collision in :mod:`weft.reference.cloth_self`.
Nothing here calls weft's compiled code.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

ArrayLike = Union[np.ndarray, Sequence[float], float]

__all__ = [
    "ClothReference",
    "SphereShape",
    "PlaneShape",
    "BoxShape",
    "CapsuleShape",
    "HeightFieldShape",
    "WindSetting",
    "project_distance",
    "constraint_pattern",
    "grid_positions",
    "grid_normals",
    "grid_triangles",
    "strain",
    "sphere_distance",
    "plane_distance",
    "box_distance",
    "capsule_distance",
    "height_field_distance",
    "hole_mask_from_image",
    "free_fall",
    "pendulum_period",
]

from weft.reference.cloth_colliders import (  # noqa: E402  (re-exported: the cloth's API)
    _EPS,
    BoxShape,
    CapsuleShape,
    HeightFieldShape,
    PlaneShape,
    SphereShape,
    WindSetting,
    _normalize,
    _points,
    _vec,
    box_distance,
    capsule_distance,
    height_field_distance,
    plane_distance,
    sphere_distance,
)
from weft.reference.cloth_formulas import (  # noqa: E402  (re-exported: the cloth's API)
    free_fall,
    pendulum_period,
    project_distance,
)
from weft.reference.cloth_grid import (  # noqa: E402, F401  (re-exported: the cloth's API)
    BEND,
    SHEAR,
    STRETCH,
    constraint_pattern,
    constraints_on_surface,
    grid_normals,
    grid_positions,
    grid_triangles,
    hole_mask_from_image,
    strain,
)
from weft.reference.cloth_interaction import ClothInteraction  # noqa: E402
from weft.reference.cloth_self import (  # noqa: E402
    GROUND_SLACK,
    SELF_COLLISION_PASSES,
    self_collide_pass,
)

# --------------------------------------------------------------------------------------------
# The solver
# --------------------------------------------------------------------------------------------

@dataclass
class _Batch:
    family: int
    a: np.ndarray
    b: np.ndarray
    index: np.ndarray  # constraint ids


_SolveBatch = Tuple[int, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]


class ClothReference(ClothInteraction):
    """The cloth solver of SPEC §2 in NumPy (float64), step for step what ``weft.Cloth`` does.

    Keyword arguments are those of ``weft.Cloth`` (``threads`` is accepted and ignored).
    Particles are indexed ``p = j * nx + i``. Per step of ``dt`` (``h = dt / substeps``,
    ``d = damping ** (60 h)``), each substep:

    1. normals (eq. 3.6 on the grid, :func:`grid_normals`; needed for wind only, and
       recomputed after every step);
    2. ``a = gravity + s (n . r) n`` (eq. 3.5, r the normalised wind direction);
    3. Position Verlet (eq. 3.12) ``x' = x + d (x - x_prev) + a h^2`` for free particles;
       pinned ones stay, grabbed ones jump to their targets (``x_prev = x``);
    4. ``iterations`` sweeps over the batches of XPBD distance constraints (multipliers from
       0 each substep, ``alpha~ = compliance / h^2``; compliance 0 is eq. 3.3/3.4), then
       tethers, then collisions (push to ``thickness`` along the normal, friction removes
       part of the tangential motion);
    5. self-collision (when enabled).

    After the step: tearing (strain > ``tear_strain`` breaks a constraint) and sleeping.

    Tethers tie each free particle to its :attr:`TETHER_ANCHORS` nearest anchors (a single
    anchor over-stretches the seam where the nearest anchor changes).
    """

    #: Anchors per particle for long-range tethers.
    TETHER_ANCHORS = 4

    def __init__(self, nx: int = 32, ny: int = 32, size: ArrayLike = (1.0, 1.0),
                 origin: ArrayLike = (-0.5, 1.0, -0.5), axis_u: ArrayLike = (1.0, 0.0, 0.0),
                 axis_v: ArrayLike = (0.0, 0.0, 1.0), mass: float = 1.0, bend_distance: int = 2,
                 extra_axial: bool = False, damping: float = 0.99,
                 gravity: ArrayLike = (0.0, -9.81, 0.0), iterations: int = 1, substeps: int = 1,
                 compliance_stretch: float = 0.0, compliance_shear: float = 0.0,
                 compliance_bend: float = 0.0, tethers: bool = False, thickness: float = 0.005,
                 self_collision: bool = False, self_thickness: float = 0.0,
                 tear_strain: float = 0.0, sleep_threshold: float = 0.0, sleep_steps: int = 30,
                 threads: int = 0) -> None:
        nx, ny = int(nx), int(ny)
        if nx < 1 or ny < 1 or nx * ny < 2:
            raise ValueError(f"cloth grid needs nx, ny >= 1 and nx*ny >= 2, got {nx}x{ny}")
        sz = _vec(size, 2, "size")
        if np.any(sz <= 0.0):
            raise ValueError(f"size must be positive, got {sz}")
        if not (math.isfinite(mass) and mass > 0.0):
            raise ValueError(f"mass must be positive, got {mass}")
        if int(bend_distance) < 2:
            raise ValueError("bend_distance must be >= 2")
        self.nx, self.ny = nx, ny
        self.n = nx * ny
        self.size = sz
        self.mass = float(mass)
        self.bend_distance = int(bend_distance)
        self.extra_axial = bool(extra_axial)
        self.damping = float(damping)
        self.gravity = _vec(gravity, 3, "gravity")
        self.iterations = int(iterations)
        self.substeps = int(substeps)
        self.compliance_stretch = float(compliance_stretch)
        self.compliance_shear = float(compliance_shear)
        self.compliance_bend = float(compliance_bend)
        self.tethers = bool(tethers)
        self.thickness = float(thickness)
        self.self_collision = bool(self_collision)
        self.self_thickness = float(self_thickness)
        self.tear_strain = float(tear_strain)
        self.sleep_threshold = float(sleep_threshold)
        self.sleep_steps = int(sleep_steps)
        self.threads = int(threads)

        self.rest_positions = grid_positions(nx, ny, sz, origin, axis_u, axis_v)
        self.x = self.rest_positions.copy()
        self.x_prev = self.x.copy()
        self.base_inverse_mass = np.full(self.n, self.n / self.mass)
        self.pinned = np.zeros(self.n, dtype=bool)
        self.hole = np.zeros(self.n, dtype=bool)
        self.grabbed = np.zeros(0, dtype=np.int64)
        self.grab_targets = np.zeros((0, 3))
        self.wind = WindSetting()
        self.colliders: List[Any] = []
        self.normals = grid_normals(self.x, nx, ny)
        self.step_count = 0
        self.sleeping = False
        self._quiet_steps = 0
        self._accumulator = 0.0
        self._pending_velocity: Optional[np.ndarray] = None
        self._last_h = 1.0 / 60.0

        pattern = constraint_pattern(nx, ny, self.bend_distance, self.extra_axial)
        self.batches: List[_Batch] = []
        a_all, b_all, fam_all = [], [], []
        start = 0
        for fam, a, b in pattern:
            self.batches.append(_Batch(fam, a, b, np.arange(start, start + len(a))))
            start += len(a)
            a_all.append(a)
            b_all.append(b)
            fam_all.append(np.full(len(a), fam, dtype=np.uint8))
        self.a = np.concatenate(a_all) if a_all else np.zeros(0, dtype=np.int64)
        self.b = np.concatenate(b_all) if b_all else np.zeros(0, dtype=np.int64)
        self.family = np.concatenate(fam_all) if fam_all else np.zeros(0, dtype=np.uint8)
        self.rest = np.linalg.norm(self.rest_positions[self.b] - self.rest_positions[self.a],
                                   axis=1)
        self.active = np.ones(len(self.a), dtype=bool)
        self._solve_cache: Optional[List[_SolveBatch]] = None
        self._tether_cache: Optional[List[Tuple[np.ndarray, np.ndarray, np.ndarray]]] = None

    # ---- state -------------------------------------------------------------------------------

    @property
    def particle_count(self) -> int:
        return self.n

    @property
    def constraint_count(self) -> int:
        return len(self.a)

    @property
    def positions(self) -> np.ndarray:
        """(N, 3) positions (a view; do not write)."""
        return self.x

    @property
    def inverse_masses(self) -> np.ndarray:
        """(N,) inverse masses: 0 for pinned, grabbed and hole particles."""
        w = np.where(self.pinned | self.hole, 0.0, self.base_inverse_mass)
        w[self.grabbed] = 0.0
        return w

    @property
    def holes(self) -> np.ndarray:
        return self.hole.reshape(self.ny, self.nx).copy()

    def _changed(self) -> None:
        self._solve_cache = None
        self._tether_cache = None

    def wake(self) -> None:
        """Ends sleeping (the next step runs)."""
        self.sleeping = False
        self._quiet_steps = 0

    def set_positions(self, positions: ArrayLike, keep_velocity: bool = False) -> None:
        """Moves every particle; without ``keep_velocity`` the velocity becomes 0."""
        p = _points(positions, "positions")
        if p.shape != (self.n, 3) or not np.all(np.isfinite(p)):
            raise ValueError(f"positions must be finite ({self.n}, 3), got {p.shape}")
        vel = self.x - self.x_prev
        self.x = p.copy()
        self.x_prev = p - vel if keep_velocity else p.copy()
        self._pending_velocity = None
        self.wake()

    def set_velocities(self, velocities: ArrayLike) -> None:
        """Velocities for the next step: it first sets ``x_prev = x - v h + g h^2 / 2`` (with
        its substep h), which makes free fall exact (SPEC §2.3)."""
        v = _points(velocities, "velocities")
        if v.shape != (self.n, 3) or not np.all(np.isfinite(v)):
            raise ValueError(f"velocities must be finite ({self.n}, 3), got {v.shape}")
        self._pending_velocity = v.copy()
        self.wake()

    def velocities(self) -> np.ndarray:
        """(x - x_prev) / h of the last substep (or the pending set velocities)."""
        if self._pending_velocity is not None:
            return self._pending_velocity.copy()
        return (self.x - self.x_prev) / self._last_h

    def reset(self) -> None:
        """Back to the rest state: torn constraints mend, grabs are released (pins, holes,
        wind and colliders stay)."""
        self.x = self.rest_positions.copy()
        self.x_prev = self.x.copy()
        self._pending_velocity = None
        self.active = ~(self.hole[self.a] | self.hole[self.b])
        self.grabbed = np.zeros(0, dtype=np.int64)
        self.grab_targets = np.zeros((0, 3))
        self._accumulator = 0.0
        self._changed()
        self.wake()

    # ---- solver ------------------------------------------------------------------------------

    def _compliance(self, family: int) -> float:
        return (self.compliance_stretch, self.compliance_shear, self.compliance_bend)[family]

    def _solve_batches(self) -> List[_SolveBatch]:
        """Per batch: (family, a, b, rest, w_a, w_b) of the active constraints with
        ``w_a + w_b > 0`` (cached until pins, grabs, holes or tears change)."""
        if self._solve_cache is None:
            w = self.inverse_masses
            out = []
            for batch in self.batches:
                sel = self.active[batch.index] & (w[batch.a] + w[batch.b] > 0.0)
                if np.any(sel):
                    a, b = batch.a[sel], batch.b[sel]
                    out.append((batch.family, a, b, self.rest[batch.index[sel]], w[a], w[b]))
            self._solve_cache = out
        return self._solve_cache

    def _tether_data(self) -> List[Tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """Tethers as rounds ``[(particles, anchors, lengths), ...]``: round t ties every free
        particle to its (t+1)-th nearest anchor (pinned or grabbed particle, by rest distance,
        lower index first on ties; at most :attr:`TETHER_ANCHORS`) at that rest distance."""
        if self._tether_cache is None:
            w = self.inverse_masses
            anchors = np.flatnonzero(~self.hole & (w == 0.0))  # pinned or grabbed
            free = np.flatnonzero(w != 0.0)
            rounds: List[Tuple[np.ndarray, np.ndarray, np.ndarray]] = []
            if len(anchors) and len(free):
                dist = np.linalg.norm(self.rest_positions[free][:, None, :]
                                      - self.rest_positions[anchors][None, :, :], axis=2)
                keep = min(self.TETHER_ANCHORS, len(anchors))
                # stable sort by distance keeps the lower anchor index first on ties
                order = np.argsort(dist, axis=1, kind="stable")[:, :keep]
                for t in range(keep):
                    col = order[:, t]
                    rounds.append((free, anchors[col], dist[np.arange(len(free)), col]))
            self._tether_cache = rounds
        return self._tether_cache

    def _relax(self, h: float, lambdas: Optional[List[np.ndarray]]) -> None:
        """One sweep: constraint batches (XPBD), then tethers, then collisions."""
        x = self.x
        for k, (fam, a, b, rest, wa, wb) in enumerate(self._solve_batches()):
            delta = x[b] - x[a]
            length = np.sqrt(np.einsum("ij,ij->i", delta, delta))
            ok = length > _EPS
            n = delta / np.where(ok, length, 1.0)[:, None]
            c = length - rest
            alpha = self._compliance(fam) / (h * h)
            if lambdas is not None and alpha > 0.0:
                lam = lambdas[k]
                dlam = (-c - alpha * lam) / (wa + wb + alpha)
                lam += np.where(ok, dlam, 0.0)
            else:
                dlam = -c / (wa + wb + alpha)
            dlam = np.where(ok, dlam, 0.0)
            x[a] -= (wa * dlam)[:, None] * n
            x[b] += (wb * dlam)[:, None] * n
        if self.tethers:
            # anchors never move here, so doing round t for all particles before round t+1
            # equals walking each particle's tethers in order
            for p, q, length in self._tether_data():
                rel = x[p] - x[q]
                dist = np.linalg.norm(rel, axis=1)
                far = dist > length
                if np.any(far):
                    pf, qf = p[far], q[far]
                    x[pf] = x[qf] + length[far][:, None] * rel[far] / dist[far][:, None]
        self._collide(friction=True)

    def _collide(self, friction: bool) -> None:
        """Projects the free particles out of the colliders (to ``thickness``); friction only
        in the relaxation, not in the re-projection after self-collision."""
        if not self.colliders:
            return
        x = self.x
        free = np.flatnonzero(self.inverse_masses > 0.0)
        for shape in self.colliders:
            s, n = shape.distance(x[free])
            s, n = np.asarray(s, dtype=np.float64), np.asarray(n, dtype=np.float64)
            hit = s < self.thickness
            if not np.any(hit):
                continue
            idx, nh = free[hit], n[hit]
            x[idx] += (self.thickness - s[hit])[:, None] * nh
            f = float(getattr(shape, "friction", 0.0))
            if friction and f > 0.0:
                v = x[idx] - self.x_prev[idx]
                vt = v - np.einsum("ij,ij->i", v, nh)[:, None] * nh
                self.x_prev[idx] += f * vt

    def self_thickness_used(self) -> float:
        """T of self-collision: ``self_thickness``, or 0.9 x the smaller grid spacing."""
        if self.self_thickness > 0.0:
            return self.self_thickness
        su = self.size[0] / (self.nx - 1) if self.nx > 1 else self.size[1]
        sv = self.size[1] / (self.ny - 1) if self.ny > 1 else self.size[0]
        return 0.9 * min(su, sv)

    def _self_collide(self, start: np.ndarray, start_normals: np.ndarray) -> None:
        """Self-collision passes of :func:`weft.reference.cloth_self.self_collide_pass`, then
        the colliders again."""
        for _ in range(SELF_COLLISION_PASSES):
            grounded = np.zeros(self.nx * self.ny, dtype=bool)
            t = self.self_thickness_used()
            for shape in self.colliders:
                s, _ = shape.distance(self.x)
                grounded |= np.asarray(s, dtype=np.float64) < self.thickness + GROUND_SLACK * t
            self_collide_pass(self.x, start, start_normals, self.rest_positions,
                              self.inverse_masses, self.hole, grounded, t)
            self._collide(friction=False)

    def _substep(self, h: float, d: float) -> None:
        w = self.inverse_masses
        acc = np.broadcast_to(self.gravity, self.x.shape)
        if self.wind.strength != 0.0:  # normals are needed for wind only (else after the step)
            self.normals = grid_normals(self.x, self.nx, self.ny, self.normals)
            r = _normalize(np.asarray(self.wind.direction, dtype=np.float64))
            nr = self.normals @ r
            acc = acc + float(self.wind.strength) * nr[:, None] * self.normals
        if self._pending_velocity is not None:
            self.x_prev = self.x - self._pending_velocity * h + 0.5 * self.gravity * h * h
            self._pending_velocity = None
        if self.self_collision:  # the start of the substep: which side of each layer
            start = self.x.copy()
            start_normals = grid_normals(start, self.nx, self.ny)
        free = w > 0.0
        x_new = np.where(free[:, None], self.x + d * (self.x - self.x_prev) + acc * h * h, self.x)
        still = free | (self.pinned & ~self.hole)  # pinned particles have no velocity
        self.x_prev = np.where(still[:, None], self.x, self.x_prev)
        self.x = x_new
        if len(self.grabbed):
            self.x_prev[self.grabbed] = self.x[self.grabbed]
            self.x[self.grabbed] = self.grab_targets
        lambdas = [np.zeros(len(entry[1])) for entry in self._solve_batches()]
        for _ in range(self.iterations):
            self._relax(h, lambdas)
        if self.self_collision:
            self._self_collide(start, start_normals)

    def step(self, dt: float = 1.0 / 60.0) -> None:
        """One step of ``dt`` seconds split into ``substeps`` (SPEC §2.3, seed alg. 3.1)."""
        if not (math.isfinite(dt) and 0.0 < dt <= 1.0):
            raise ValueError(f"dt must be in (0, 1] seconds, got {dt}")
        if self.sleeping:
            return
        h = dt / self.substeps
        d = self.damping ** (h * 60.0)
        for _ in range(self.substeps):
            self._substep(h, d)
        self._last_h = h
        self.normals = grid_normals(self.x, self.nx, self.ny, self.normals)
        self.step_count += 1
        self._after_step(h)

    def _after_step(self, h: float) -> None:
        if self.tear_strain > 0.0 and np.any(self.active):
            idx = np.flatnonzero(self.active)
            length = np.linalg.norm(self.x[self.b[idx]] - self.x[self.a[idx]], axis=1)
            broken = np.abs(length - self.rest[idx]) / self.rest[idx] > self.tear_strain
            if np.any(broken):
                self.active[idx[broken]] = False
                self._changed()
        if self.sleep_threshold > 0.0:
            free = self.inverse_masses > 0.0
            speed = (float(np.mean(np.linalg.norm(self.x[free] - self.x_prev[free], axis=1)))
                     / h if np.any(free) else 0.0)
            self._quiet_steps = self._quiet_steps + 1 if speed < self.sleep_threshold else 0
            if self._quiet_steps >= self.sleep_steps:
                self.sleeping = True

    def advance(self, real_dt: float, rate: float = 60.0, max_steps: int = 8) -> int:
        """Fixed-rate stepping (SPEC §2.4): runs ``floor(acc * rate)`` steps of ``1/rate``, at
        most ``max_steps`` (then the leftover time is dropped); returns how many ran."""
        self._accumulator += real_dt
        n = int(math.floor(self._accumulator * rate))
        if n > max_steps:
            n = max_steps
            self._accumulator = 0.0
        else:
            self._accumulator -= n / rate
        for _ in range(n):
            self.step(1.0 / rate)
        return n

    def project_constraints(self) -> None:
        """One relaxation sweep (multipliers from 0, h = 1/60) + tethers + collisions, without
        integration; with compliance 0 exactly eq. 3.3/3.4 per constraint."""
        lambdas = [np.zeros(len(entry[1])) for entry in self._solve_batches()]
        self._relax(1.0 / 60.0, lambdas)

    # ---- outputs -----------------------------------------------------------------------------

    def stats(self) -> Dict[str, Any]:
        mean, mx = strain(self.x, self.a, self.b, self.rest, self.active)
        return {"mean_strain": mean, "max_strain": mx, "active_constraints": int(self.active.sum())}

    def constraints(self) -> Dict[str, np.ndarray]:
        return {"a": self.a.astype(np.int32), "b": self.b.astype(np.int32),
                "rest": self.rest.copy(), "family": self.family.copy(),
                "active": self.active.copy()}

    def kinetic_energy(self) -> float:
        """Sum of m v^2 / 2 over the cloth (not holes), v = (x - x_prev)/h of the last
        substep, m = mass / N."""
        solid = ~self.hole
        v = (self.x[solid] - self.x_prev[solid]) / self._last_h
        return float(0.5 * self.mass / self.n * np.sum(v * v))

    def edge_active(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Whether the grid edges (a, b) are active constraints."""
        key = np.minimum(self.a, self.b) * self.n + np.maximum(self.a, self.b)
        order = np.argsort(key)
        q = np.minimum(a, b).astype(np.int64) * self.n + np.maximum(a, b)
        pos = np.clip(np.searchsorted(key[order], q), 0, len(order) - 1)
        found = key[order][pos] == q
        return found & self.active[order][pos]

    def triangles(self) -> np.ndarray:
        """Mesh triangle indices (M, 3) uint32 (holes and torn edges left out)."""
        return grid_triangles(self.nx, self.ny, self.edge_active, self.hole)

    def mesh(self) -> Dict[str, np.ndarray]:
        """positions, normals, uvs and triangle indices (no tangents)."""
        jj, ii = np.meshgrid(np.arange(self.ny), np.arange(self.nx), indexing="ij")
        uv = np.stack([ii.reshape(-1) / max(self.nx - 1, 1), jj.reshape(-1) / max(self.ny - 1, 1)],
                      axis=1)
        return {"positions": self.x.copy(), "normals": self.normals.copy(), "uvs": uv,
                "indices": self.triangles()}
