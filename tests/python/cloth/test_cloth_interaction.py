"""weft.Cloth's interaction with the world against independent references (SPEC §2.2): collider
distances and projection (eq. 3.7, plane, box, capsule, height field), friction, wind (eq. 3.5,
normals eq. 3.6), hole masks, grabbing and picking, tearing, sleeping and self-collision.
Shared helpers come from test_cloth.py."""

from __future__ import annotations

import math
from typing import Any, List, Tuple

import numpy as np
import pytest
import weft
from test_cloth import DT, G, hanging, positions64, triangle_set
from weft.reference import cloth as ref

# --------------------------------------------------------------------------------------------
# Colliders
# --------------------------------------------------------------------------------------------

def _rotation(axis: Tuple[float, float, float], angle: float) -> np.ndarray:
    k = np.asarray(axis, dtype=np.float64)
    k /= np.linalg.norm(k)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx


def _shapes() -> List[Tuple[str, Any, Any]]:
    rot = _rotation((0.3, 1.0, -0.2), 0.7)
    xs, zs = np.linspace(0, 1, 7), np.linspace(0, 1, 5)
    bumpy = 0.2 * np.sin(3 * xs)[None, :] * np.cos(2 * zs)[:, None] + 0.05 * zs[:, None]
    tilted = 0.3 * xs[None, :] - 0.2 * zs[:, None] + 0 * zs[:, None]
    return [
        ("sphere", weft.Collider.sphere((0.1, 0.2, -0.3), 0.5),
         ref.SphereShape((0.1, 0.2, -0.3), 0.5)),
        ("plane", weft.Collider.plane((0, 0.1, 0), (0.2, 1.0, -0.3)),
         ref.PlaneShape((0, 0.1, 0), (0.2, 1.0, -0.3))),
        ("box", weft.Collider.box((0.1, 0.0, 0.2), (0.4, 0.2, 0.3), rotation=rot),
         ref.BoxShape((0.1, 0.0, 0.2), (0.4, 0.2, 0.3), rot)),
        ("capsule", weft.Collider.capsule((-0.3, 0, 0), (0.4, 0.2, 0.1), 0.25),
         ref.CapsuleShape((-0.3, 0, 0), (0.4, 0.2, 0.1), 0.25)),
        ("height_field", weft.Collider.height_field(bumpy, (-0.5, -0.1, -0.5), size=(1.0, 1.0)),
         ref.HeightFieldShape(bumpy, (-0.5, -0.1, -0.5), (1.0, 1.0))),
        ("tilted_field", weft.Collider.height_field(tilted, (-0.5, 0.0, -0.5), size=(1.0, 1.0)),
         ref.HeightFieldShape(tilted, (-0.5, 0.0, -0.5), (1.0, 1.0))),
    ]


@pytest.mark.parametrize("index", range(6), ids=[s[0] for s in _shapes()])
def test_collider_distance(index: int) -> None:
    name, collider, shape = _shapes()[index]
    rng = np.random.default_rng(7 + index)
    pts = rng.uniform(-0.8, 0.8, size=(400, 3))
    if "field" in name:
        pts[:, [0, 2]] = rng.uniform(-0.49, 0.49, size=(400, 2))
    d, n = collider.distance(pts)
    ed, en = shape.distance(pts)
    assert d.shape == (400,) and n.shape == (400, 3)
    np.testing.assert_allclose(d, ed, atol=2e-6)
    # normals are defined away from medial axes (box centre planes, capsule axis)
    ok = np.abs(ed) > 1e-3
    np.testing.assert_allclose(n[ok], en[ok], atol=1e-4)
    assert np.any(ed < 0) and np.any(ed > 0)


def test_analytic_distances() -> None:
    """The reference shapes themselves against hand-computed values."""
    d, n = ref.sphere_distance([[0, 2, 0]], (0, 0, 0), 0.5)
    assert d[0] == pytest.approx(1.5) and np.allclose(n[0], (0, 1, 0))
    d, _ = ref.box_distance([[2, 0, 0], [0, 0.1, 0], [1.5, 1.5, 0]], (0, 0, 0), (1, 0.5, 1))
    np.testing.assert_allclose(d, [1.0, -0.4, math.hypot(0.5, 1.0)])
    d, _ = ref.capsule_distance([[0.5, 1, 0], [2, 0, 0]], (0, 0, 0), (1, 0, 0), 0.25)
    np.testing.assert_allclose(d, [0.75, 0.75])
    # a planar height field is a plane: exact signed distance
    xs = np.linspace(0, 1, 4)
    h = 0.5 * xs[None, :] + np.zeros((3, 1))
    p = np.array([[0.2, 1.0, 0.3]])
    d, n = ref.height_field_distance(p, h, (0, 0, 0), (1, 1))
    expect_n = np.array([-0.5, 1.0, 0.0]) / math.sqrt(1.25)
    np.testing.assert_allclose(n[0], expect_n)
    assert d[0] == pytest.approx(p[0] @ expect_n)  # the plane y = x / 2 through 0


@pytest.mark.parametrize("index", range(6), ids=[s[0] for s in _shapes()])
def test_projection_out_of_collider(index: int) -> None:
    """A particle inside a collider ends on its surface + thickness (eq. 3.7 for the sphere)."""
    name, collider, shape = _shapes()[index]
    thickness = 0.01
    cloth = weft.Cloth(nx=2, ny=1, origin=(0, 0, 0), gravity=(0, 0, 0), thickness=thickness)
    cloth.pin([1])  # the pinned partner keeps the constraint out of the way
    inside = {"sphere": (0.25, 0.45, -0.1), "plane": (0.1, 0.0, 0.2), "box": (0.2, 0.05, 0.25),
              "capsule": (0.1, 0.05, 0.0), "height_field": (0.1, -0.2, 0.1),
              "tilted_field": (0.1, -0.2, 0.1)}[name]
    p0 = np.array(inside)
    assert shape.distance(p0)[0][0] < 0.0
    cloth.set_positions(np.stack([p0, p0 + [1.0, 0, 0]]))
    assert cloth.add_collider(collider) == 0 and cloth.collider_count == 1
    cloth.project_constraints()
    got = positions64(cloth)
    # on a curved height field the distance is first-order (to the tangent plane): close only
    tol = 2e-3 if name == "height_field" else 2e-5
    assert collider.distance(got[:1])[0][0] == pytest.approx(thickness, abs=tol)
    s, n = shape.distance(p0)
    np.testing.assert_allclose(got[0], p0 + (thickness - s[0]) * n[0], atol=2e-5)
    if name == "sphere":  # eq. 3.7: M + (r + thickness) (x - M)/|x - M|
        c, r = np.array([0.1, 0.2, -0.3]), 0.5
        np.testing.assert_allclose(got[0], c + (r + thickness) * (p0 - c) / np.linalg.norm(p0 - c),
                                   atol=2e-6)
    np.testing.assert_array_equal(got[1], np.float32(p0 + [1.0, 0, 0]))  # pinned: not collided
    # outside beyond the thickness: untouched
    far = p0 + 3.0 * np.array([0, 1.0, 0]) if name != "box" else p0 + [0, 2.0, 0]
    cloth.set_positions(np.stack([far, far + [1.0, 0, 0]]))
    cloth.project_constraints()
    np.testing.assert_allclose(positions64(cloth)[0], far, atol=1e-6)
    cloth.clear_colliders()
    assert cloth.collider_count == 0


def test_set_collider_moves_it() -> None:
    cloth = weft.Cloth(nx=2, ny=1, origin=(0, 0, 0), gravity=(0, 0, 0), thickness=0.0)
    cloth.pin([1])
    cid = cloth.add_collider(weft.Collider.sphere((5, 5, 5), 0.1))
    cloth.project_constraints()
    np.testing.assert_allclose(cloth.positions[0], (0, 0, 0), atol=1e-7)
    cloth.set_collider(cid, weft.Collider.sphere((0, -0.1, 0), 0.3))
    cloth.project_constraints()
    np.testing.assert_allclose(cloth.positions[0], (0, 0.2, 0), atol=1e-6)
    with pytest.raises(weft.InvalidArgument):
        cloth.set_collider(5, weft.Collider.sphere((0, 0, 0), 0.3))


@pytest.mark.parametrize("friction", [0.0, 0.5, 1.0])
def test_friction_on_plane(friction: float) -> None:
    """Sliding on a plane: after the contact the tangential motion is scaled by (1 - f)."""
    thickness, v = 0.005, 0.6
    cloth = weft.Cloth(nx=2, ny=1, origin=(0, 0.0, 0), damping=1.0, thickness=thickness)
    cloth.add_collider(weft.Collider.plane((0, -thickness, 0), (0, 1, 0), friction=friction))
    cloth.set_velocities(np.tile([v, 0, 0], (2, 1)))
    x0 = positions64(cloth)
    cloth.step(DT)
    cloth.step(DT)
    got = positions64(cloth)
    np.testing.assert_allclose(got[:, 0] - x0[:, 0], v * DT * (1 + (1 - friction)), atol=2e-6)
    np.testing.assert_allclose(got[:, 1], 0.0, atol=2e-6)


# --------------------------------------------------------------------------------------------
# Wind (eq. 3.5)
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("direction,factor", [((0, 1, 1), 1 / math.sqrt(2)), ((0, -2, 0), -1.0),
                                              ((1, 0, 0), 0.0), ((0.3, 0, -1), 0.0)])
def test_wind_acceleration(direction: Tuple[float, float, float], factor: float) -> None:
    """Flat horizontal cloth (normals +Y), no gravity: a = s (n.r) n, so one step from rest
    moves every particle by s (n.r) dt^2 along +Y; wind in the cloth's plane does nothing."""
    s, dt = 3.0, 0.05
    cloth = weft.Cloth(nx=5, ny=4, gravity=(0, 0, 0), damping=1.0)
    x0 = positions64(cloth)
    cloth.wind = weft.Wind(direction=direction, strength=s)
    assert cloth.wind.strength == pytest.approx(s)
    cloth.step(dt)
    np.testing.assert_allclose(cloth.normals, np.tile([0, 1, 0], (20, 1)), atol=1e-6)
    expect = x0 + np.array([0, s * factor * dt * dt, 0])
    np.testing.assert_allclose(positions64(cloth), expect, atol=1e-6)
    r = ref.ClothReference(nx=5, ny=4, gravity=(0, 0, 0), damping=1.0)
    r.set_wind(direction, s)
    r.step(dt)
    np.testing.assert_allclose(r.positions - r.rest_positions, expect - x0, atol=1e-12)


def test_wind_normals_follow_the_cloth() -> None:
    """Normals (eq. 3.6) of a tilted cloth; wind can change at any time."""
    u, v = np.array([1.0, 0, 0]), np.array([0, 0.6, 0.8])
    cloth = weft.Cloth(nx=4, ny=4, axis_u=u, axis_v=v, gravity=(0, 0, 0), damping=1.0)
    cloth.wind = weft.Wind(direction=(0, 0, 1), strength=2.0)
    x0 = positions64(cloth)
    cloth.step(0.1)
    n = np.cross(v, u)
    np.testing.assert_allclose(cloth.normals, np.tile(n, (16, 1)), atol=1e-6)
    np.testing.assert_allclose(positions64(cloth) - x0, np.tile(2.0 * n[2] * n * 0.01, (16, 1)),
                               atol=1e-6)
    cloth.wind = weft.Wind(direction=(0, 0, 1), strength=0.0)
    before = positions64(cloth)
    cloth.step(0.1)  # no wind, no gravity: keeps its velocity
    np.testing.assert_allclose(positions64(cloth) - before, np.tile(2.0 * n[2] * n * 0.01, (16, 1)),
                               atol=1e-6)


# --------------------------------------------------------------------------------------------
# Holes, grab, pick, tearing, sleeping
# --------------------------------------------------------------------------------------------

def test_hole_mask() -> None:
    nx, ny = 8, 6
    cloth = hanging(nx, ny)
    mask = np.zeros((ny, nx), dtype=bool)
    mask[2:4, 3:5] = True
    mask[5, 0] = True
    full = cloth.mesh()["indices"]
    assert len(full) == 2 * (nx - 1) * (ny - 1)
    cloth.set_holes(mask)
    np.testing.assert_array_equal(cloth.holes, mask)
    hole = mask.reshape(-1)
    w = np.full(nx * ny, nx * ny, dtype=np.float32)
    w[[0, nx - 1]] = 0.0
    w[hole] = 0.0
    np.testing.assert_array_equal(cloth.inverse_masses, w)
    c = cloth.constraints()
    touching = hole[c["a"]] | hole[c["b"]]
    # constraints go with their ends and with the faces they run through (issue 17: nothing
    # spans a hole), by the geometric test of the reference
    on = ref.constraints_on_surface(nx, ref.grid_triangles(nx, ny, hole=hole), c["a"], c["b"])
    assert (on & ~touching).sum() < (~touching).sum()  # some span the hole without touching it
    np.testing.assert_array_equal(c["active"], on & ~touching)
    assert cloth.stats()["active_constraints"] == int((on & ~touching).sum())
    tris = cloth.mesh()["indices"]
    assert tris.dtype == np.uint32 and tris.shape[1] == 3
    assert not hole[tris].any()
    expect = ref.grid_triangles(nx, ny, hole=hole)
    assert triangle_set(tris) == triangle_set(expect)
    x0 = positions64(cloth)
    for _ in range(10):
        cloth.step(DT)
    np.testing.assert_array_equal(positions64(cloth)[hole], x0[hole])  # holes are gone
    # the same as the reference after those steps
    r = ref.ClothReference(nx=nx, ny=ny, origin=(-0.5, 1.5, 0.0), axis_v=(0, -1, 0))
    r.pin([0, nx - 1])
    r.set_holes(mask)
    for _ in range(10):
        r.step(DT)
    np.testing.assert_allclose(positions64(cloth), r.positions, atol=1e-4)
    # numbers work as a mask; an all-zero mask fills the holes again
    cloth.set_holes(mask.astype(np.float32) * 2.0)
    np.testing.assert_array_equal(cloth.holes, mask)
    cloth.set_holes(np.zeros((ny, nx), dtype=bool))
    assert cloth.constraints()["active"].all()


@pytest.mark.parametrize("channels", [1, 4])
def test_hole_image(channels: int) -> None:
    """A uint8 image of any size is sampled at the particles' UVs: dark (or transparent)
    texels are holes."""
    nx, ny = 8, 6
    img = np.full((64, 48, channels) if channels > 1 else (64, 48), 255, dtype=np.uint8)
    if channels == 1:
        img[:, :24] = 20  # left half dark
    else:
        img[..., :3] = 0  # black but opaque: not a hole
        img[:, :24, 3] = 0  # left half transparent
    cloth = weft.Cloth(nx=nx, ny=ny)
    cloth.set_holes(img)
    expect = np.zeros((ny, nx), dtype=bool)
    expect[:, :4] = True  # u = i/7 < 0.5
    np.testing.assert_array_equal(cloth.holes, expect)
    np.testing.assert_array_equal(ref.hole_mask_from_image(img, nx, ny), expect)
    assert triangle_set(cloth.mesh()["indices"]) == triangle_set(
        ref.grid_triangles(nx, ny, hole=expect.reshape(-1)))


def test_grab_follows_targets_and_release_restores() -> None:
    n = 8
    cloth = hanging(n)
    w0 = np.array(cloth.inverse_masses)
    idx = [n * (n - 1), n * n - 1]  # the bottom corners
    targets = np.array([[-0.7, 0.3, 0.4], [0.6, 0.2, 0.5]], dtype=np.float32)
    cloth.grab(idx, targets)
    assert np.all(cloth.inverse_masses[idx] == 0.0)
    for _ in range(3):
        cloth.step(DT)
        np.testing.assert_array_equal(cloth.positions[idx], targets)
    moved = targets + np.float32(0.25)
    cloth.move_grab(moved)
    cloth.step(DT)
    np.testing.assert_array_equal(cloth.positions[idx], moved)
    # grabbed particles are exact targets even with substeps and iterations
    cloth.substeps, cloth.iterations = 3, 4
    cloth.step(DT)
    np.testing.assert_array_equal(cloth.positions[idx], moved)
    cloth.release()
    np.testing.assert_array_equal(cloth.inverse_masses, w0)
    cloth.step(DT)
    assert not np.array_equal(cloth.positions[idx], moved)  # free again
    with pytest.raises(weft.InvalidArgument):
        cloth.move_grab(moved)  # nothing grabbed


def test_grab_matches_reference() -> None:
    n = 6
    cloth = hanging(n, iterations=2)
    r = ref.ClothReference(nx=n, ny=n, origin=(-0.5, 1.5, 0.0), axis_v=(0, -1, 0), iterations=2)
    r.pin([0, n - 1])
    targets = np.array([[0.0, 0.4, 0.3]])
    for obj in (cloth, r):
        obj.grab([n * n - 3], targets)
    for k in range(8):
        for obj in (cloth, r):
            obj.move_grab(targets + [0.02 * k, 0, 0])
            obj.step(DT)
    np.testing.assert_allclose(positions64(cloth), r.positions, atol=1e-4)


def test_pick() -> None:
    cloth = weft.Cloth(nx=8, ny=8)
    k = 3 * 8 + 5
    p = np.asarray(cloth.positions[k], dtype=np.float64)
    assert cloth.pick(p + [0, 1, 0], (0, -1, 0)) == k
    assert cloth.pick(p + [0.01, 1, 0], (0, -2, 0), max_distance=0.05) == k
    assert cloth.pick(p + [0, 1, 0], (0, 1, 0)) == -1  # pointing away
    assert cloth.pick((5, 5, 5), (0, -1, 0)) == -1


def test_tearing() -> None:
    n, tear = 8, 0.3
    cloth = hanging(n, tear_strain=tear)
    full = len(cloth.mesh()["indices"])
    bottom = list(range(n * (n - 1), n * n))
    start = np.asarray(cloth.positions, dtype=np.float64)[bottom]
    for k in range(1, 31):
        cloth.grab(bottom, start + [0, -0.1 * k, 0])
        cloth.step(DT)
    c = cloth.constraints()
    active = c["active"]
    assert active.sum() < len(active)
    assert cloth.stats()["active_constraints"] == int(active.sum())
    # after the step every intact constraint is within the tear strain in tension (faces tear
    # when stretched; compression folds cloth, it does not tear it)
    x = positions64(cloth)
    s = (np.linalg.norm(x[c["b"]] - x[c["a"]], axis=1) - c["rest"]) / c["rest"]
    assert s[active].max() <= tear + 1e-5
    # the mesh keeps exactly the triangles whose three edges are intact
    tris = cloth.mesh()["indices"]
    assert len(tris) < full
    key = {(min(a, b), max(a, b)): on for a, b, on in zip(c["a"].tolist(), c["b"].tolist(),
                                                          active.tolist())}
    edge_active = np.vectorize(lambda a, b: key.get((min(a, b), max(a, b)), False))
    assert triangle_set(tris) == triangle_set(ref.grid_triangles(n, n, edge_active))
    # reset mends the cloth
    cloth.reset()
    assert cloth.constraints()["active"].all()
    np.testing.assert_allclose(cloth.positions, ref.grid_positions(n, n, (1, 1), (-0.5, 1.5, 0),
                                                                  (1, 0, 0), (0, -1, 0)), atol=1e-6)


def test_sleep_and_wake() -> None:
    thickness = 0.005
    cloth = weft.Cloth(nx=6, ny=6, thickness=thickness, sleep_threshold=0.01, sleep_steps=10)
    cloth.add_collider(weft.Collider.plane((0, 1.0 - thickness, 0), (0, 1, 0)))
    for _ in range(9):
        cloth.step(DT)
    assert not cloth.sleeping
    cloth.step(DT)
    assert cloth.sleeping
    assert cloth.kinetic_energy() < 1e-8
    frozen = np.array(cloth.positions)
    cloth.gravity = (0, 0, 0)  # changing settings wakes it up
    assert not cloth.sleeping
    cloth.gravity = (0, -G, 0)
    for _ in range(10):
        cloth.step(DT)
    assert cloth.sleeping
    cloth.step(DT)
    # the same rest state (rest lengths now exact in double: it creeps ~1e-7 m, not 0)
    np.testing.assert_allclose(cloth.positions, frozen, atol=1e-6)
    cloth.grab([0], [[-0.5, 1.5, -0.5]])  # grabbing wakes it
    assert not cloth.sleeping
    cloth.step(DT)
    assert cloth.positions[0, 1] == pytest.approx(1.5)
    cloth.release()
    cloth.wake()
    assert not cloth.sleeping


def test_self_collision_pushes_apart() -> None:
    """Two particles of a 2x2 cloth (constraints made ~ineffective by a huge compliance) placed
    1 cm apart are pushed to the self-collision thickness, symmetrically."""
    soft = dict(nx=2, ny=2, gravity=(0, 0, 0), compliance_stretch=1e6, compliance_shear=1e6,
                compliance_bend=1e6, self_thickness=0.05)
    x = ref.grid_positions(2, 2)
    x[3] = x[0] + [0.006, 0.008, 0.0]  # 0.01 from particle 0; rest distance sqrt(2) > T
    results = {}
    for on in (False, True):
        cloth = weft.Cloth(self_collision=on, **soft)
        cloth.set_positions(x)
        cloth.step(DT)
        results[on] = positions64(cloth)
    assert np.linalg.norm(results[False][3] - results[False][0]) == pytest.approx(0.01, abs=1e-5)
    got = results[True]
    assert np.linalg.norm(got[3] - got[0]) == pytest.approx(0.05, abs=1e-5)
    mid = 0.5 * (x[0] + x[3])
    np.testing.assert_allclose(0.5 * (got[0] + got[3]), mid, atol=1e-5)
    r = ref.ClothReference(self_collision=True, **soft)
    r.set_positions(x)
    r.step(DT)
    np.testing.assert_allclose(got, r.positions, atol=1e-5)
