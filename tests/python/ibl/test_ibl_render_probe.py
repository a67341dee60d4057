"""Dynamic reflection capture (SPEC §1.3, issue 5): the scene rendered into a cube from a
reflective sphere's position and used as its reflection. Each face is checked against an
ordinary render from the same point (90 degree camera, mirrored: cube faces are mirror images),
the sphere's pixels against Fresnel x the capture sampled in NumPy, and the capture's reuse."""

from __future__ import annotations

import numpy as np
import pytest
import weft
from weft.reference import ibl_shading as ref

EYE = (0.0, 0.6, 3.0)
PROBE = np.array([0.0, 0.6, 0.0])
SIZE = 32


def probe_scene(f0: float = 1.0) -> weft.Scene:
    scene = weft.Scene()
    scene.ambient = (0.15, 0.15, 0.15)
    scene.background = (0.1, 0.2, 0.4)
    scene.add_mesh(weft.Mesh.plane(6.0, 6.0), weft.Material(kd=(0.6, 0.5, 0.4)))
    scene.add_mesh(weft.Mesh.box((0.6, 0.6, 0.6)), weft.Material(kd=(0.1, 0.8, 0.2)),
                   transform=translate(1.5, 0.3, -0.5))
    scene.add_mesh(weft.Mesh.box((0.5, 1.2, 0.5)), weft.Material(kd=(0.9, 0.1, 0.1)),
                   transform=translate(-1.2, 0.6, -1.0))
    mirror = weft.Material(kd=(0.0, 0.0, 0.0), reflectivity=(f0, f0, f0), shininess=1e5,
                           dynamic_reflection=True)
    m = translate(*PROBE)
    m[:3, :3] *= 0.5
    scene.add_mesh(weft.Mesh.uv_sphere(1.0, 64, 32), mirror, transform=m)
    scene.add_light(weft.DirectionalLight(direction=(-0.4, -1.0, -0.3), cast_shadows=False))
    return scene


def translate(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = (x, y, z)
    return m


def camera() -> weft.Camera:
    return weft.Camera(position=EYE, target=tuple(PROBE), fov_y=0.8)


# face -> (look direction, up) of an ordinary camera seeing the same square, and whether the
# face's columns run against the camera's (CubeMap.h: +X (1, -v, -u), ..., rows along -Y for
# the side faces)
FACES = {0: ((1, 0, 0), (0, 1, 0)), 1: ((-1, 0, 0), (0, 1, 0)), 4: ((0, 0, 1), (0, 1, 0)),
         5: ((0, 0, -1), (0, 1, 0))}


@pytest.mark.parametrize("face", sorted(FACES))
def test_capture_faces_are_the_scene_seen_from_the_probe(make_renderer, face) -> None:
    scene = probe_scene()
    r = make_renderer(48, 48)
    r.probe_size = SIZE
    r.render(scene, camera())
    cube = r.reflection_probe()
    assert cube.shape == (6, SIZE, SIZE, 4)
    look, up = FACES[face]
    view = weft.Camera(position=tuple(PROBE), target=tuple(PROBE + look), up=up,
                       fov_y=np.pi / 2, near=0.02)
    plain = make_renderer(SIZE, SIZE).render_linear(scene, view)[..., :3]
    got = cube[face, ..., :3][:, ::-1]  # faces mirror the camera's view horizontally
    diff = np.abs(got - plain).max(axis=-1)
    # same rasteriser, transforms composed differently: pixels on silhouettes may flip
    assert np.mean(diff < 1e-3) > 0.97, np.mean(diff < 1e-3)
    assert plain.std() > 0.02  # the face shows something


def test_mirror_sphere_reflects_the_capture_with_fresnel(make_renderer) -> None:
    for f0 in (1.0, 0.1):
        scene = probe_scene(f0)
        r = make_renderer(96, 96)
        r.probe_size = SIZE
        debug = r.render_debug(scene, camera())
        cube = r.reflection_probe()[..., :3].astype(np.float64)
        sphere = debug["mask"] & (debug["instance"] == 3)
        assert sphere.mean() > 0.05
        p, n = debug["position"][sphere], debug["normal"][sphere]
        v = np.asarray(EYE) - p
        v /= np.linalg.norm(v, axis=1, keepdims=True)
        ndv = np.einsum("nk,nk->n", n, v)
        rdir = 2.0 * ndv[:, None] * n - v
        fresnel = f0 + (1.0 - f0) * (1.0 - np.clip(ndv, 0.0, 1.0))[:, None] ** 5
        # plus the ambient term I_A K_A T = 0.15 (K_A = 1, T = white); no light: kd = ks = 0
        want = fresnel * ref.sample_face_bilinear(cube, rdir) + 0.15
        got = debug["linear"][sphere][:, :3]
        err = np.abs(got - want).max(axis=-1)
        # bilinear lookups of a 32^2 capture with hard edges (boxes, horizon): a tiny change
        # of R near an edge moves the value a lot; most pixels agree to float precision
        assert np.median(err) < 1e-4 and np.mean(err < 1.0 / 255.0) > 0.95, (
            f0, np.median(err), np.mean(err < 1.0 / 255.0))


def test_capture_is_redone_only_when_the_scene_changes(make_renderer) -> None:
    scene = probe_scene()
    r = make_renderer(32, 32)
    r.probe_size = 16
    probe_passes = lambda: [p["name"] for p in r.stats["passes"] if p["name"].startswith("probe")]  # noqa: E731
    first = r.render_linear(scene, camera())
    assert probe_passes() == [f"probe[{f}]" for f in range(6)]
    np.testing.assert_array_equal(first, r.render_linear(scene, camera()))
    assert probe_passes() == [] and "probe" in r.stats["reused"]
    scene.set_transform(1, translate(1.2, 0.3, 0.8))  # the green box moves
    moved = r.render_linear(scene, camera())
    assert len(probe_passes()) == 6 and not np.array_equal(first, moved)
    plain = weft.Scene()
    plain.add_mesh(weft.Mesh.plane(2.0, 2.0))
    r.render(plain, camera())
    assert probe_passes() == [] and "probe" not in r.stats["reused"]
    with pytest.raises(weft.InvalidArgument):
        r.reflection_probe()
    with pytest.raises(weft.InvalidArgument):
        weft.Material(dynamic_reflection=True)  # nothing to weight the reflection with
    with pytest.raises(weft.InvalidArgument):
        r.probe_size = 2
