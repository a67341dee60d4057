"""OBJ + MTL loading (tinyobjloader reads the text) against trimesh as the independent reader of
the same files: faces that use elements defined after them, negative indices, index 0 refused,
.mtl Kd/Ks/Ns/map_Kd as weft Materials (weft.load_obj_parts), files the hand-written reader
refused, files trimesh writes, and the materials as rendered."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import weft

trimesh = pytest.importorskip("trimesh")

OBJ = """mtllib two.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
usemtl red
f 1/1/1 2/2/1 3/3/1
usemtl textured
f -4/-4/2 -2/-2/2 -1/-1/2
# the normals come after the faces that use them
vn 0 0 1
vn 0 0.6 0.8
"""

MTL = """# two materials
newmtl red
Kd 0.8 0.1 0.2
Ks 0.3 0.3 0.3
Ns 50
newmtl textured
Kd 0.5 0.5 0.5
Ks 0.9 0.8 0.7
Ns 200
map_Kd tex.png
"""


def texture_image() -> np.ndarray:
    image = np.zeros((2, 4, 3), np.uint8)
    image[:, :2, 0] = 255  # left half red, right half green
    image[:, 2:, 1] = 255
    return image


@pytest.fixture
def two_materials(tmp_path: Path) -> Path:
    (tmp_path / "two.mtl").write_text(MTL)
    weft.save_png(str(tmp_path / "tex.png"), texture_image())
    path = tmp_path / "two.obj"
    path.write_text(OBJ)
    return path


def by_centroid(corners: np.ndarray) -> np.ndarray:
    """Triangles (T, 3, 3) in the order of their centroids (trimesh regroups faces)."""
    c = corners.mean(axis=1)
    return corners[np.lexsort((c[:, 2], c[:, 1], c[:, 0]))]


def trimesh_parts(path: Path) -> dict:
    scene = trimesh.load(str(path), process=False)
    return dict(scene.geometry)


def test_parts_match_trimesh(two_materials: Path) -> None:
    parts = {p.name: p for p in weft.load_obj_parts(str(two_materials))}
    theirs = trimesh_parts(two_materials)
    assert set(parts) == set(theirs) == {"red", "textured"}
    for name, part in parts.items():
        t = theirs[name]
        ours_corners = part.mesh.positions[part.mesh.indices.reshape(-1, 3)]
        np.testing.assert_allclose(ours_corners, t.vertices[t.faces], atol=1e-6)
        # OBJ's v = 0 is the bottom row; weft's the top one
        ours_uv = part.mesh.uvs[part.mesh.indices.reshape(-1, 3)]
        their_uv = np.asarray(t.visual.uv)[t.faces]
        np.testing.assert_allclose(ours_uv, np.stack([their_uv[..., 0], 1 - their_uv[..., 1]], -1),
                                   atol=1e-6)
        np.testing.assert_allclose(part.mesh.normals[part.mesh.indices.reshape(-1, 3)],
                                   np.asarray(t.vertex_normals)[t.faces], atol=1e-6)
        m, tm = part.material, t.visual.material
        np.testing.assert_allclose(m.kd, np.asarray(tm.diffuse[:3]) / 255.0, atol=0.5 / 255)
        np.testing.assert_allclose(m.ks, np.asarray(tm.specular[:3]) / 255.0, atol=0.5 / 255)
        assert m.shininess == pytest.approx(tm.glossiness)
        if tm.image is None:
            assert m.texture is None
        else:
            assert m.texture.srgb
            np.testing.assert_array_equal(m.texture.image[..., :3],
                                          np.asarray(tm.image.convert("RGB")))


def test_map_options_are_skipped(tmp_path: Path, two_materials: Path) -> None:
    # options before the file name (trimesh does not read these); a name with a space
    (tmp_path / "two.mtl").write_text(MTL.replace("map_Kd tex.png",
                                                  "map_Kd -s 1 1 1 -o 0.5 -clamp on my tex.png"))
    weft.save_png(str(tmp_path / "my tex.png"), texture_image())
    parts = {p.name: p for p in weft.load_obj_parts(str(two_materials))}
    np.testing.assert_array_equal(parts["textured"].material.texture.image[..., :3],
                                  texture_image())


def test_load_obj_still_gives_one_mesh_and_ignores_materials(tmp_path: Path) -> None:
    path = tmp_path / "nomtl.obj"
    path.write_text(OBJ)  # its .mtl does not exist: load_obj does not read it
    mesh = weft.load_obj(str(path))
    assert mesh.triangle_count == 2
    theirs = trimesh.load(str(path), force="mesh", process=False)
    np.testing.assert_allclose(by_centroid(mesh.positions[mesh.indices.reshape(-1, 3)]),
                               by_centroid(theirs.vertices[theirs.faces]), atol=1e-6)
    with pytest.raises(weft.IoError, match="two.mtl"):
        weft.load_obj_parts(str(path))


def test_index_zero_and_out_of_range_are_clear_errors(tmp_path: Path) -> None:
    header = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    for face, message in (("f 0 1 2", "index 0 is invalid"), ("f 1 2 4", "out of range"),
                          ("f 1//3 2//3 3//3\nvn 0 0 1", "normal index 3 is out of range"),
                          ("f -4 1 2", "out of range")):
        path = tmp_path / "bad.obj"
        path.write_text(header + face + "\n")
        with pytest.raises(weft.IoError, match=f"bad.obj:4: .*{message}"):
            weft.load_obj(str(path))


def test_material_errors(tmp_path: Path, two_materials: Path) -> None:
    (tmp_path / "tex.png").unlink()
    with pytest.raises(weft.IoError, match="tex.png"):
        weft.load_obj_parts(str(two_materials))
    # tinyobjloader reads the numbers (a word that is none reads as 0); weft refuses what its
    # Material cannot hold, naming the .mtl and the material
    (tmp_path / "two.mtl").write_text("newmtl red\nKd 0.8 -1 0.2\n")
    with pytest.raises(weft.IoError, match="two.mtl': material 'red': Kd needs finite non-neg"):
        weft.load_obj_parts(str(two_materials))
    (tmp_path / "two.mtl").write_text("newmtl red\nKs 1 1 1e999\n")
    with pytest.raises(weft.IoError, match="material 'red': Ks"):
        weft.load_obj_parts(str(two_materials))
    (tmp_path / "two.mtl").write_text("newmtl red\nKd 1 1 1\n")
    with pytest.raises(weft.IoError, match="'textured' is not defined"):
        weft.load_obj_parts(str(two_materials))


def test_trimesh_export_round_trip(tmp_path: Path) -> None:
    from PIL import Image

    box = trimesh.creation.box(extents=(1.0, 2.0, 0.5))
    uv = np.random.default_rng(1).random((len(box.vertices), 2))
    image = np.zeros((8, 8, 3), np.uint8)
    image[:4] = (200, 30, 30)
    image[4:] = (30, 30, 200)
    box.visual = trimesh.visual.TextureVisuals(
        uv=uv, material=trimesh.visual.material.SimpleMaterial(
            image=Image.fromarray(image), diffuse=(204, 153, 102, 255)))
    files = trimesh.exchange.obj.export_obj(box, include_texture=True, return_texture=True,
                                            mtl_name="box.mtl")
    text, textures = files
    (tmp_path / "box.obj").write_text(text)
    for name, data in textures.items():
        (tmp_path / name).write_bytes(data)
    (part,) = weft.load_obj_parts(str(tmp_path / "box.obj"))
    theirs = trimesh.load(str(tmp_path / "box.obj"), force="mesh", process=False)
    np.testing.assert_allclose(part.mesh.positions[part.mesh.indices.reshape(-1, 3)],
                               theirs.vertices[theirs.faces], atol=1e-6)
    np.testing.assert_allclose(part.material.kd,
                               np.asarray(theirs.visual.material.diffuse[:3]) / 255,
                               atol=0.5 / 255)
    np.testing.assert_array_equal(part.material.texture.image[..., :3], image)


def test_obj_with_materials_renders_them(make_renderer, two_materials: Path) -> None:
    scene = weft.Scene()
    for part in weft.load_obj_parts(str(two_materials)):
        scene.add_mesh(part.mesh, part.material)
    scene.add_light(weft.DirectionalLight(direction=(0.0, 0.0, -1.0), cast_shadows=False))
    camera = weft.Camera(position=(0.5, 0.5, 2.0), target=(0.5, 0.5, 0.0), fov_y=0.8)
    debug = make_renderer(64, 64).render_debug(scene, camera)
    mask, albedo, uv = debug["mask"], debug["albedo"][..., :3], debug["uv"]
    # the red triangle (below the diagonal x = y) has no texture: albedo 1
    lower = mask & (uv[..., 0] > uv[..., 1] - 1e-3) & (1 - uv[..., 1] < uv[..., 0] - 0.1)
    upper = mask & (1 - uv[..., 1] > uv[..., 0] + 0.1)
    assert lower.sum() > 100 and upper.sum() > 100
    assert np.abs(albedo[lower] - 1.0).max() < 1e-3
    # the textured one shows the texture: 4 texels, red then green; bilinear filtering (and
    # the repeat wrap at the edges) mixes them except between the centres of equal texels
    left = upper & (uv[..., 0] > 0.15) & (uv[..., 0] < 0.35)
    right = upper & (uv[..., 0] > 0.65) & (uv[..., 0] < 0.85)
    assert left.sum() > 20 and right.sum() > 20
    assert np.abs(albedo[left] - [1, 0, 0]).max() < 1e-3
    assert np.abs(albedo[right] - [0, 1, 0]).max() < 1e-3


def test_many_interleaved_materials(tmp_path: Path) -> None:
    # 300 materials used in turn by 900 triangles: each part gets exactly its own faces.
    count = 300
    lines = ["mtllib many.mtl"]
    mtl = []
    for k in range(count):
        mtl += [f"newmtl m{k}", f"Kd {k / count:.6f} 0.5 0.5"]
    for t in range(3 * count):
        x = float(t)
        lines += [f"v {x} 0 0", f"v {x + 1} 0 0", f"v {x} 1 0", f"usemtl m{t % count}",
                  "f -3 -2 -1"]
    (tmp_path / "many.mtl").write_text("\n".join(mtl) + "\n")
    path = tmp_path / "many.obj"
    path.write_text("\n".join(lines) + "\n")
    parts = weft.load_obj_parts(str(path))
    assert [p.name for p in parts] == [f"m{k}" for k in range(count)]
    for k, part in enumerate(parts):
        assert part.mesh.triangle_count == 3
        assert part.material.kd[0] == pytest.approx(k / count, abs=1e-6)
        xs = sorted(part.mesh.positions[part.mesh.indices.reshape(-1, 3)[:, 0], 0])
        assert xs == [k, k + count, k + 2 * count]


def test_faces_before_the_elements_they_use(tmp_path: Path) -> None:
    """Positions, texture coordinates and normals all defined after the faces (and a quad)."""
    rng = np.random.default_rng(7)
    positions = rng.normal(size=(5, 3)).round(4)
    uvs = rng.random((5, 2)).round(4)
    normals = rng.normal(size=(5, 3))
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    lines = ["f 1/1/1 2/2/2 3/3/3", "f 1/1/1 3/3/3 4/4/4 5/5/5"]
    lines += [f"v {x} {y} {z}" for x, y, z in positions]
    lines += [f"vt {u} {v}" for u, v in uvs]
    lines += [f"vn {x:.6f} {y:.6f} {z:.6f}" for x, y, z in normals]
    path = tmp_path / "forward.obj"
    path.write_text("\n".join(lines) + "\n")
    mesh = weft.load_obj(str(path))
    theirs = trimesh.load(str(path), force="mesh", process=False)
    ours = mesh.indices.reshape(-1, 3)
    assert len(ours) == len(theirs.faces) == 3

    def triangles(positions: np.ndarray, uvs: np.ndarray) -> np.ndarray:
        """(T, 3, 5) corners, each triangle turned to start at its smallest x (the winding
        kept; trimesh splits the quad at another corner), in the order of their centroids."""
        corners = np.concatenate([positions, uvs], -1)
        start = np.argmin(positions[..., 0], axis=1)
        turned = np.stack([np.roll(c, -k, axis=0) for c, k in zip(corners, start)])
        return turned[np.argsort(turned[:, :, :3].mean(axis=1) @ [1.0, 1e3, 1e6])]

    uv = mesh.uvs[ours]
    np.testing.assert_allclose(
        triangles(mesh.positions[ours], np.concatenate([uv[..., :1], 1 - uv[..., 1:]], -1)),
        triangles(theirs.vertices[theirs.faces], np.asarray(theirs.visual.uv)[theirs.faces]),
        atol=1e-6)
    # the normals are the file's (each position has one)
    corner_positions = mesh.positions[ours].reshape(-1, 3)
    which = np.argmin(np.linalg.norm(corner_positions[:, None] - positions[None], axis=2), axis=1)
    np.testing.assert_allclose(mesh.normals[ours].reshape(-1, 3), normals[which], atol=1e-5)


def test_files_the_hand_written_reader_refused(tmp_path: Path) -> None:
    """Statements before the first newmtl (the hand-written reader: "'Kd' before any 'newmtl'")
    and an mtllib line naming a missing file before the one that exists (it read the whole line
    as one name): tinyobjloader takes both, trimesh reads the same materials from the same .mtl."""
    mtl = "# exported\nKd 0.1 0.2 0.3\nNs 7\n" + MTL
    (tmp_path / "real.mtl").write_text(mtl)
    weft.save_png(str(tmp_path / "tex.png"), texture_image())
    path = tmp_path / "two.obj"
    path.write_text(OBJ.replace("mtllib two.mtl", "mtllib missing.mtl real.mtl"))
    reference = tmp_path / "reference.obj"  # trimesh reads one library per line
    reference.write_text(OBJ.replace("mtllib two.mtl", "mtllib real.mtl"))
    parts = {p.name: p for p in weft.load_obj_parts(str(path))}
    theirs = trimesh_parts(reference)
    assert set(parts) == set(theirs) == {"red", "textured"}
    for name, part in parts.items():
        m, tm = part.material, theirs[name].visual.material
        np.testing.assert_allclose(m.kd, np.asarray(tm.diffuse[:3]) / 255.0, atol=0.5 / 255)
        np.testing.assert_allclose(m.ks, np.asarray(tm.specular[:3]) / 255.0, atol=0.5 / 255)
        assert m.shininess == pytest.approx(tm.glossiness)


def test_errors_name_the_line(tmp_path: Path) -> None:
    header = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    cases = (("v 1e999 0 0\nf 1 2 3", "bad.obj:4: position is not finite"),
             ("vn 0 0 1\r\nf 1//1 2//1", "bad.obj:5: face needs at least 3 vertices, has 2"),
             ("f 1 2 3 # a comment", "bad.obj:4: position index 0 is invalid.*comment"),
             ("mtllib a.mtl b.mtl\nf 1 2 3", "bad.obj:4: cannot open MTL file '.*a.mtl'"))
    for body, message in cases:
        path = tmp_path / "bad.obj"
        path.write_text(header + body + "\n")
        with pytest.raises(weft.IoError, match=message):
            weft.load_obj_parts(str(path))
    # load_obj reads no material library
    assert weft.load_obj(str(path)).triangle_count == 1


def test_missing_statements_take_tinyobjloaders_defaults(tmp_path: Path) -> None:
    """What ModelIo.h documents: Ks 0, Ns 1 (clamped to weft's >= 1), Kd 0 or 0.6 with a
    map_Kd, a one-number Kd as (r, 0, 0)."""
    weft.save_png(str(tmp_path / "t.png"), texture_image())
    (tmp_path / "d.mtl").write_text("newmtl textured\nmap_Kd t.png\nnewmtl grey\nKd 0.5\n"
                                   "newmtl bare\n")
    path = tmp_path / "d.obj"
    path.write_text("mtllib d.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n" +
                    "".join(f"usemtl {n}\nf 1 2 3\n" for n in ("textured", "grey", "bare")))
    got = {p.name: p.material for p in weft.load_obj_parts(str(path))}
    assert got["textured"].kd == pytest.approx((0.6, 0.6, 0.6)) and got["textured"].texture
    assert got["grey"].kd == pytest.approx((0.5, 0.0, 0.0))
    assert got["bare"].kd == (0, 0, 0) and got["bare"].ks == (0, 0, 0)
    assert got["bare"].shininess == 1.0
