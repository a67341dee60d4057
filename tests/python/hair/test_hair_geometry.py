"""Hair and fur generators, tangents and ribbons against NumPy references and analytic facts."""

from __future__ import annotations

import numpy as np
import pytest
import weft
from weft.reference import hair_geometry as G


@pytest.mark.parametrize("strands, points", [(10_000, 160_000), (10_000, 687_532),
                                             (15_000, 1_031_268)])
def test_seed_sizes_exact(strands: int, points: int) -> None:
    h = weft.generate_hair(strands, points, style="wavy")
    assert h.strand_count == strands and h.point_count == points
    seg = h.segments.astype(np.int64) + 1
    assert seg.max() - seg.min() <= 1 and seg.sum() == points


def test_straight_hair_roots_on_scalp_and_length() -> None:
    center, radii = np.array([0.0, 1.6, 0.0]), np.array([0.09, 0.11, 0.1])
    h = weft.generate_hair(200, 200 * 12, droop=0.0, length=0.2, scalp_center=center,
                           scalp_radii=radii, scalp_cutoff=0.2)
    off = h.offsets
    roots = h.points[off[:-1]].astype(np.float64)
    np.testing.assert_allclose(np.sum(((roots - center) / radii) ** 2, axis=1), 1.0, atol=1e-5)
    assert np.all((roots[:, 1] - center[1]) / radii[1] >= 0.2 - 1e-6)
    for s in range(0, 200, 37):
        p = h.points[off[s]:off[s + 1]].astype(np.float64)
        normal = (p[0] - center) / radii ** 2
        normal /= np.linalg.norm(normal)
        np.testing.assert_allclose(p - p[0], np.outer(np.linspace(0, 0.2, len(p)), normal),
                                   atol=2e-6)


def test_droop_lengths_and_curl_radius() -> None:
    h = weft.generate_hair(50, 50 * 40, droop=0.8, length=0.3, length_jitter=0.2, seed=7)
    off = h.offsets
    lengths = [np.sum(np.linalg.norm(np.diff(h.points[off[s]:off[s + 1]], axis=0), axis=1))
               for s in range(50)]
    assert 0.3 * 0.8 - 1e-4 <= min(lengths) and max(lengths) <= 0.3 * 1.2 + 1e-4
    assert np.std(lengths) > 0.01
    tips = h.points[off[1:] - 1]
    roots = h.points[off[:-1]]
    assert np.mean(tips[:, 1] - roots[:, 1]) < -0.05  # drooping strands end lower
    r, center, radii = 0.02, np.array([0.0, 1.6, 0.0]), np.array([0.09, 0.11, 0.1])
    c = weft.generate_hair(20, 20 * 201, style="curly", droop=0.0, curl_radius=r, length=0.2,
                           wave_frequency=10.0)  # exactly 2 turns of 100 samples each
    off = c.offsets
    for s in range(0, 20, 7):  # every point is r from the helix axis (along the root normal)
        p = c.points[off[s]:off[s + 1]].astype(np.float64)
        n = (p[0] - center) / radii ** 2
        n /= np.linalg.norm(n)
        rel = p - p[:-1].mean(axis=0)
        radial = rel - np.outer(rel @ n, n)
        np.testing.assert_allclose(np.linalg.norm(radial, axis=1), r, rtol=1e-3)


def test_generators_are_deterministic_and_validate() -> None:
    a = weft.generate_hair(100, 1000, style="wavy", seed=3, threads=1)
    b = weft.generate_hair(100, 1000, style="wavy", seed=3, threads=2)
    np.testing.assert_array_equal(a.points, b.points)
    c = weft.generate_hair(100, 1000, style="wavy", seed=4)
    assert not np.array_equal(a.points, c.points)
    for kwargs in (dict(strands=0), dict(points=10), dict(style="frizzy"), dict(droop=2.0),
                   dict(length=float("nan")), dict(scalp_radii=(1, 0, 1))):
        with pytest.raises(weft.InvalidArgument):
            weft.generate_hair(**{"strands": 10, "points": 100, **kwargs})


def _mesh_args(mesh: "weft.Mesh"):
    return mesh.positions, mesh.normals, mesh.uvs, mesh.indices


def test_fur_matches_numpy_reference(smooth_texture) -> None:
    mesh = weft.Mesh.uv_sphere(0.5, 8, 5)
    tex = smooth_texture(16, 16, 3)
    kw = dict(level=3, segments=10, length=0.3, length_jitter=0.3, direction_jitter=0.4,
              down=(0.1, -0.5, 0.0), seed=9)
    fur = weft.generate_fur(mesh, texture=tex, **kw)
    pts, cols = G.fur(*_mesh_args(mesh), texture=tex, **kw)
    assert fur.strand_count == mesh.triangle_count * 9 and fur.point_count == len(pts)
    np.testing.assert_allclose(fur.points, pts, atol=2e-6)
    np.testing.assert_allclose(fur.colors[::11], cols, atol=1e-5)
    assert list(fur.segments[:3]) == [10, 10, 10]


def test_fur_seed_listing_geometry() -> None:
    """One flat triangle, level 1: the strand starts at the centroid along the normal and bends
    by `down` per segment exactly as 002 listing 1."""
    mesh = weft.Mesh([[0, 0, 0], [1, 0, 0], [0, 0, -1]], [[0, 1, 0]] * 3, [[0, 0]] * 3, [[0, 1, 2]])
    fur = weft.generate_fur(mesh, segments=10, length=0.3)
    p = [np.array([1 / 3, 0, -1 / 3])]
    d = np.array([0.0, 1.0, 0.0])
    for _ in range(10):
        p.append(p[-1] + d * 0.03)
        d = d + np.array([0, -0.5, 0]) * 0.03
    np.testing.assert_allclose(fur.points, np.array(p), atol=1e-6)


def test_fur_density_and_validation() -> None:
    mesh = weft.Mesh.plane(2.0, 1.0, 2, 1)  # 4 triangles of 0.5 m^2
    fur = weft.generate_fur(mesh, density=200.0)  # level round(sqrt(100)) = 10
    assert fur.strand_count == 4 * 100
    with pytest.raises(weft.InvalidArgument):
        weft.generate_fur(mesh, level=0)
    with pytest.raises(weft.InvalidArgument):
        weft.generate_fur(mesh, length_jitter=1.5)
    with pytest.raises(weft.InvalidArgument):
        weft.generate_fur(mesh, down=(0, float("nan"), 0))
    with pytest.raises(weft.InvalidArgument):
        weft.generate_fur(mesh, level=1024, segments=65535)  # more points than 2^32


def test_tangents_and_ribbons_match_reference() -> None:
    h = weft.generate_hair(30, 30 * 9, style="curly", seed=2)
    off = h.offsets
    np.testing.assert_allclose(h.tangents(), G.tangents(h.points, off), atol=1e-5)
    eye = (0.3, 2.0, 1.5)
    thick = np.random.default_rng(1).uniform(0.5, 1.5, h.point_count)
    h2 = weft.HairStrands(h.points, h.segments, thickness=thick)
    np.testing.assert_allclose(h2.ribbons(eye, 0.01), G.ribbons(h.points, off, thick, eye, 0.01),
                               atol=1e-6)
    tri = h2.ribbon_indices()
    assert tri.shape == (2 * (h.point_count - h.strand_count), 3)
    smooth = weft.generate_hair(30, 30 * 20, droop=0.5)  # tangents close to segment directions
    tri = smooth.ribbon_indices()
    v = smooth.ribbons(eye, 0.01).astype(np.float64)
    a, b, c = v[tri[:, 0]], v[tri[:, 1]], v[tri[:, 2]]
    normal = np.cross(b - a, c - a)
    facing = np.sum(normal * (np.asarray(eye) - a), axis=1) > 0
    assert facing.mean() > 0.99  # a few flip where a strand turns through the view direction


def test_degenerate_tangents() -> None:
    pts = np.array([[0, 0, 0], [0, 0, 0], [0, 0, 1], [5, 5, 5], [5, 5, 5], [1, 1, 1]], float)
    h = weft.HairStrands(pts, [2, 1, 0])
    t = h.tangents()
    assert np.all(np.isfinite(t))
    np.testing.assert_allclose(t, [[0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 1, 0], [0, 1, 0],
                                   [0, 1, 0]], atol=1e-6)
    r = h.ribbons((0, 0, 1), 1.0)  # the eye on the tangent line: fallback side vector
    assert np.all(np.isfinite(r))
