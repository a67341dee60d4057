"""Material maps (SPEC §1.4, §1.5): tangents, tangent-space normal maps (eq. 2.11-2.12) on
still, rotated and mirrored meshes, specular maps, and alpha-tested holes that also cut the
shadow; checked against NumPy evaluations from the same frame's debug outputs."""

from __future__ import annotations

import math

import numpy as np
import pytest
import weft
from weft import reference as ref


def transform(rotation_y: float = 0.0, scale=(1.0, 1.0, 1.0), offset=(0.0, 0.0, 0.0)) -> np.ndarray:
    c, s = math.cos(rotation_y), math.sin(rotation_y)
    r = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    m = np.eye(4, dtype=np.float32)
    m[:3, :3] = r @ np.diag(scale)
    m[:3, 3] = offset
    return m


def bumpy_normal_map(size: int = 32) -> np.ndarray:
    """A smooth, seamless tangent-space normal map (tilts up to ~35 degrees)."""
    y, x = np.mgrid[0:size, 0:size].astype(np.float64)
    tx = 0.6 * np.sin(2 * np.pi * x / size)
    ty = 0.6 * np.cos(2 * np.pi * y / size)
    n = np.stack([tx, ty, np.ones_like(tx)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    return np.clip(np.rint((n * 0.5 + 0.5) * 255), 0, 255).astype(np.uint8)


def test_tangents_of_built_in_shapes() -> None:
    plane = weft.Mesh.plane(2.0, 3.0, 2, 2)
    np.testing.assert_allclose(plane.tangents, np.tile([1.0, 0, 0, 1.0], (plane.vertex_count, 1)),
                               atol=1e-6)
    sphere = weft.Mesh.uv_sphere(1.0, 16, 8)
    t, n, p = sphere.tangents, sphere.normals, sphere.positions
    assert np.all(np.abs(np.abs(t[:, 3]) - 1.0) < 1e-6)
    np.testing.assert_allclose(np.linalg.norm(t[:, :3], axis=1), 1.0, atol=1e-5)
    assert np.abs(np.sum(t[:, :3] * n, axis=1)).max() < 1e-5
    # away from the poles, +u runs around the Y axis: t follows the circle of latitude (up to
    # the facets' area weighting) in one consistent direction
    ring = np.abs(p[:, 1]) < 0.9
    circle = np.stack([-p[ring, 2], np.zeros(ring.sum()), p[ring, 0]], axis=1)
    circle /= np.linalg.norm(circle, axis=1, keepdims=True)
    along = np.sum(t[ring, :3] * circle, axis=1)
    assert np.all(np.abs(along) > 0.99) and (np.all(along > 0) or np.all(along < 0))
    box = weft.Mesh.box((1.0, 2.0, 3.0))
    bt, bp, buv, bi = box.tangents, box.positions, box.uvs, box.indices.reshape(-1, 3)
    for tri in bi:  # dP/du of each face from its own corners (u is linear on a face)
        e1, e2 = bp[tri[1]] - bp[tri[0]], bp[tri[2]] - bp[tri[0]]
        d1, d2 = buv[tri[1]] - buv[tri[0]], buv[tri[2]] - buv[tri[0]]
        det = d1[0] * d2[1] - d2[0] * d1[1]
        dpdu = (e1 * d2[1] - e2 * d1[1]) / det
        dpdv = (e2 * d1[0] - e1 * d2[0]) / det
        for v in tri:
            np.testing.assert_allclose(bt[v, :3], dpdu / np.linalg.norm(dpdu), atol=1e-5)
            b = bt[v, 3] * np.cross(box.normals[v], bt[v, :3])
            assert np.dot(b, -dpdv) > 0  # the bitangent points towards decreasing v


@pytest.mark.parametrize("case", ["still", "rotated", "mirrored"])
def test_normal_map_gives_eq_2_11_normals(make_renderer, case: str) -> None:
    nmap = bumpy_normal_map()
    mat = weft.Material(kd=(0.8, 0.8, 0.8), ks=(0.3, 0.3, 0.3), shininess=16.0,
                        normal_map=weft.Texture(nmap, srgb=False, mipmaps=False))
    m = {"still": transform(), "rotated": transform(0.7),
         "mirrored": transform(0.3, scale=(-1.0, 1.0, 1.0))}[case]
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(2.0, 2.0), mat, transform=m)
    scene.add_light(weft.DirectionalLight(direction=(-0.3, -1.0, -0.4), cast_shadows=False))
    camera = weft.Camera(position=(0.0, 2.2, 0.6), target=(0.0, 0.0, 0.0), fov_y=1.0)
    debug = make_renderer(96, 96).render_debug(scene, camera)
    mask = debug["mask"]
    assert mask.mean() > 0.5
    # the frame in world space: tangent = M * (1, 0, 0), normal = +Y, b = w (n x t)
    t = m[:3, :3] @ np.array([1.0, 0.0, 0.0])
    t /= np.linalg.norm(t)
    n = np.array([0.0, 1.0, 0.0])
    w = -1.0 if np.linalg.det(m[:3, :3]) < 0 else 1.0
    b = w * np.cross(n, t)
    texel = ref.sample_bilinear_repeat(nmap.astype(np.float64) / 255.0, debug["uv"][mask])
    mm = texel * 2.0 - 1.0
    expected = mm[:, :1] * t + mm[:, 1:2] * b + mm[:, 2:3] * n
    expected /= np.linalg.norm(expected, axis=1, keepdims=True)
    got = debug["normal"][mask]
    angle = np.degrees(np.arccos(np.clip(np.sum(got * expected, axis=1), -1, 1)))
    assert np.percentile(angle, 99) < 1.0 and angle.max() < 2.0, angle.max()
    tilt = np.degrees(np.arccos(np.clip(got[:, 1], -1, 1)))
    assert tilt.max() > 20.0  # the map really perturbs the normal
    # and the shading uses that normal (oracle from the same frame)
    oracle = ref.shade_debug_frame(debug, camera.position, scene.lights, scene.ambient,
                                   scene.background, ref.SurfaceMaterial.from_weft(mat),
                                   frame_albedo=True)
    err = np.abs(debug["linear"][..., :3] - oracle[..., :3]).max(axis=-1)[mask]
    assert err.max() <= 1e-3


def test_specular_map_scales_ks(make_renderer) -> None:
    spec = np.zeros((8, 8, 3), np.uint8)
    spec[:, 4:] = 255  # right half shiny, left half matte
    mat = weft.Material(kd=(0.3, 0.3, 0.3), ks=(0.9, 0.9, 0.9), shininess=8.0,
                        specular_map=weft.Texture(spec, srgb=False, mipmaps=False))
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(2.0, 2.0), mat)
    scene.add_light(weft.DirectionalLight(direction=(0.0, -1.0, 0.3), cast_shadows=False))
    camera = weft.Camera(position=(0.0, 2.0, -0.6), target=(0.0, 0.0, 0.0), fov_y=1.0)
    debug = make_renderer(96, 96).render_debug(scene, camera)
    mask = debug["mask"]
    u = debug["uv"][..., 0]
    # texels are 1/8 wide: half a texel from each boundary the bilinear filter sees one half only
    matte = mask & (u % 1.0 > 0.07) & (u % 1.0 < 0.43)
    shiny = mask & (u % 1.0 > 0.57) & (u % 1.0 < 0.93)
    assert matte.sum() > 100 and shiny.sum() > 100
    assert np.all(debug["specular_map"][matte] == 0.0)
    assert np.all(debug["specular_map"][shiny] == 1.0)
    material = ref.SurfaceMaterial.from_weft(mat)
    material_ks = dict(ks=np.asarray(mat.ks) * debug["specular_map"][..., None])
    colour = ref.blinn_phong(debug["position"], debug["normal"], camera.position, scene.lights,
                             scene.ambient, albedo=debug["albedo"], ka=mat.ka, kd=mat.kd,
                             shininess=mat.shininess, **material_ks)
    err = np.abs(debug["linear"][..., :3] - colour).max(axis=-1)[mask]
    assert err.max() <= 1e-3
    # without the map the matte half would show the highlight
    plain = ref.blinn_phong(debug["position"], debug["normal"], camera.position, scene.lights,
                            scene.ambient, albedo=debug["albedo"], ka=mat.ka, kd=mat.kd,
                            ks=mat.ks, shininess=mat.shininess)
    assert np.abs(plain - debug["linear"][..., :3]).max(axis=-1)[matte].max() > 0.05
    assert material.ks == tuple(mat.ks)


def test_alpha_holes_cut_the_image_and_the_shadow(make_renderer) -> None:
    """A sheet with square holes floats above the ground under a light from straight above:
    through the holes the camera sees the ground, and the ground below a hole is lit while the
    ground below the sheet is shadowed."""
    tex = np.full((4, 4, 4), 255, np.uint8)
    tex[::2, ::2, 3] = 0  # holes: every other texel in both directions
    sheet = weft.Material(kd=(0.9, 0.2, 0.2), texture=weft.Texture(tex, mipmaps=False),
                          alpha_cutoff=0.5)
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(6.0, 6.0), weft.Material(kd=(0.8, 0.8, 0.8)))
    scene.add_mesh(weft.Mesh.plane(2.0, 2.0), sheet, transform=transform(offset=(0, 1.0, 0)))
    scene.add_light(weft.DirectionalLight(direction=(0.0, -1.0, 0.0)))
    # from high above, so the ground under a hole is seen through that hole
    camera = weft.Camera(position=(0.0, 8.0, 0.01), target=(0.0, 0.0, 0.0), fov_y=0.45)
    renderer = make_renderer(160, 160, shadow_map_size=2048, pcf_radius=0)
    debug = renderer.render_debug(scene, camera)
    inst, pos = debug["instance"], debug["position"]

    def sheet_alpha(x: np.ndarray, z: np.ndarray) -> np.ndarray:
        """Alpha of the sheet texel above world (x, z) (the plane's uv: u = x/2 + 0.5)."""
        u, v = x / 2.0 + 0.5, z / 2.0 + 0.5
        i, j = np.floor(u * 4).astype(int), np.floor(v * 4).astype(int)
        inside = (u > 0) & (u < 1) & (v > 0) & (v < 1)
        alpha = np.where(inside, tex[np.clip(j, 0, 3), np.clip(i, 0, 3), 3], 255)
        # near texel centres, where the bilinear alpha stays on the texel's side of 0.5
        fu, fv = (u * 4) % 1.0, (v * 4) % 1.0
        centre = (np.abs(fu - 0.5) < 0.2) & (np.abs(fv - 0.5) < 0.2) & inside
        return alpha, centre

    on_sheet = inst == 1
    assert on_sheet.sum() > 500
    a, centre = sheet_alpha(pos[..., 0], pos[..., 2])
    assert np.all(a[on_sheet & centre] == 255), "the sheet is drawn where it has holes"
    ground = inst == 0
    a, centre = sheet_alpha(pos[..., 0], pos[..., 2])
    under_hole = ground & centre & (a == 0)
    assert under_hole.sum() > 50
    assert np.all(debug["shadow"][under_hole] == 1.0), "holes must let the light through"
    # from below the sheet's height the ground under its opaque texels is in view
    low = renderer.render_debug(scene, weft.Camera(position=(0.0, 0.5, 3.0),
                                                   target=(0.0, 0.0, 0.0), fov_y=0.9))
    pos = low["position"]
    a, centre = sheet_alpha(pos[..., 0], pos[..., 2])
    ground = low["instance"] == 0
    under_sheet = ground & centre & (a == 255) & (np.abs(pos[..., 0]) < 1) & \
        (np.abs(pos[..., 2]) < 1)
    under_hole = ground & centre & (a == 0)
    assert under_sheet.sum() > 50 and under_hole.sum() > 50
    assert np.all(low["shadow"][under_sheet] == 0.0), "the sheet must shadow the ground"
    assert np.all(low["shadow"][under_hole] == 1.0)


def test_material_validation() -> None:
    with pytest.raises(ValueError, match="linear"):
        weft.Material(normal_map=weft.Texture(np.zeros((2, 2, 3), np.uint8), srgb=True))
    with pytest.raises(ValueError):
        weft.Material(alpha_cutoff=1.5)
    with pytest.raises(ValueError):
        weft.Material(alpha_cutoff=math.nan)
    m = weft.Material()
    with pytest.raises(ValueError):
        m.alpha_cutoff = -0.1
    assert m.alpha_cutoff == 0.0
    assert m.specular_model == "blinn_phong"  # the seed's by default
    m.specular_model = "ggx"
    assert m.specular_model == "ggx"
    assert weft.Material(specular_model="ggx").specular_model == "ggx"
    with pytest.raises(ValueError, match="'blinn_phong' or 'ggx'"):
        m.specular_model = "phong"
    with pytest.raises(ValueError, match="'blinn_phong' or 'ggx'"):
        weft.Material(specular_model="GGX")
