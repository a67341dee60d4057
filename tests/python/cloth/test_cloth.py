"""weft.Cloth against independent references (SPEC §2, seed chapter 3).

Each test compares the C++ solver with a formula computed here in NumPy (eq. 3.3/3.4, free
fall, the pendulum period, eq. 3.5, 3.7, collider distances, the XPBD static sag) or with
``weft.reference.cloth.ClothReference``, the same algorithm in float64 NumPy. weft works in
float32, so tolerances are float32 rounding unless a test says otherwise.
"""

from __future__ import annotations

import math
from typing import Any, Dict

import numpy as np
import pytest
import weft
from weft.reference import cloth as ref

DT = 1.0 / 60.0
G = 9.81


def hanging(n: int = 8, m: int = 0, **settings: Any) -> "weft.Cloth":
    """The standard scene: a 1 m cloth hanging in the XY plane from its two top corners."""
    m = m or n
    kw: Dict[str, Any] = dict(nx=n, ny=m, origin=(-0.5, 1.5, 0.0), axis_u=(1, 0, 0),
                              axis_v=(0, -1, 0))
    kw.update(settings)
    cloth = weft.Cloth(**kw)
    cloth.pin([0, n - 1])
    return cloth


def positions64(cloth: Any) -> np.ndarray:
    return np.asarray(cloth.positions, dtype=np.float64)


def triangle_set(indices: np.ndarray) -> set:
    """Triangles as a set of sorted index triples (order and winding ignored)."""
    return {tuple(sorted(t)) for t in np.asarray(indices).tolist()}


# --------------------------------------------------------------------------------------------
# Construction, views, properties
# --------------------------------------------------------------------------------------------

def test_grid_views_and_constraint_pattern() -> None:
    nx, ny = 7, 5
    cloth = weft.Cloth(nx=nx, ny=ny, size=(1.2, 0.8), origin=(0.1, 2.0, -0.3),
                       axis_u=(0, 0, 2), axis_v=(1, 0, 0), mass=2.0, extra_axial=True,
                       bend_distance=2, threads=1)
    assert (cloth.nx, cloth.ny, cloth.particle_count) == (nx, ny, nx * ny)
    p = cloth.positions
    assert p.shape == (nx * ny, 3) and p.dtype == np.float32
    assert p.strides == (16, 4)  # a view of the x, y, z, w records
    assert not p.flags.writeable
    with pytest.raises(ValueError):
        p[0, 0] = 1.0
    expect = ref.grid_positions(nx, ny, (1.2, 0.8), (0.1, 2.0, -0.3), (0, 0, 2), (1, 0, 0))
    np.testing.assert_allclose(p, expect, atol=2e-6)
    w = cloth.inverse_masses
    assert w.shape == (nx * ny,) and not w.flags.writeable
    np.testing.assert_allclose(w, nx * ny / 2.0, rtol=1e-6)

    # constraints: same pairs, families and batch order as the reference pattern
    c = cloth.constraints()
    pattern = ref.constraint_pattern(nx, ny, 2, True)
    a = np.concatenate([pa for _, pa, _ in pattern])
    b = np.concatenate([pb for _, _, pb in pattern])
    fam = np.concatenate([np.full(len(pa), f) for f, pa, _ in pattern])
    assert cloth.constraint_count == len(a) == len(c["a"])
    np.testing.assert_array_equal(c["a"], a)
    np.testing.assert_array_equal(c["b"], b)
    np.testing.assert_array_equal(c["family"], fam)
    assert c["active"].all()
    np.testing.assert_allclose(c["rest"], np.linalg.norm(expect[b] - expect[a], axis=1), rtol=1e-6)
    # each batch is conflict-free: no particle twice
    for _, pa, pb in pattern:
        ends = np.concatenate([pa, pb])
        assert len(np.unique(ends)) == len(ends)
    # every undirected pair at most once, 12 + 4 neighbours in the interior
    pairs = set(zip(np.minimum(a, b).tolist(), np.maximum(a, b).tolist()))
    assert len(pairs) == len(a)
    interior = 2 * nx + 2  # particle (2, 2)
    assert sum(1 for x, y in pairs if interior in (x, y)) == 16

    # zero-copy: the same view sees the next step
    cloth.step(DT)
    assert not np.array_equal(p, expect.astype(np.float32))
    np.testing.assert_array_equal(p, cloth.positions)


def test_settings_are_properties() -> None:
    cloth = weft.Cloth(nx=4, ny=4)
    values = dict(damping=0.95, iterations=3, substeps=2, compliance_stretch=1e-6,
                  compliance_shear=2e-6, compliance_bend=3e-4, tethers=True, thickness=0.01,
                  self_collision=True, self_thickness=0.02, tear_strain=0.5,
                  sleep_threshold=0.001, sleep_steps=12, threads=2)
    for name, value in values.items():
        setattr(cloth, name, value)
        got = getattr(cloth, name)
        assert got == pytest.approx(value, rel=1e-6), name
    cloth.gravity = (0.0, -1.0, 0.5)
    assert tuple(cloth.gravity) == pytest.approx((0.0, -1.0, 0.5))
    for name in ("nx", "ny", "particle_count", "constraint_count", "step_count", "sleeping"):
        with pytest.raises(AttributeError):
            setattr(cloth, name, 1)
    cloth.step(DT)
    assert cloth.step_count == 1


# --------------------------------------------------------------------------------------------
# The seed's equations
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("pinned", [None, 0, 1])
def test_one_projection_is_eq_3_3_3_4(pinned: Any) -> None:
    cloth = weft.Cloth(nx=2, ny=1, size=(1.0, 1.0), origin=(0, 0, 0), gravity=(0, 0, 0))
    assert cloth.constraint_count == 1
    if pinned is not None:
        cloth.pin([pinned])
    xa, xb = np.array([0.1, 0.2, 0.3]), np.array([1.3, -0.4, 0.5])
    cloth.set_positions(np.stack([xa, xb]))
    w = np.asarray(cloth.inverse_masses, dtype=np.float64)
    cloth.project_constraints()
    ea, eb = ref.project_distance(xa, xb, w[0], w[1], 1.0)
    got = positions64(cloth)
    np.testing.assert_allclose(got[0], ea, atol=1e-6)
    np.testing.assert_allclose(got[1], eb, atol=1e-6)
    assert np.linalg.norm(got[1] - got[0]) == pytest.approx(1.0, abs=1e-6)
    # the reference solver takes the same step
    r = ref.ClothReference(nx=2, ny=1, size=(1.0, 1.0), origin=(0, 0, 0), gravity=(0, 0, 0))
    if pinned is not None:
        r.pin([pinned])
    r.set_positions(np.stack([xa, xb]))
    r.project_constraints()
    np.testing.assert_allclose(r.positions, np.stack([ea, eb]), atol=1e-12)


def test_one_xpbd_projection() -> None:
    """With compliance alpha: dlambda = -C / (w_a + w_b + alpha / h^2), h = 1/60."""
    alpha = 2e-3
    cloth = weft.Cloth(nx=2, ny=1, origin=(0, 0, 0), gravity=(0, 0, 0), compliance_stretch=alpha)
    xa, xb = np.array([0.0, 0.0, 0.0]), np.array([1.5, 0.0, 0.0])
    cloth.set_positions(np.stack([xa, xb]))
    w = float(cloth.inverse_masses[0])
    cloth.project_constraints()
    dlam = -0.5 / (2 * w + alpha * 3600.0)
    expect = np.stack([xa - w * dlam * np.array([1.0, 0, 0]),
                       xb + w * dlam * np.array([1.0, 0, 0])])
    np.testing.assert_allclose(positions64(cloth), expect, atol=1e-6)


def test_free_fall_is_exact() -> None:
    """Verlet is exact for constant acceleration (damping 1): x0 + v0 t + g t^2 / 2."""
    cloth = weft.Cloth(nx=3, ny=2, damping=1.0, substeps=3, origin=(-0.5, 1.0, -0.5))
    x0 = positions64(cloth)
    v0 = np.tile([0.7, 3.0, -0.4], (6, 1))
    cloth.set_velocities(v0)
    np.testing.assert_allclose(cloth.velocities(), v0, rtol=1e-6)
    g = np.array([0.0, -G, 0.0])
    cloth.step(DT)
    np.testing.assert_allclose(positions64(cloth), ref.free_fall(x0, v0, g, DT), atol=2e-6)
    for _ in range(299):
        cloth.step(DT)
    t = 300 * DT
    expect = ref.free_fall(x0, v0, g, t)
    scale = np.abs(expect - x0).max()  # ~ 100 m: float32 Verlet keeps ~1e-4 of it
    err = np.abs(positions64(cloth) - expect).max() / scale
    assert err < 5e-4, err
    vel = cloth.velocities()
    np.testing.assert_allclose(vel, v0 + g * t, atol=G * DT)
    # the float64 reference is exact
    r = ref.ClothReference(nx=3, ny=2, damping=1.0, substeps=3)
    r.set_velocities(v0)
    for _ in range(300):
        r.step(DT)
    np.testing.assert_allclose(r.positions, expect, rtol=1e-10, atol=1e-9)


def test_pendulum_period() -> None:
    """Two particles, the top one pinned: small-angle period 2 pi sqrt(L/g) within 1%."""
    theta = 0.05
    cloth = weft.Cloth(nx=1, ny=2, size=(1.0, 1.0), origin=(0, 0, 0), axis_u=(0, 0, 1),
                       axis_v=(math.sin(theta), -math.cos(theta), 0), damping=1.0)
    cloth.pin([0])
    dt = 1.0 / 600.0
    xs = np.empty(3000)
    for k in range(len(xs)):
        cloth.step(dt)
        xs[k] = cloth.positions[1, 0]
    t = (np.arange(len(xs)) + 1) * dt
    cross = np.flatnonzero(np.sign(xs[:-1]) != np.sign(xs[1:]))
    assert len(cross) >= 4
    tc = t[cross] - xs[cross] * dt / (xs[cross + 1] - xs[cross])
    period = 2.0 * float(np.mean(np.diff(tc)))
    expect = 2.0 * math.pi * math.sqrt(1.0 / G)
    assert abs(period / expect - 1.0) < 0.01, (period, expect)
    assert abs(period / ref.pendulum_period(1.0, G, theta) - 1.0) < 0.002
    # the rod keeps its length
    assert np.linalg.norm(cloth.positions[1] - cloth.positions[0]) == pytest.approx(1.0, abs=1e-5)


def test_tethers_bound_the_stretch() -> None:
    n = 16
    plain, tied = hanging(n), hanging(n, tethers=True)
    for _ in range(60):
        plain.step(DT)
        tied.step(DT)
    assert tied.stats()["max_strain"] < 0.5 * plain.stats()["max_strain"]
    # with one anchor, no particle ever ends farther from it than at rest
    single = weft.Cloth(nx=n, ny=n, origin=(-0.5, 1.5, 0.0), axis_v=(0, -1, 0), tethers=True)
    single.pin([0])
    rest = ref.grid_positions(n, n, (1, 1), (-0.5, 1.5, 0), (1, 0, 0), (0, -1, 0))
    limit = np.linalg.norm(rest - rest[0], axis=1)
    for _ in range(30):
        single.step(DT)
        x = positions64(single)
        assert np.all(np.linalg.norm(x - x[0], axis=1) <= limit * (1 + 1e-5) + 1e-6)


# --------------------------------------------------------------------------------------------
# XPBD: stiffness independent of the iteration count
# --------------------------------------------------------------------------------------------

def _column_sag(iterations: int, substeps: int, compliance: float, steps: int = 600) -> float:
    nx, ny = 4, 10
    cloth = weft.Cloth(nx=nx, ny=ny, origin=(-0.5, 1.5, 0.0), axis_v=(0, -1, 0),
                       iterations=iterations, substeps=substeps,
                       compliance_stretch=compliance, compliance_shear=1e6, compliance_bend=1e6)
    cloth.pin(list(range(nx)))  # the whole top row
    for _ in range(steps):
        cloth.step(DT)
    return 0.5 - float(np.mean(cloth.positions[-nx:, 1]))  # drop of the bottom row


def test_xpbd_sag_converges_to_the_static_solution() -> None:
    """A cloth hanging from its whole top row, stretch compliance alpha (shear and bend ~off):
    each column is a chain of springs, and the bottom row drops by
    alpha m g (ny-1) ny / 2. XPBD converges to it as iterations x substeps grow (successive
    differences shrink); plain PBD (compliance 0) halves its sag with every doubling of the
    iterations: its stiffness is a function of the iteration count."""
    alpha, nx, ny = 1e-3, 4, 10
    analytic = alpha * (1.0 / (nx * ny)) * G * (ny - 1) * ny / 2.0
    sags = [_column_sag(k, k, alpha) for k in (1, 2, 4, 8)]
    diffs = np.abs(np.diff(sags))
    assert np.all(diffs[1:] < 0.5 * diffs[:-1]), sags
    assert sags[-1] == pytest.approx(analytic, rel=0.02), (sags, analytic)
    pbd = [_column_sag(k, 1, 0.0) for k in (1, 2, 4, 8)]
    ratios = np.array(pbd[1:]) / np.array(pbd[:-1])
    assert np.all((ratios > 0.35) & (ratios < 0.65)), pbd


# --------------------------------------------------------------------------------------------
# The C++ solver against the NumPy reference; threads; stepping helpers
# --------------------------------------------------------------------------------------------

def test_matches_numpy_reference() -> None:
    kw = dict(nx=8, ny=6, origin=(-0.5, 1.5, 0.0), axis_v=(0, -1, 0), iterations=2, substeps=2,
              compliance_bend=1e-4, compliance_shear=1e-6, tethers=True, damping=0.98)
    cloth, r = weft.Cloth(**kw), ref.ClothReference(**kw)
    for obj in (cloth, r):
        obj.pin([0, 7])
    cloth.wind = weft.Wind(direction=(0.3, 0.1, 1.0), strength=5.0)
    r.set_wind((0.3, 0.1, 1.0), 5.0)
    cloth.add_collider(weft.Collider.sphere((0, 1.0, 0.05), 0.2))
    r.add_collider(ref.SphereShape((0, 1.0, 0.05), 0.2))
    cloth.add_collider(weft.Collider.plane((0, 0.9, 0), (0, 1, 0.2), friction=0.3))
    r.add_collider(ref.PlaneShape((0, 0.9, 0), (0, 1, 0.2), friction=0.3))
    for _ in range(10):
        cloth.step(DT)
        r.step(DT)
    np.testing.assert_allclose(positions64(cloth), r.positions, atol=1e-4)
    np.testing.assert_allclose(cloth.normals, r.normals, atol=1e-3)
    s, rs = cloth.stats(), r.stats()
    assert s["mean_strain"] == pytest.approx(rs["mean_strain"], rel=1e-3, abs=1e-6)
    assert s["max_strain"] == pytest.approx(rs["max_strain"], rel=1e-3, abs=1e-6)
    assert cloth.kinetic_energy() == pytest.approx(r.kinetic_energy(), rel=1e-3)
    np.testing.assert_allclose(cloth.velocities(), r.velocities(), atol=1e-2)


def test_threads_bit_identical() -> None:
    out = []
    for threads in (1, 2):
        cloth = hanging(48, threads=threads, iterations=2, substeps=2, compliance_bend=1e-5,
                        tethers=True, self_collision=True)
        cloth.wind = weft.Wind(direction=(0, 0.2, 1), strength=8.0)
        cloth.add_collider(weft.Collider.sphere((0, 0.9, 0.1), 0.2))
        for _ in range(25):
            cloth.step(DT)
        out.append(np.array(cloth.positions))
    np.testing.assert_array_equal(out[0], out[1])


def test_advance_fixed_rate() -> None:
    cloth = weft.Cloth(nx=4, ny=4)
    assert cloth.advance(4 / 64, rate=64) == 4
    assert cloth.advance(0.5 / 64, rate=64) == 0  # leftover kept
    assert cloth.advance(0.5 / 64, rate=64) == 1
    assert cloth.step_count == 5
    assert cloth.advance(10.0, rate=64, max_steps=8) == 8  # capped, backlog dropped
    assert cloth.advance(0.5 / 64, rate=64) == 0
    assert cloth.step_count == 13
    r = ref.ClothReference(nx=4, ny=4)
    assert [r.advance(t, rate=64) for t in (4 / 64, 0.5 / 64, 0.5 / 64)] == [4, 0, 1]


def test_set_positions_and_velocities() -> None:
    cloth = weft.Cloth(nx=3, ny=3, gravity=(0, 0, 0), damping=1.0)
    x = positions64(cloth) + [0.0, 0.5, 0.0]
    cloth.set_positions(x)
    cloth.step(DT)
    np.testing.assert_allclose(positions64(cloth), x, atol=1e-6)  # at rest
    cloth.set_velocities(np.tile([0, 0, 1.0], (9, 1)))
    cloth.step(DT)
    cloth.set_positions(x, keep_velocity=True)
    cloth.step(DT)
    np.testing.assert_allclose(positions64(cloth), x + [0, 0, DT], atol=1e-6)


def test_mesh_output() -> None:
    nx, ny = 6, 5
    cloth = weft.Cloth(nx=nx, ny=ny)
    cloth.step(DT)
    mesh = cloth.mesh()
    n = nx * ny
    assert mesh["positions"].shape == (n, 3) and mesh["normals"].shape == (n, 3)
    assert mesh["uvs"].shape == (n, 2) and mesh["tangents"].shape == (n, 4)
    np.testing.assert_array_equal(mesh["positions"], cloth.positions)
    jj, ii = np.meshgrid(np.arange(ny), np.arange(nx), indexing="ij")
    np.testing.assert_allclose(mesh["uvs"],
                               np.stack([ii.ravel() / (nx - 1), jj.ravel() / (ny - 1)], 1),
                               atol=1e-7)
    np.testing.assert_allclose(np.linalg.norm(mesh["normals"], axis=1), 1.0, atol=1e-5)
    np.testing.assert_allclose(mesh["normals"], np.tile([0, 1, 0], (n, 1)), atol=1e-5)
    np.testing.assert_allclose(mesh["tangents"][:, :3], np.tile([1, 0, 0], (n, 1)), atol=1e-5)
    assert set(np.unique(mesh["tangents"][:, 3]).tolist()) <= {-1.0, 1.0}
    tris = mesh["indices"]
    assert tris.dtype == np.uint32 and tris.shape == (2 * (nx - 1) * (ny - 1), 3)
    assert triangle_set(tris) == triangle_set(ref.grid_triangles(nx, ny))
    # triangles face the normals: (p1 - p0) x (p2 - p0) . n > 0 for this winding, or all < 0
    p = mesh["positions"].astype(np.float64)
    face = np.cross(p[tris[:, 1]] - p[tris[:, 0]], p[tris[:, 2]] - p[tris[:, 0]])
    sign = np.sign(face @ np.array([0, 1.0, 0]))
    assert abs(sign.sum()) == len(tris)


# --------------------------------------------------------------------------------------------
# Validation
# --------------------------------------------------------------------------------------------

def test_invalid_arguments_rejected() -> None:
    assert issubclass(weft.InvalidArgument, ValueError)
    nan, inf = float("nan"), float("inf")
    bad_ctor = [dict(nx=1, ny=1), dict(nx=0, ny=5), dict(size=(nan, 1.0)), dict(size=(-1.0, 1.0)),
                dict(size=(1.0, 0.0)), dict(origin=(0, inf, 0)), dict(axis_u=(0, 0, 0)),
                dict(axis_u=(1, 0, 0), axis_v=(2, 0, 0)), dict(mass=0.0), dict(mass=nan),
                dict(damping=nan), dict(gravity=(0, nan, 0)), dict(iterations=0),
                dict(substeps=0), dict(compliance_stretch=-1.0), dict(compliance_bend=nan),
                dict(thickness=-0.1), dict(tear_strain=nan), dict(size=(1.0, 1.0, 1.0))]
    for kw in bad_ctor:
        with pytest.raises(ValueError):
            weft.Cloth(**kw)
    cloth = weft.Cloth(nx=4, ny=3)
    n = cloth.particle_count
    good = np.zeros((n, 3))
    bad_calls = [
        lambda: cloth.set_positions(np.full((n, 3), nan)),
        lambda: cloth.set_positions(np.zeros((n - 1, 3))),
        lambda: cloth.set_positions(np.zeros((n, 2))),
        lambda: cloth.set_velocities(np.where(np.eye(n, 3) > 0, inf, 0.0)),
        lambda: cloth.pin([n]),
        lambda: cloth.pin([-1]),
        lambda: cloth.grab([0], [[nan, 0, 0]]),
        lambda: cloth.grab([0, 1], [[0, 0, 0]]),
        lambda: cloth.step(nan),
        lambda: cloth.step(-DT),
        lambda: cloth.step(0.0),
        lambda: cloth.advance(nan),
        lambda: setattr(cloth, "iterations", 0),
        lambda: setattr(cloth, "damping", nan),
        lambda: setattr(cloth, "gravity", (0, inf, 0)),
        lambda: setattr(cloth, "wind", weft.Wind(direction=(0, 0, 0), strength=1.0)),
        lambda: weft.Wind(direction=(nan, 0, 0), strength=1.0),
        lambda: weft.Wind(direction=(1, 0, 0), strength=inf),
        lambda: cloth.set_holes(np.zeros((4, 3), dtype=bool)),
        lambda: cloth.set_holes(np.full((3, 4), nan)),
        lambda: weft.Collider.sphere((0, 0, 0), -1.0),
        lambda: weft.Collider.sphere((nan, 0, 0), 1.0),
        lambda: weft.Collider.plane((0, 0, 0), (0, 0, 0)),
        lambda: weft.Collider.box((0, 0, 0), (1, -1, 1)),
        lambda: weft.Collider.box((0, 0, 0), (1, 1, 1), rotation=np.ones((3, 3))),
        lambda: weft.Collider.capsule((0, 0, 0), (1, 0, 0), 0.0),
        lambda: weft.Collider.height_field(np.zeros((1, 5)), (0, 0, 0), (1, 1)),
        lambda: weft.Collider.height_field(np.full((3, 3), nan), (0, 0, 0), (1, 1)),
        lambda: weft.Collider.height_field(np.zeros((3, 3)), (0, 0, 0), (-1, 1)),
        lambda: weft.Collider.sphere((0, 0, 0), 1.0, friction=2.0),
        lambda: weft.Collider.sphere((0, 0, 0), 1.0).distance(np.zeros((3, 2))),
        lambda: cloth.pick((0, 0, 0), (0, 0, 0)),
    ]
    for i, call in enumerate(bad_calls):
        with pytest.raises(ValueError):
            call()
            pytest.fail(f"bad call {i} was accepted")
    # the cloth is still usable and unchanged by the rejected calls
    cloth.set_positions(good)
    cloth.step(DT)
    assert np.all(np.isfinite(cloth.positions))
