"""The Python API: devices, value types, meshes, files, camera matrices, and clean exceptions
(never a crash) for bad input."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
import weft
from weft import Error, InvalidArgument, IoError

NAN = float("nan")
INF = float("inf")


def quad_arrays():
    positions = np.array([[0, 0, 0], [1, 0, 0], [1, 0, -1], [0, 0, -1]], dtype=np.float32)
    normals = np.tile(np.array([0, 1, 0], dtype=np.float32), (4, 1))
    uvs = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=np.float32)
    indices = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)
    return positions, normals, uvs, indices


# --------------------------------------------------------------------------------------------
# Module, devices, exceptions
# --------------------------------------------------------------------------------------------

def test_exception_hierarchy() -> None:
    assert issubclass(Error, RuntimeError)
    assert issubclass(InvalidArgument, Error) and issubclass(InvalidArgument, ValueError)
    assert issubclass(IoError, Error) and issubclass(IoError, OSError)


def test_version_and_all() -> None:
    assert isinstance(weft.__version__, str) and weft.__version__
    for name in weft.__all__:
        assert hasattr(weft, name), name


def test_devices_one_selected() -> None:
    devices = weft.devices()
    assert len(devices) >= 1
    assert sum(1 for d in devices if d["selected"]) == 1
    for d in devices:
        assert {"index", "name", "type", "api_version", "driver", "selected"} <= set(d)
        assert d["type"] in ("discrete", "integrated", "virtual", "cpu", "other")
        assert isinstance(d["name"], str) and d["name"]
    selected = next(d for d in devices if d["selected"])
    assert weft.Renderer(8, 8).device_name == selected["name"]


def test_validation_layers_are_on() -> None:
    assert os.environ.get("WEFT_VALIDATION") == "1"
    assert weft.validation_enabled(), \
        "WEFT_VALIDATION=1 but the validation layers are not active (is " \
        "vulkan-validationlayers installed?)"
    assert isinstance(weft.validation_messages(), list)


# --------------------------------------------------------------------------------------------
# Meshes
# --------------------------------------------------------------------------------------------

def _check_ccw_outward(mesh: weft.Mesh, centre=np.zeros(3)) -> None:
    p = mesh.positions.astype(np.float64)
    tri = mesh.indices.astype(np.int64)
    a, b, c = p[tri[:, 0]], p[tri[:, 1]], p[tri[:, 2]]
    face_n = np.cross(b - a, c - a)
    outward = (a + b + c) / 3.0 - centre
    assert np.all(np.einsum("ij,ij->i", face_n, outward) > 0.0)


def test_mesh_from_arrays_and_copies() -> None:
    positions, normals, uvs, indices = quad_arrays()
    mesh = weft.Mesh(positions, normals, uvs, indices)
    assert mesh.vertex_count == 4 and mesh.triangle_count == 2
    assert mesh.positions.shape == (4, 3) and mesh.positions.dtype == np.float32
    assert mesh.normals.shape == (4, 3) and mesh.uvs.shape == (4, 2)
    assert mesh.indices.shape == (2, 3) and mesh.indices.dtype == np.uint32
    assert np.array_equal(mesh.positions, positions)
    assert np.array_equal(mesh.indices, indices)
    got = mesh.positions
    got[:] = 7.0
    assert np.array_equal(mesh.positions, positions), "positions must be a copy"
    positions[:] = 5.0
    assert not np.any(mesh.positions == 5.0), "the mesh must not alias the input"


def test_builtin_meshes() -> None:
    plane = weft.Mesh.plane(2.0, 3.0, 2, 2)
    assert plane.vertex_count == 9 and plane.triangle_count == 8
    p = plane.positions
    assert np.allclose(p[:, 1], 0.0)
    assert np.isclose(p[:, 0].min(), -1.0) and np.isclose(p[:, 0].max(), 1.0)
    assert np.isclose(p[:, 2].min(), -1.5) and np.isclose(p[:, 2].max(), 1.5)
    assert np.allclose(plane.normals, [0.0, 1.0, 0.0])
    assert np.allclose(plane.uvs[:, 0], p[:, 0] / 2.0 + 0.5, atol=1e-6)   # u along +X
    assert np.allclose(plane.uvs[:, 1], p[:, 2] / 3.0 + 0.5, atol=1e-6)   # v along +Z
    tri = plane.indices.astype(np.int64)
    n = np.cross(p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]])
    assert np.all(n[:, 1] > 0.0), "plane triangles must be counter-clockwise seen from +Y"

    sphere = weft.Mesh.uv_sphere(0.75, 24, 12)
    r = np.linalg.norm(sphere.positions, axis=1)
    assert np.allclose(r, 0.75, atol=1e-5)
    assert np.allclose(sphere.normals, sphere.positions / r[:, None], atol=1e-5)
    _check_ccw_outward(sphere)

    box = weft.Mesh.box((1.0, 2.0, 3.0))
    assert box.vertex_count == 24 and box.triangle_count == 12
    assert np.allclose(np.abs(box.positions), [0.5, 1.0, 1.5])
    assert np.allclose(np.linalg.norm(box.normals, axis=1), 1.0)
    _check_ccw_outward(box)


@pytest.mark.parametrize("what", [
    "positions_2d", "positions_1d", "normals_count", "uvs_shape", "indices_shape",
    "indices_range", "positions_nan", "normals_inf", "empty"])
def test_mesh_bad_input(what: str) -> None:
    positions, normals, uvs, indices = quad_arrays()
    if what == "positions_2d":
        positions = positions[:, :2].copy()
    elif what == "positions_1d":
        positions = positions.reshape(-1)
    elif what == "normals_count":
        normals = normals[:3].copy()
    elif what == "uvs_shape":
        uvs = np.zeros((4, 3), dtype=np.float32)
    elif what == "indices_shape":
        indices = np.array([[0, 1], [2, 3]], dtype=np.uint32)
    elif what == "indices_range":
        indices = np.array([[0, 1, 2], [0, 2, 4]], dtype=np.uint32)
    elif what == "positions_nan":
        positions[1, 0] = NAN
    elif what == "normals_inf":
        normals[2, 1] = INF
    elif what == "empty":
        positions = np.zeros((0, 3), dtype=np.float32)
        normals = np.zeros((0, 3), dtype=np.float32)
        uvs = np.zeros((0, 2), dtype=np.float32)
        indices = np.zeros((0, 3), dtype=np.uint32)
    with pytest.raises(InvalidArgument):
        weft.Mesh(positions, normals, uvs, indices)


def test_mesh_bad_dtypes() -> None:
    positions, normals, uvs, indices = quad_arrays()
    with pytest.raises((TypeError, ValueError)):
        weft.Mesh(np.array([["a", "b", "c"]] * 4), normals, uvs, indices)
    with pytest.raises((TypeError, ValueError)):
        weft.Mesh(positions.astype(np.complex64) + 1j, normals, uvs, indices)
    with pytest.raises((TypeError, ValueError)):
        weft.Mesh(positions, normals, uvs, np.array([[0, 1, 2], [0, -2, 3]], dtype=np.int64))
    with pytest.raises((TypeError, ValueError)):
        weft.Mesh(positions, normals, uvs, np.array([[0, 1, 2], [0, 2.5, 3]]))


def test_builtin_mesh_bad_parameters() -> None:
    with pytest.raises(InvalidArgument):
        weft.Mesh.plane(0.0, 1.0)
    with pytest.raises(InvalidArgument):
        weft.Mesh.plane(1.0, 1.0, 0, 1)
    with pytest.raises(InvalidArgument):
        weft.Mesh.uv_sphere(NAN)
    with pytest.raises(InvalidArgument):
        weft.Mesh.uv_sphere(1.0, 2, 1)
    with pytest.raises(InvalidArgument):
        weft.Mesh.box((1.0, -1.0, 1.0))


# --------------------------------------------------------------------------------------------
# Textures, materials, lights, camera, scene
# --------------------------------------------------------------------------------------------

def test_texture_shapes() -> None:
    for shape in [(4, 6), (4, 6, 1), (4, 6, 2), (4, 6, 3), (4, 6, 4)]:
        tex = weft.Texture(np.zeros(shape, dtype=np.uint8))
        assert (tex.height, tex.width) == (4, 6)
    tex = weft.Texture(np.zeros((3, 5, 3), dtype=np.uint8), srgb=False, mipmaps=False)
    assert (tex.height, tex.width) == (3, 5)


@pytest.mark.parametrize("image", [
    np.zeros((4, 4, 5), dtype=np.uint8), np.zeros((4, 4, 0), dtype=np.uint8),
    np.zeros((2, 4, 4, 3), dtype=np.uint8), np.zeros((0, 4, 3), dtype=np.uint8),
    np.zeros(16, dtype=np.uint8)])
def test_texture_bad_shape(image: np.ndarray) -> None:
    with pytest.raises(InvalidArgument):
        weft.Texture(image)


def test_texture_bad_dtype() -> None:
    with pytest.raises((TypeError, ValueError)):
        weft.Texture(np.full((4, 4, 3), 0.5, dtype=np.float32))
    with pytest.raises((TypeError, ValueError)):
        weft.Texture(np.full((4, 4, 3), 300, dtype=np.int32))


def test_material_properties() -> None:
    tex = weft.Texture(np.full((2, 2, 3), 200, dtype=np.uint8))
    m = weft.Material(ka=(0.1, 0.2, 0.3), kd=(0.4, 0.5, 0.6), ks=(0.7, 0.8, 0.9), shininess=40.0,
                      base_color=(0.5, 0.25, 1.0), texture=tex)
    assert m.ka == pytest.approx((0.1, 0.2, 0.3))
    assert m.kd == pytest.approx((0.4, 0.5, 0.6))
    assert m.ks == pytest.approx((0.7, 0.8, 0.9))
    assert m.shininess == pytest.approx(40.0)
    assert m.base_color == pytest.approx((0.5, 0.25, 1.0))
    assert m.texture is not None and m.texture.width == 2
    m.kd = (1.0, 0.0, 0.0)
    m.shininess = 8.0
    m.texture = None
    assert m.kd == pytest.approx((1.0, 0.0, 0.0)) and m.shininess == pytest.approx(8.0)
    assert m.texture is None
    d = weft.Material()
    assert d.ka == pytest.approx((1, 1, 1)) and d.ks == pytest.approx((0, 0, 0))
    assert d.shininess == pytest.approx(32.0)


@pytest.mark.parametrize("kwargs", [dict(kd=(-0.1, 0.0, 0.0)), dict(ks=(NAN, 0.0, 0.0)),
                                    dict(shininess=0.0), dict(shininess=INF)])
def test_material_bad_values(kwargs) -> None:
    scene = weft.Scene()
    with pytest.raises(InvalidArgument):
        scene.add_mesh(weft.Mesh.box(), weft.Material(**kwargs))


def test_light_properties_and_bad_values() -> None:
    light = weft.DirectionalLight()
    assert light.direction == pytest.approx((0.0, -1.0, 0.0))
    assert light.color == pytest.approx((1.0, 1.0, 1.0))
    assert light.intensity == pytest.approx(1.0) and light.cast_shadows is True
    scene = weft.Scene()
    for kwargs in [dict(direction=(NAN, -1.0, 0.0)), dict(direction=(0.0, 0.0, 0.0)),
                   dict(direction=(0.0, INF, 0.0)), dict(color=(-1.0, 0.0, 0.0)),
                   dict(intensity=NAN)]:
        with pytest.raises(InvalidArgument):
            scene.add_light(weft.DirectionalLight(**kwargs))
    lid = scene.add_light(weft.DirectionalLight(direction=(1.0, -1.0, 0.0), intensity=2.0))
    with pytest.raises(InvalidArgument):
        scene.set_light(lid, weft.DirectionalLight(direction=(0.0, NAN, 0.0)))
    assert scene.lights[lid].intensity == pytest.approx(2.0)


@pytest.mark.parametrize("kwargs", [
    dict(position=(NAN, 1.0, 4.0)), dict(target=(0.0, INF, 0.0)), dict(up=(0.0, NAN, 0.0)),
    dict(position=(0.0, 0.0, 0.0), target=(0.0, 0.0, 0.0)), dict(up=(0.0, 0.0, -1.0),
                                                                  position=(0.0, 0.0, 4.0)),
    dict(fov_y=0.0), dict(fov_y=math.pi), dict(fov_y=NAN), dict(near=0.0),
    dict(near=10.0, far=1.0)])
def test_camera_bad_values(kwargs) -> None:
    scene, _ = weft.default_scene()
    renderer = weft.Renderer(16, 16, shadow_map_size=256)
    with pytest.raises(InvalidArgument):
        camera = weft.Camera(**kwargs)
        renderer.render(scene, camera)
    # the renderer is still usable afterwards
    assert renderer.render(scene, weft.Camera()).shape == (16, 16, 4)


def test_camera_matrices() -> None:
    cam = weft.Camera(position=(1.0, 2.0, 5.0), target=(0.0, 0.5, 0.0), fov_y=0.9, near=0.1,
                      far=50.0)
    view = cam.view_matrix()
    proj = cam.projection_matrix(2.0)
    assert view.shape == (4, 4) and view.dtype == np.float32
    assert proj.shape == (4, 4) and proj.dtype == np.float32
    eye = np.array([1.0, 2.0, 5.0, 1.0])
    target = np.array([0.0, 0.5, 0.0, 1.0])
    assert np.allclose(view @ eye, [0, 0, 0, 1], atol=1e-5)
    t_view = view @ target
    dist = np.linalg.norm(eye[:3] - target[:3])
    assert np.allclose(t_view, [0.0, 0.0, -dist, 1.0], atol=1e-5)  # right-handed, looks down -z

    def ndc(world):
        c = proj @ view @ np.append(world, 1.0)
        return c[:3] / c[3]

    assert np.allclose(ndc(target[:3])[:2], 0.0, atol=1e-5)
    forward = (target[:3] - eye[:3]) / dist
    assert ndc(eye[:3] + forward * 0.1)[2] == pytest.approx(0.0, abs=1e-5)    # near -> 0
    assert ndc(eye[:3] + forward * 50.0)[2] == pytest.approx(1.0, abs=1e-4)   # far -> 1
    assert 0.0 < ndc(target[:3])[2] < 1.0
    # Vulkan: +Y world (up on screen) has negative NDC y
    up_point = target[:3] + np.array([0.0, 0.3, 0.0])
    assert ndc(up_point)[1] < 0.0
    # vertical field of view and aspect
    assert proj[1, 1] == pytest.approx(-1.0 / math.tan(0.45), rel=1e-5) or \
        proj[1, 1] == pytest.approx(1.0 / math.tan(0.45), rel=1e-5)
    assert abs(proj[0, 0]) == pytest.approx(abs(proj[1, 1]) / 2.0, rel=1e-5)


def test_camera_matrices_match_rendered_positions() -> None:
    """World positions from render_debug project back onto their own pixel centres."""
    scene, camera = weft.default_scene()
    width, height = 80, 60
    renderer = weft.Renderer(width, height, shadow_map_size=256)
    debug = renderer.render_debug(scene, camera)
    mask = debug["mask"]
    rows, cols = np.nonzero(mask)
    world = debug["position"][mask].astype(np.float64)
    vp = camera.projection_matrix(width / height).astype(np.float64) @ \
        camera.view_matrix().astype(np.float64)
    clip = world @ vp[:, :3].T + vp[:, 3]
    ndc = clip[:, :2] / clip[:, 3:4]
    px = (ndc[:, 0] * 0.5 + 0.5) * width
    py = (ndc[:, 1] * 0.5 + 0.5) * height
    assert np.abs(px - (cols + 0.5)).max() < 0.05
    assert np.abs(py - (rows + 0.5)).max() < 0.05


def test_scene_api() -> None:
    scene = weft.Scene()
    assert scene.instance_count == 0 and scene.lights == []
    a = scene.add_mesh(weft.Mesh.box((2.0, 2.0, 2.0)))
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = (5.0, 0.0, 0.0)
    b = scene.add_mesh(weft.Mesh.box(), weft.Material(kd=(0.5, 0.5, 0.5)), m, cast_shadows=False)
    assert (a, b) == (0, 1) and scene.instance_count == 2
    lo, hi = scene.bounds()
    assert np.allclose(lo, (-1.0, -1.0, -1.0)) and np.allclose(hi, (5.5, 1.0, 1.0))
    m[:3, 3] = (0.0, 3.0, 0.0)
    scene.set_transform(b, m)
    lo, hi = scene.bounds()
    assert np.allclose(hi, (1.0, 3.5, 1.0))
    scene.set_material(a, weft.Material(kd=(0.1, 0.2, 0.3)))
    scene.ambient = (0.3, 0.2, 0.1)
    scene.background = (0.0, 0.5, 1.0)
    assert scene.ambient == pytest.approx((0.3, 0.2, 0.1))
    assert scene.background == pytest.approx((0.0, 0.5, 1.0))
    lid = scene.add_light(weft.DirectionalLight(direction=(0.0, -1.0, -1.0)))
    assert lid == 0 and len(scene.lights) == 1
    scene.set_light(lid, weft.DirectionalLight(color=(1.0, 0.0, 0.0)))
    assert scene.lights[0].color == pytest.approx((1.0, 0.0, 0.0))


def test_default_scene() -> None:
    scene, camera = weft.default_scene()
    assert scene.instance_count >= 3
    assert any(light.cast_shadows for light in scene.lights)
    assert isinstance(camera, weft.Camera)


@pytest.mark.parametrize("bad", [
    np.eye(3, dtype=np.float32), np.eye(4, dtype=np.float32)[:3], np.zeros(16, dtype=np.float32),
    "nan", "inf"])
def test_transform_bad_input(bad) -> None:
    if isinstance(bad, str):
        m = np.eye(4, dtype=np.float32)
        m[1, 3] = NAN if bad == "nan" else INF
        bad = m
    scene = weft.Scene()
    with pytest.raises(InvalidArgument):
        scene.add_mesh(weft.Mesh.box(), weft.Material(), bad)
    good = scene.add_mesh(weft.Mesh.box())
    with pytest.raises(InvalidArgument):
        scene.set_transform(good, bad)
    assert scene.instance_count == 1


def test_transform_bad_dtype_and_ids() -> None:
    scene = weft.Scene()
    with pytest.raises((TypeError, ValueError)):
        scene.add_mesh(weft.Mesh.box(), weft.Material(), np.full((4, 4), "x"))
    with pytest.raises((ValueError, IndexError)):
        scene.set_transform(3, np.eye(4, dtype=np.float32))
    with pytest.raises((ValueError, IndexError)):
        scene.set_material(0, weft.Material())
    with pytest.raises((ValueError, IndexError)):
        scene.set_light(0, weft.DirectionalLight())


# --------------------------------------------------------------------------------------------
# Renderer settings and sizes
# --------------------------------------------------------------------------------------------

def test_renderer_properties_round_trip() -> None:
    r = weft.Renderer(32, 24, shadow_map_size=1024, pcf_radius=2, bias_constant=0.001,
                      bias_slope=0.002, bias_max=0.02, normal_offset=1.0)
    assert (r.width, r.height) == (32, 24)
    assert r.shadow_map_size == 1024 and r.pcf_radius == 2
    assert r.bias_constant == pytest.approx(0.001) and r.bias_slope == pytest.approx(0.002)
    assert r.bias_max == pytest.approx(0.02) and r.normal_offset == pytest.approx(1.0)
    r.pcf_radius = 3
    r.shadow_map_size = 512
    assert r.pcf_radius == 3 and r.shadow_map_size == 512
    r.resize(40, 20)
    assert (r.width, r.height) == (40, 20)
    scene, camera = weft.default_scene()
    assert r.render(scene, camera).shape == (20, 40, 4)
    assert r.shadow_info(0)["size"] == 512 and r.shadow_info(0)["pcf_radius"] == 3
    assert r.shadow_map(0).shape == (512, 512)


@pytest.mark.parametrize("size", [(0, 16), (16, 0), (0, 0)])
def test_zero_size_renderer(size) -> None:
    with pytest.raises(InvalidArgument):
        weft.Renderer(*size)
    r = weft.Renderer(16, 12, shadow_map_size=256)
    with pytest.raises(InvalidArgument):
        r.resize(*size)
    assert (r.width, r.height) == (16, 12)
    scene, camera = weft.default_scene()
    assert r.render(scene, camera).shape == (12, 16, 4)


def test_negative_and_huge_sizes() -> None:
    with pytest.raises((InvalidArgument, TypeError, OverflowError)):
        weft.Renderer(-4, 16)
    with pytest.raises(Error):
        r = weft.Renderer(1 << 20, 8)
        scene, camera = weft.default_scene()
        r.render(scene, camera)


@pytest.mark.parametrize("kwargs", [dict(pcf_radius=-1), dict(pcf_radius=8),
                                    dict(shadow_map_size=0), dict(bias_constant=NAN),
                                    dict(bias_max=-1.0), dict(normal_offset=INF)])
def test_renderer_bad_settings(kwargs) -> None:
    with pytest.raises(InvalidArgument):
        weft.Renderer(16, 16, **kwargs)
    r = weft.Renderer(16, 16, shadow_map_size=256, pcf_radius=1)
    name, value = next(iter(kwargs.items()))
    before = getattr(r, name)
    with pytest.raises(InvalidArgument):
        setattr(r, name, value)
    assert getattr(r, name) == before


def test_shadow_info_bad_index() -> None:
    scene, camera = weft.default_scene()
    r = weft.Renderer(16, 16, shadow_map_size=256)
    r.render(scene, camera)
    with pytest.raises((ValueError, IndexError)):
        r.shadow_map(99)
    with pytest.raises((ValueError, IndexError)):
        r.shadow_info(-5)


def test_render_empty_scene() -> None:
    """Nothing to draw is not an error: every pixel is background."""
    scene = weft.Scene()
    scene.background = (0.25, 0.5, 0.75)
    r = weft.Renderer(16, 8, shadow_map_size=256)
    debug = r.render_debug(scene, weft.Camera())
    assert not debug["mask"].any()
    assert np.allclose(debug["linear"][..., :3], (0.25, 0.5, 0.75), atol=1e-6)


# --------------------------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------------------------

OBJ_QUAD = """# a unit quad in the XZ plane, facing +Y
o quad
v 0 0 0
v 1 0 0
v 1 0 -1
v 0 0 -1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 1 0
g ignored
usemtl ignored
s off
f 1/1/1 2/2/1 3/3/1 4/4/1
"""


def test_load_obj(tmp_path) -> None:
    path = tmp_path / "quad.obj"
    path.write_text(OBJ_QUAD)
    mesh = weft.load_obj(str(path))
    assert mesh.triangle_count == 2
    corners = {tuple(np.round(p, 5)) for p in mesh.positions}
    assert corners == {(0, 0, 0), (1, 0, 0), (1, 0, -1), (0, 0, -1)}
    assert np.allclose(mesh.normals, (0.0, 1.0, 0.0))
    by_pos = {tuple(np.round(p, 5)): tuple(np.round(t, 5)) for p, t in zip(mesh.positions,
                                                                           mesh.uvs)}
    # OBJ's vt has v = 0 at the bottom of the image, weft's uv (0, 0) is the top-left texel
    assert by_pos[(1, 0, -1)] == (1, 0)
    assert by_pos[(0, 0, 0)] == (0, 1)


def test_load_obj_negative_indices_and_missing_normals(tmp_path) -> None:
    path = tmp_path / "tri.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 1 0 -1\nf -3 -2 -1\n")
    mesh = weft.load_obj(str(path))
    assert mesh.triangle_count == 1 and mesh.vertex_count == 3
    assert np.allclose(mesh.normals, (0.0, 1.0, 0.0), atol=1e-6)  # computed, CCW -> +Y
    assert np.allclose(mesh.uvs, 0.0)


@pytest.mark.parametrize("text", ["v 0 0 0\nv 1 0 0\nv 1 0 -1\nf 1 2 9\n",
                                  "v 0 0 1e999\nf 1 1 1\n",
                                  "v 0 0 0\nv 1 0 0\nv 1 0 -1\nf 1/1 2\n",
                                  "v 0 0 0\nv 1 0 0\nv 1 0 -1\nf x 2 3\n"])
def test_load_obj_malformed(tmp_path, text: str) -> None:
    path = tmp_path / "bad.obj"
    path.write_text(text)
    with pytest.raises(IoError, match="bad.obj:"):
        weft.load_obj(str(path))


def test_load_obj_reads_numbers_as_tinyobjloader_does(tmp_path) -> None:
    """Words that are no number read as 0 (a missing z, a texture index 'x'): accepted now."""
    path = tmp_path / "words.obj"
    path.write_text("v 0 0\nv 1 0 0\nv 1 0 -1\nf 1/x 2 3\n")
    mesh = weft.load_obj(str(path))
    assert mesh.triangle_count == 1
    assert {tuple(p) for p in mesh.positions} == {(0, 0, 0), (1, 0, 0), (1, 0, -1)}


def test_missing_files(tmp_path) -> None:
    missing = str(tmp_path / "does_not_exist")
    with pytest.raises(IoError):
        weft.load_obj(missing + ".obj")
    with pytest.raises(OSError):
        weft.load_png(missing + ".png")
    with pytest.raises(IoError):
        weft.Texture.load(missing + ".png")
    garbage = tmp_path / "garbage.png"
    garbage.write_bytes(b"this is not a PNG file at all")
    with pytest.raises(IoError):
        weft.load_png(str(garbage))
    with pytest.raises(IoError):
        weft.Texture.load(str(garbage))


@pytest.mark.parametrize("shape", [(5, 7), (5, 7, 1), (5, 7, 2), (5, 7, 3), (5, 7, 4)])
def test_png_round_trip(tmp_path, shape) -> None:
    rng = np.random.default_rng(3)
    image = rng.integers(0, 256, size=shape, dtype=np.uint8)
    path = str(tmp_path / "img.png")
    weft.save_png(path, image)
    loaded = weft.load_png(path)
    assert loaded.dtype == np.uint8 and loaded.ndim == 3
    assert loaded.shape[:2] == shape[:2]
    assert np.array_equal(loaded.reshape(image.shape), image)
    tex = weft.Texture.load(path, srgb=False, mipmaps=False)
    assert (tex.height, tex.width) == shape[:2]


def test_save_png_bad_input(tmp_path) -> None:
    with pytest.raises(InvalidArgument):
        weft.save_png(str(tmp_path / "a.png"), np.zeros((4, 4, 5), dtype=np.uint8))
    with pytest.raises((TypeError, ValueError)):
        weft.save_png(str(tmp_path / "b.png"), np.zeros((4, 4, 3), dtype=np.float32))


# --------------------------------------------------------------------------------------------
# Representations
# --------------------------------------------------------------------------------------------

def test_reprs() -> None:
    scene, camera = weft.default_scene()
    objects = {
        "Mesh": weft.Mesh.box(),
        "Texture": weft.Texture(np.zeros((2, 3, 3), dtype=np.uint8)),
        "Material": weft.Material(),
        "DirectionalLight": weft.DirectionalLight(),
        "Camera": camera,
        "Scene": scene,
        "Renderer": weft.Renderer(8, 8, shadow_map_size=256),
    }
    for name, obj in objects.items():
        text = repr(obj)
        assert name in text, f"repr of {name} is {text!r}"
        assert "object at 0x" not in text
