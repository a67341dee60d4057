"""weft.Mesh without normals or UVs computes them: angle-weighted normals checked against the
analytic normals of shapes and against trimesh's vertex_normals (an independent implementation
of the same weighting); the planar UV fallback as documented."""

from __future__ import annotations

import numpy as np
import pytest
import weft


def _sphere(radius: float = 1.0):
    m = weft.Mesh.uv_sphere(radius, 48, 24)
    return m.positions, m.indices


def test_sphere_normals_are_the_radial_direction():
    positions, faces = _sphere(2.0)
    mesh = weft.Mesh(positions, indices=faces)
    used = np.unique(faces)  # uv_sphere leaves one seam vertex at each pole unused
    radial = positions[used] / np.linalg.norm(positions[used], axis=1, keepdims=True)
    cos = np.sum(mesh.normals[used] * radial, axis=1)
    # The seam is split, so seam vertices see the triangles of one side only (tilted by about
    # half a segment, 3.75 degrees); elsewhere the smooth normal is within a fraction of a degree.
    assert cos.min() > np.cos(np.radians(4.0))
    assert np.median(cos) > np.cos(np.radians(0.25))
    np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, atol=1e-5)


def test_normals_are_angle_weighted():
    # Vertex 0 is shared by a triangle facing +Z (angle 90 degrees at vertex 0) and one facing
    # -X (angle 45 degrees at vertex 0); the areas (8 and 0.5) would weigh them otherwise.
    p = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0],           # +Z, right angle at vertex 0
                  [0, 0, 1], [0, 1, 1]], np.float32)          # -X, 45 degrees at vertex 0
    faces = np.array([[0, 1, 2], [0, 3, 4]], np.uint32)
    n0 = weft.Mesh(p, indices=faces).normals[0]
    expected = np.array([-np.pi / 4, 0.0, np.pi / 2])
    np.testing.assert_allclose(n0, expected / np.linalg.norm(expected), atol=1e-6)


def test_splitting_a_face_does_not_change_the_normal():
    # A unit square facing +Z as 2 triangles and one facing +X as 1 or 4 triangles (a fan from
    # the shared corner): angle weights give the same normal at the shared corner both ways.
    def corner_normal(split):
        p = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],       # +Z square
             [0, 0, -1], [0, 1, -1]]                            # -X square with 0, 3
        f = [[0, 1, 2], [0, 2, 3]]
        if split:
            p += [[0, 0.5, -1], [0, 1, -0.5], [0, 0.25, -0.5]]
            f += [[0, 3, 7], [0, 7, 5], [0, 5, 6], [0, 6, 4]]
        else:
            f += [[0, 3, 5], [0, 5, 4]]
        return weft.Mesh(np.array(p, np.float32), indices=np.array(f)).normals[0]
    np.testing.assert_allclose(corner_normal(True), corner_normal(False), atol=1e-6)


def test_normals_match_trimesh():
    trimesh = pytest.importorskip("trimesh")
    positions, faces = _sphere(1.0)
    box = weft.Mesh.box((1.0, 2.0, 3.0))
    for pos, tri in ((positions, faces), (box.positions, box.indices)):
        ours = weft.Mesh(pos, indices=tri).normals
        tm = trimesh.Trimesh(vertices=pos, faces=tri, process=False)
        # trimesh's vertex_normals: face normals weighted by the corner angles, normalised
        theirs = np.asarray(tm.vertex_normals)
        used = np.unique(tri)  # trimesh leaves unused vertices at zero, weft gives them +Y
        assert len(used) > 0.9 * len(pos)
        np.testing.assert_allclose(ours[used], theirs[used], atol=1e-5)


def test_given_attributes_are_kept():
    plane = weft.Mesh.plane(2.0, 1.0, 3, 2)
    again = weft.Mesh(plane.positions, plane.normals, plane.uvs, plane.indices)
    np.testing.assert_array_equal(again.normals, plane.normals)
    np.testing.assert_array_equal(again.uvs, plane.uvs)


def test_planar_uvs_of_a_flat_xz_patch_match_mesh_plane():
    plane = weft.Mesh.plane(2.0, 1.0, 4, 2)
    mesh = weft.Mesh(plane.positions, normals=plane.normals, indices=plane.indices)
    x, z = plane.positions[:, 0], plane.positions[:, 2]
    np.testing.assert_allclose(mesh.uvs[:, 0], (x + 1.0) / 2.0, atol=1e-6)
    np.testing.assert_allclose(mesh.uvs[:, 1], (z + 0.5) / 2.0, atol=1e-6)
    assert mesh.uvs[:, 0].max() == pytest.approx(1.0)


def test_an_isolated_vertex_gets_a_unit_normal():
    p = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [5, 5, 5]], np.float32)
    mesh = weft.Mesh(p, indices=np.array([[0, 1, 2]]))
    np.testing.assert_allclose(mesh.normals[3], [0, 1, 0])
    np.testing.assert_allclose(mesh.normals[0], [0, 0, 1], atol=1e-6)


def test_bad_input_is_a_clear_error():
    p = np.zeros((3, 3), np.float32)
    with pytest.raises(weft.InvalidArgument, match="indices"):
        weft.Mesh(p)
    with pytest.raises(weft.InvalidArgument, match="out of range"):
        weft.Mesh(np.eye(3, dtype=np.float32), indices=np.array([[0, 1, 7]]))
    with pytest.raises(weft.InvalidArgument, match="multiple of 3"):
        weft.Mesh(np.eye(3, dtype=np.float32), indices=np.array([0, 1, 2, 0]))
