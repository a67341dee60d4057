"""weft.load_gltf on glTF 2.0 files written by pygltflib and trimesh (independent writers), with
trimesh as the independent reader of the same files: geometry, node transforms, flat normals
when the file has none, the material mapping, the base colour texture as rendered, and clear
IoErrors for broken files."""

from __future__ import annotations

import json
import struct
from pathlib import Path

import numpy as np
import pytest
import weft

pygltflib = pytest.importorskip("pygltflib")
trimesh = pytest.importorskip("trimesh")

FLOAT, USHORT = 5126, 5123


def png_bytes(tmp_path: Path, image: np.ndarray) -> bytes:
    path = tmp_path / "texture.png"
    weft.save_png(str(path), image)
    return path.read_bytes()


def quad_arrays():
    positions = np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]], np.float32)
    normals = np.tile(np.array([0, 1, 0], np.float32), (4, 1))
    uvs = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], np.float32)
    indices = np.array([0, 2, 1, 0, 3, 2], np.uint16)  # counter-clockwise seen from +Y
    return positions, normals, uvs, indices


def write_gltf(path: Path, positions, indices, normals=None, uvs=None, png=None, material=None,
               node=None, texture_extensions=None, mode=4, binary=None) -> Path:
    """One mesh with one primitive through pygltflib; `material` holds pbrMetallicRoughness
    fields plus alphaMode/alphaCutoff/doubleSided; `node` holds Node fields."""
    g = pygltflib
    blob = b""
    views, accessors = [], []

    def add(data: np.ndarray, type_: str, component: int, target=None) -> int:
        nonlocal blob
        while len(blob) % 4:
            blob += b"\0"
        raw = data.tobytes()
        views.append(g.BufferView(buffer=0, byteOffset=len(blob), byteLength=len(raw),
                                  target=target))
        blob += raw
        if type_ == "image":
            return len(views) - 1
        kw = {}
        if type_ == "VEC3" and component == FLOAT:
            kw = dict(min=data.min(axis=0).tolist(), max=data.max(axis=0).tolist())
        accessors.append(g.Accessor(bufferView=len(views) - 1, componentType=component,
                                    count=len(data), type=type_, **kw))
        return len(accessors) - 1

    attributes = g.Attributes(POSITION=add(positions, "VEC3", FLOAT, g.ARRAY_BUFFER))
    if normals is not None:
        attributes.NORMAL = add(normals, "VEC3", FLOAT, g.ARRAY_BUFFER)
    if uvs is not None:
        attributes.TEXCOORD_0 = add(uvs, "VEC2", FLOAT, g.ARRAY_BUFFER)
    index_accessor = add(indices, "SCALAR", USHORT, g.ELEMENT_ARRAY_BUFFER)
    images, textures, samplers = [], [], []
    mat = dict(material or {})
    pbr = g.PbrMetallicRoughness(**{k: v for k, v in mat.items()
                                    if k in ("baseColorFactor", "metallicFactor",
                                             "roughnessFactor")})
    if png is not None:
        view = add(np.frombuffer(png, np.uint8), "image", 0)
        images.append(g.Image(bufferView=view, mimeType="image/png"))
        samplers.append(g.Sampler())
        textures.append(g.Texture(source=0, sampler=0))
        pbr.baseColorTexture = g.TextureInfo(index=0, extensions=texture_extensions or {})
    gm = g.Material(pbrMetallicRoughness=pbr, alphaMode=mat.get("alphaMode", "OPAQUE"),
                    alphaCutoff=mat.get("alphaCutoff"), doubleSided=mat.get("doubleSided", False))
    gltf = g.GLTF2(
        scene=0, scenes=[g.Scene(nodes=[0])], nodes=[g.Node(mesh=0, **(node or {}))],
        meshes=[g.Mesh(name="quad", primitives=[g.Primitive(attributes=attributes,
                                                            indices=index_accessor,
                                                            material=0, mode=mode)])],
        materials=[gm], accessors=accessors, bufferViews=views,
        buffers=[g.Buffer(byteLength=len(blob))], images=images, textures=textures,
        samplers=samplers)
    if texture_extensions:
        gltf.extensionsUsed = list(texture_extensions)
    gltf.set_binary_blob(blob)
    if binary if binary is not None else path.suffix == ".glb":
        gltf.save_binary(str(path))
    else:
        gltf.convert_buffers(g.BufferFormat.DATAURI)
        gltf.save(str(path))
    return path


def test_quad_geometry_matches_the_file_and_trimesh(tmp_path: Path) -> None:
    positions, normals, uvs, indices = quad_arrays()
    for name in ("quad.gltf", "quad.glb"):
        path = write_gltf(tmp_path / name, positions, indices, normals, uvs)
        (part,) = weft.load_gltf(str(path))
        assert part.name == "quad"
        np.testing.assert_array_equal(part.mesh.positions, positions)
        np.testing.assert_array_equal(part.mesh.normals, normals)
        np.testing.assert_array_equal(part.mesh.uvs, uvs)
        np.testing.assert_array_equal(part.mesh.indices.ravel(), indices)
        theirs = trimesh.load(str(path), force="mesh", process=False)
        np.testing.assert_allclose(part.mesh.positions, theirs.vertices, atol=1e-6)
        np.testing.assert_array_equal(part.mesh.indices.reshape(-1, 3), theirs.faces)


def test_trimesh_scene_with_node_transforms(tmp_path: Path) -> None:
    # trimesh writes the scene graph (node matrices); its own reader flattens it to world space.
    scene = trimesh.Scene()
    box = trimesh.creation.box(extents=(1.0, 2.0, 3.0))
    sphere = trimesh.creation.icosphere(subdivisions=2, radius=0.5)
    moved = trimesh.transformations.compose_matrix(
        translate=(2.0, 0.5, -1.0), angles=(0.3, 0.7, -0.2), scale=(1.5, 1.5, 1.5))
    mirrored = np.diag([-1.0, 1.0, 1.0, 1.0])
    mirrored[:3, 3] = (-3.0, 0.0, 0.0)
    scene.add_geometry(box, node_name="box", geom_name="box", transform=moved)
    scene.add_geometry(sphere, node_name="ball", geom_name="ball", transform=mirrored)
    path = tmp_path / "scene.glb"
    path.write_bytes(scene.export(file_type="glb"))

    parts = {p.name: p for p in weft.load_gltf(str(path))}
    assert set(parts) == {"box", "ball"}
    truth = trimesh.load(str(path), process=False)
    for name, part in parts.items():
        geometry = truth.geometry[name]
        world = trimesh.transform_points(geometry.vertices, truth.graph[name][0])
        # Triangle by triangle (weft unwelds a primitive without normals, and a mirror
        # reverses the corner order): the centroids and the corner sets agree.
        ours = part.mesh.positions[part.mesh.indices.reshape(-1, 3)]
        theirs = world[geometry.faces]
        assert len(ours) == len(theirs)
        np.testing.assert_allclose(ours.mean(axis=1), theirs.mean(axis=1), atol=1e-5)
        np.testing.assert_allclose(np.sort(ours, axis=1), np.sort(theirs, axis=1), atol=1e-5)
        # front faces stay outside, also under the mirror: every triangle's geometric normal
        # points away from the shape's centre
        p = part.mesh.positions
        tri = part.mesh.indices.reshape(-1, 3)
        n = np.cross(p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]])
        outward = p[tri].mean(axis=1) - p.mean(axis=0)
        assert np.all(np.sum(n * outward, axis=1) > 0)
        # the file's normals, transformed by the inverse transpose, agree with the faces
        vn = part.mesh.normals[tri[:, 0]]
        assert np.all(np.sum(vn * n, axis=1) > 0)


def test_missing_normals_are_flat_and_missing_uvs_planar(tmp_path: Path) -> None:
    # A tent: two faces sharing an edge. glTF requires flat normals without NORMAL.
    positions = np.array([[0, 0, 0], [1, 1, 0], [0, 0, 1], [1, 1, 1], [2, 0, 0], [2, 0, 1]],
                         np.float32)
    indices = np.array([0, 2, 1, 1, 2, 3, 1, 3, 4, 4, 3, 5], np.uint16)
    (part,) = weft.load_gltf(str(write_gltf(tmp_path / "tent.gltf", positions, indices)))
    mesh = part.mesh
    assert mesh.vertex_count == 12  # unwelded: one vertex per corner
    tri = mesh.indices.reshape(-1, 3)
    s = np.sqrt(0.5)
    expected = [[-s, s, 0]] * 2 + [[s, s, 0]] * 2
    for t, e in zip(tri, expected):
        np.testing.assert_allclose(mesh.normals[t], np.tile(e, (3, 1)), atol=1e-6)
    # planar fallback: the tent is thinnest along y; u along x (longest), v along z
    np.testing.assert_allclose(mesh.uvs[:, 0], mesh.positions[:, 0] / 2.0, atol=1e-6)
    np.testing.assert_allclose(mesh.uvs[:, 1], mesh.positions[:, 2] / 2.0, atol=1e-6)


def test_material_mapping(tmp_path: Path) -> None:
    positions, normals, uvs, indices = quad_arrays()
    image = np.zeros((4, 8, 4), np.uint8)
    image[..., 3] = 255
    image[:, :4, 0] = 255  # left half red, right half blue
    image[:, 4:, 2] = 255
    material = dict(baseColorFactor=[0.8, 0.6, 0.4, 1.0], metallicFactor=0.25,
                    roughnessFactor=0.5, alphaMode="MASK", alphaCutoff=0.3, doubleSided=True)
    path = write_gltf(tmp_path / "m.glb", positions, indices, normals, uvs,
                      png=png_bytes(tmp_path, image), material=material)
    m = weft.load_gltf(str(path))[0].material
    base = np.array([0.8, 0.6, 0.4])
    np.testing.assert_allclose(m.base_color, base, atol=1e-6)
    np.testing.assert_allclose(m.kd, [0.75] * 3, atol=1e-6)
    np.testing.assert_allclose(m.ks, 0.04 * 0.75 + base * 0.25, atol=1e-6)
    alpha = 0.5 ** 2
    assert m.shininess == pytest.approx(2 / alpha**2 - 2)  # 30
    assert m.alpha_cutoff == pytest.approx(0.3)
    assert m.two_sided
    assert m.texture is not None and m.texture.srgb
    np.testing.assert_array_equal(m.texture.image, image)
    # trimesh reads the same factors and image
    tm = trimesh.load(str(path), force="mesh", process=False).visual.material
    np.testing.assert_allclose(np.asarray(tm.baseColorFactor[:3]) / 255.0, base, atol=1 / 255)
    np.testing.assert_array_equal(np.asarray(tm.baseColorTexture.convert("RGBA")), image)


def test_texture_transform_moves_the_uvs(tmp_path: Path) -> None:
    positions, normals, uvs, indices = quad_arrays()
    image = np.full((2, 2, 4), 255, np.uint8)
    transform = {"KHR_texture_transform": {"offset": [0.5, 0.25], "scale": [2.0, 3.0],
                                           "rotation": np.pi / 2}}
    path = write_gltf(tmp_path / "t.gltf", positions, indices, normals, uvs,
                      png=png_bytes(tmp_path, image), texture_extensions=transform)
    got = weft.load_gltf(str(path))[0].mesh.uvs
    # the extension's matrix: translation * rotation * scale, rotation [[c, s], [-s, c]]
    c, s = np.cos(np.pi / 2), np.sin(np.pi / 2)
    scaled = uvs * [2.0, 3.0]
    expected = np.stack([c * scaled[:, 0] + s * scaled[:, 1],
                         -s * scaled[:, 0] + c * scaled[:, 1]], axis=1) + [0.5, 0.25]
    np.testing.assert_allclose(got, expected, atol=1e-6)


def test_textured_gltf_renders_its_texture(tmp_path: Path, make_renderer) -> None:
    positions, normals, uvs, indices = quad_arrays()
    image = np.zeros((4, 8, 4), np.uint8)
    image[..., 3] = 255
    image[:, :4, 0] = 255
    image[:, 4:, 2] = 255
    path = write_gltf(tmp_path / "r.glb", positions, indices, normals, uvs,
                      png=png_bytes(tmp_path, image), material=dict(roughnessFactor=1.0))
    scene = weft.Scene()
    for part in weft.load_gltf(str(path)):
        scene.add_mesh(part.mesh, part.material)
    scene.add_light(weft.DirectionalLight(direction=(0.0, -1.0, 0.0), cast_shadows=False))
    camera = weft.Camera(position=(0.0, 3.0, 0.01), target=(0.0, 0.0, 0.0), fov_y=0.9)
    debug = make_renderer(64, 64).render_debug(scene, camera)
    mask, albedo, u = debug["mask"], debug["albedo"], debug["uv"][..., 0]
    red = mask & (u > 0.1) & (u < 0.4)
    blue = mask & (u > 0.6) & (u < 0.9)
    assert red.sum() > 200 and blue.sum() > 200
    assert np.abs(albedo[red][:, :3] - [1.0, 0.0, 0.0]).max() < 1e-3
    assert np.abs(albedo[blue][:, :3] - [0.0, 0.0, 1.0]).max() < 1e-3
    # +x is u = 1 (blue): on screen, the camera looks down with +x to the right
    x = np.nonzero(red.any(axis=0))[0].mean(), np.nonzero(blue.any(axis=0))[0].mean()
    assert x[0] != x[1]


def glb_parts(path: Path):
    data = path.read_bytes()
    length = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + length])
    return doc, data


def test_broken_files_are_io_errors(tmp_path: Path) -> None:
    positions, normals, uvs, indices = quad_arrays()
    good = write_gltf(tmp_path / "good.gltf", positions, indices, normals, uvs)
    doc = json.loads(good.read_text())

    def broken(name: str, text: str | bytes) -> str:
        p = tmp_path / name
        p.write_bytes(text if isinstance(text, bytes) else text.encode())
        return str(p)

    cases = {
        "not json": broken("a.gltf", "{ this is not json"),
        "truncated glb": broken("b.glb", write_gltf(tmp_path / "g.glb", positions, indices)
                                .read_bytes()[:40]),
        "empty": broken("c.gltf", ""),
    }
    past = json.loads(json.dumps(doc))
    past["accessors"][0]["count"] = 1000  # beyond its buffer view
    cases["accessor past its view"] = broken("d.gltf", json.dumps(past))
    index = json.loads(json.dumps(doc))
    index["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 42
    cases["missing accessor"] = broken("e.gltf", json.dumps(index))
    cycle = json.loads(json.dumps(doc))
    cycle["nodes"] = [{"mesh": 0, "children": [1]}, {"children": [0]}]
    cases["node cycle"] = broken("f.gltf", json.dumps(cycle))
    external = json.loads(json.dumps(doc))
    external["buffers"][0]["uri"] = "missing.bin"
    cases["missing buffer file"] = broken("g.gltf", json.dumps(external))
    device = json.loads(json.dumps(doc))
    device["buffers"][0]["uri"] = "/dev/zero"
    cases["device as buffer"] = broken("h.gltf", json.dumps(device))
    no_tris = json.loads(json.dumps(doc))
    no_tris["meshes"][0]["primitives"][0]["mode"] = 1  # lines
    cases["only lines"] = broken("i.gltf", json.dumps(no_tris))
    for what, path in cases.items():
        with pytest.raises(weft.IoError, match="glTF"):
            weft.load_gltf(path)
        print(what, "ok")
    with pytest.raises(weft.IoError, match="does_not_exist"):
        weft.load_gltf(str(tmp_path / "does_not_exist.glb"))


def test_oversized_image_is_refused_before_decoding(tmp_path: Path) -> None:
    positions, normals, uvs, indices = quad_arrays()
    png = bytearray(png_bytes(tmp_path, np.zeros((2, 2, 4), np.uint8)))
    struct.pack_into(">II", png, 16, 40000, 40000)  # IHDR width, height (CRC now wrong too)
    path = write_gltf(tmp_path / "big.glb", positions, indices, normals, uvs, png=bytes(png))
    with pytest.raises(weft.IoError, match="40000x40000"):
        weft.load_gltf(str(path))


def test_external_buffer_and_jpeg_image_files(tmp_path: Path) -> None:
    # .gltf + .bin + a JPEG beside it, the layout exporters write by default; the files are
    # read through weft's checked reader.
    from PIL import Image

    positions, normals, uvs, indices = quad_arrays()
    path = write_gltf(tmp_path / "ext.gltf", positions, indices, normals, uvs)
    gltf = pygltflib.GLTF2().load(str(path))
    gltf.convert_buffers(pygltflib.BufferFormat.BINFILE)
    image = np.zeros((16, 16, 3), np.uint8)
    image[:8] = (250, 20, 20)
    image[8:] = (20, 20, 250)
    Image.fromarray(image).save(tmp_path / "photo.jpg", quality=95)
    gltf.images = [pygltflib.Image(uri="photo.jpg")]
    gltf.textures = [pygltflib.Texture(source=0)]
    gltf.materials[0].pbrMetallicRoughness.baseColorTexture = pygltflib.TextureInfo(index=0)
    gltf.save(str(path))
    assert any(p.suffix == ".bin" for p in tmp_path.iterdir())
    (part,) = weft.load_gltf(str(path))
    np.testing.assert_array_equal(part.mesh.positions, positions)
    got = part.material.texture.image[..., :3].astype(int)
    theirs = np.asarray(Image.open(tmp_path / "photo.jpg").convert("RGB")).astype(int)
    assert np.abs(got - theirs).max() <= 2  # two JPEG decoders may round differently
    (tmp_path / "photo.jpg").write_bytes(b"not an image")
    with pytest.raises(weft.IoError, match="not a PNG or JPEG"):
        weft.load_gltf(str(path))


def test_strips_and_fans_cover_the_polygon_facing_front(tmp_path: Path) -> None:
    # A convex hexagon in the XZ plane facing +Y, as a triangle fan around vertex 0 and as a
    # strip zig-zagging across it: both must cover its area (shoelace formula) with every
    # triangle counter-clockwise seen from +Y.
    angles = np.arange(6) * np.pi / 3
    ring = np.stack([np.cos(angles), np.zeros(6), -np.sin(angles)], axis=1).astype(np.float32)
    area = 0.5 * abs(np.dot(ring[:, 0], np.roll(ring[:, 2], -1)) -
                     np.dot(ring[:, 2], np.roll(ring[:, 0], -1)))
    up = np.tile(np.array([0, 1, 0], np.float32), (6, 1))
    fan = np.arange(6, dtype=np.uint16)
    strip = np.array([0, 1, 5, 2, 4, 3], np.uint16)  # v0 v1 v5 v2 v4 v3 zig-zags across
    for name, order, mode in (("fan", fan, 6), ("strip", strip, 5)):
        (part,) = weft.load_gltf(str(write_gltf(tmp_path / f"{name}.gltf", ring, order, up,
                                                mode=mode)))
        p, tri = part.mesh.positions, part.mesh.indices.reshape(-1, 3)
        assert len(tri) == 4, name
        n = np.cross(p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]])
        assert np.all(n[:, 1] > 0), name
        assert 0.5 * n[:, 1].sum() == pytest.approx(area, rel=1e-6), name


def test_node_instancing_bomb_is_refused(tmp_path: Path) -> None:
    # Each node lists the next one twice: 2^40 visits if followed.
    positions, normals, uvs, indices = quad_arrays()
    doc = json.loads(write_gltf(tmp_path / "q.gltf", positions, indices, normals, uvs).read_text())
    doc["nodes"] = [{"children": [i + 1, i + 1]} for i in range(40)] + [{"mesh": 0}]
    path = tmp_path / "bomb.gltf"
    path.write_text(json.dumps(doc))
    with pytest.raises(weft.IoError, match="more than"):
        weft.load_gltf(str(path))
    doc["nodes"] = [{"children": [i + 1, i + 1]} for i in range(40)] + [{}]  # no mesh at all
    path.write_text(json.dumps(doc))
    with pytest.raises(weft.IoError, match="instanced more than"):
        weft.load_gltf(str(path))
