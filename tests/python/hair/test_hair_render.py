"""Hair in the renderer: scene API, which passes a frame runs, and per-fragment shading against
the NumPy hair model (weft.reference.hair) evaluated from the frame's debug outputs."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import weft
from weft.reference import hair as R


def strands_along_x(ys, zs, x=0.5, transparency=0.0, segments=4):
    """Straight strands from -x to +x at each (y, z), `segments` segments each."""
    pts = []
    for y, z in zip(ys, zs):
        xs = np.linspace(-x, x, segments + 1)
        pts.append(np.stack([xs, np.full_like(xs, y), np.full_like(xs, z)], axis=1))
    points = np.concatenate(pts).astype(np.float32)
    return weft.HairStrands(points, default_segments=segments,
                            default_transparency=transparency)


def camera_at(z=2.0, target=(0.0, 0.0, 0.0), fov=0.8):
    return weft.Camera((target[0], target[1], z), target, (0, 1, 0), fov)


def pass_names(renderer):
    return [p["name"] for p in renderer.stats["passes"]]


def hair_passes(renderer):
    return [n for n in pass_names(renderer) if n.startswith("hair")]


#: Opaque hair in an anti-aliased frame (msaa > 1, the default): the pixels strands cover
#: entirely, then the partly covered ones accumulated and composited over them.
OPAQUE = ["hair", "hair_fringe", "hair_composite"]


@pytest.fixture
def small():
    r = weft.Renderer(48, 48, shadow_map_size=128)
    r.hair_dom_size = 32
    return r


def test_scene_without_hair_adds_no_hair_pass(small):
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.uv_sphere(0.5, 12, 8))
    scene.add_light(weft.DirectionalLight((0, -1, 0), (1, 1, 1), 1.0, True))
    small.render(scene, camera_at())
    assert hair_passes(small) == []
    assert "forward" in pass_names(small) and "shadow[0]" in pass_names(small)


def test_opaque_hair_without_shadow_caster_runs_only_the_hair_pass(small):
    scene = weft.Scene()
    scene.add_hair(strands_along_x([0.0, 0.1], [0.0, 0.0]))
    scene.add_light(weft.DirectionalLight((0, -1, 0), (1, 1, 1), 1.0, False))
    small.render(scene, camera_at())
    assert hair_passes(small) == OPAQUE
    assert not any(n.startswith("shadow") for n in pass_names(small))
    small.msaa = 1  # no anti-aliasing: one strand per pixel, one pass
    small.render(scene, camera_at())
    assert hair_passes(small) == ["hair"]


def test_shadow_casting_directional_light_adds_deep_opacity_passes(small):
    scene = weft.Scene()
    scene.add_hair(strands_along_x([0.0, 0.1], [0.0, 0.0]))
    scene.add_light(weft.DirectionalLight((0, -1, 0), (1, 1, 1), 1.0, True))
    small.render(scene, camera_at())
    names = pass_names(small)
    assert hair_passes(small) == ["hair_dom_depth", "hair_dom_opacity"] + OPAQUE
    assert names.index("shadow[0]") < names.index("forward") < names.index("hair")
    small.hair_dom = False
    small.render(scene, camera_at())
    assert hair_passes(small) == OPAQUE


def test_point_light_shadows_hair_without_deep_opacity(small):
    scene = weft.Scene()
    scene.add_hair(strands_along_x([0.0, 0.1], [0.0, 0.0]))
    scene.add_light(weft.PointLight((0, 1, 0), (1, 1, 1), 1.0, cast_shadows=True))
    small.render(scene, camera_at())
    assert hair_passes(small) == OPAQUE
    assert sum(n.startswith("shadow[0]") for n in pass_names(small)) == 6


def test_transparent_hair_adds_oit_passes_only_when_enabled(small):
    scene = weft.Scene()
    scene.add_hair(strands_along_x([0.0], [0.0], transparency=0.5))
    small.render(scene, camera_at())
    assert hair_passes(small) == ["hair_oit", "hair_composite"]
    scene.add_hair(strands_along_x([0.2], [0.0]))  # an opaque one as well
    small.render(scene, camera_at())
    assert hair_passes(small) == ["hair", "hair_fringe", "hair_oit", "hair_composite"]
    small.hair_transparency = False
    small.render(scene, camera_at())
    assert hair_passes(small) == OPAQUE


def test_hair_draws_and_casts_into_shadow_maps(small):
    scene = weft.Scene()
    scene.ambient = (0, 0, 0)
    scene.add_mesh(weft.Mesh.plane(2, 2, 1, 1), weft.Material(),
                   np.array([[1, 0, 0, 0], [0, 1, 0, -0.3], [0, 0, 1, 0], [0, 0, 0, 1]], float),
                   cast_shadows=False)
    ys = np.zeros(40)
    zs = np.linspace(-0.2, 0.2, 40)
    scene.add_hair(strands_along_x(ys, zs, segments=8), weft.HairMaterial("kajiya_kay"))
    # the shadow falls 0.3 m towards -z, partly beside the strands
    scene.add_light(weft.DirectionalLight((0, -1, -1), (1, 1, 1), 1.0, True))
    small.hair_dom = False
    camera = weft.Camera((0, 1.5, 0.01), (0, -0.3, 0), (0, 0, -1), 0.9)
    d = small.render_debug(scene, camera)
    assert (d["hair"] == 0).sum() > 50  # the strands cover pixels
    ground = (d["instance"] == 0)
    lit = d["shadow"][ground]
    # the strands shadow the ground (one-texel lines in a map fitted to them: PCF sees a
    # third of its taps covered at least)
    assert lit.min() <= 2 / 3 + 1e-6 and lit.max() == 1.0
    for prim in ("lines", "ribbons"):
        small.hair_primitive = prim
        img = small.render_linear(scene, camera)
        assert np.isfinite(img).all()


def test_ribbons_cover_their_width():
    r = weft.Renderer(64, 64, shadow_map_size=64)
    scene = weft.Scene()
    scene.add_hair(strands_along_x([0.0], [0.0], x=2.0))
    camera = camera_at(2.0, fov=0.5)  # 2 tan(0.25) ~ 1.02 m over 64 pixels
    r.hair_primitive = "lines"
    lines = (r.render_debug(scene, camera)["hair"] == 0).sum(axis=0)
    r.hair_primitive = "ribbons"
    r.hair_width = 0.16  # thickness 1: 0.16 m, ~10 pixels
    ribbons = (r.render_debug(scene, camera)["hair"] == 0).sum(axis=0)
    assert np.all(lines[4:-4] == 1)
    assert np.all(np.abs(ribbons[4:-4] - 0.16 / (2 * 2 * np.tan(0.25)) * 64) <= 1.0)


@pytest.mark.parametrize("order", [(2, 1, 0), (0, 1, 2)])
def test_aa_shares_of_a_pixel_go_to_the_nearest_strand_at_each_point(order):
    """Three horizontal ribbons under one pixel row, each narrower than a pixel (so all of them
    go through the anti-aliased fringe passes), at three depths: red nearest over rows
    [0.1, 0.4] of the row, green behind it over [0.25, 0.75], blue farthest over [0.55, 0.95].
    Area-exact, the row shows red 0.3, green 0.35 (its part below red), blue 0.2 (below both)
    and 0.15 of the black background, whatever order they are drawn in. (Before, after the
    nearest strand the others took what was still free in drawing order: drawn blue first,
    blue got 0.4 and green 0.15.)"""
    H = W = 32
    dist, fov, row = 3.0, 0.3, 16
    cam = weft.Camera((0.0, 0.0, dist), (0.0, 0.0, 0.0), (0, 1, 0), fov)
    p11 = abs(cam.projection_matrix(1.0)[1, 1])
    # (colour, depth z, rows covered within the pixel row)
    strands = [((1.0, 0.0, 0.0), 0.02, (0.1, 0.4)), ((0.0, 1.0, 0.0), 0.0, (0.25, 0.75)),
               ((0.0, 0.0, 1.0), -0.02, (0.55, 0.95))]
    scene = weft.Scene()
    scene.ambient = (1.0, 1.0, 1.0)  # no lights: a strand shows its diffuse colour
    for i in order:
        colour, z, (lo, hi) = strands[i]
        metres_per_row = 2.0 * (dist - z) / (p11 * H)
        y = -((row + 0.5 * (lo + hi)) / H * 2.0 - 1.0) * (dist - z) / p11  # rows grow downwards
        points = np.array([[-1.5, y, z], [1.5, y, z]], np.float32)
        width = (hi - lo) * metres_per_row
        scene.add_hair(weft.HairStrands(points, default_segments=1, default_thickness=width),
                       weft.HairMaterial("kajiya_kay", diffuse=colour, specular=(0.0, 0.0, 0.0)))
    r = weft.Renderer(W, H, shadow_map_size=64)  # msaa 4: anti-aliased
    r.hair_primitive = "ribbons"
    r.hair_width = 1.0  # a strand's width is its thickness in metres
    img = r.render_linear(scene, cam)[..., :3]
    assert "hair_fringe" in pass_names(r)
    got = img[row, 10:22]
    np.testing.assert_allclose(got, np.tile([0.3, 0.35, 0.2], (12, 1)), atol=0.03)
    assert np.abs(img[row - 1, 10:22]).max() < 0.01 and np.abs(img[row + 1, 10:22]).max() < 0.01


@pytest.mark.parametrize("model", ["kajiya_kay", "sadeghi", "marschner"])
def test_fragment_shading_matches_numpy_model(model):
    r = weft.Renderer(64, 64, shadow_map_size=64)
    scene = weft.Scene()
    scene.ambient = (0.05, 0.04, 0.03)
    rng = np.random.default_rng(3)
    n = 12
    pts = []
    for i in range(n):  # bent strands: tangents vary along and between strands
        s = np.linspace(0, 1, 9)
        a = rng.uniform(0, np.pi)
        pts.append(np.stack([0.6 * (s - 0.5) * np.cos(a), 0.3 * np.sin(3 * s + i) - 0.1 + 0.02 * i,
                             0.6 * (s - 0.5) * np.sin(a)], axis=1))
    strands = weft.HairStrands(np.concatenate(pts).astype(np.float32), default_segments=8,
                               colors=rng.uniform(0.3, 1.0, (n * 9, 3)).astype(np.float32))
    material = weft.HairMaterial(model, diffuse=(0.4, 0.3, 0.2))
    scene.add_hair(strands, material)
    light_dir = np.array([0.4, -1.0, -0.3])
    scene.add_light(weft.DirectionalLight(tuple(light_dir), (1.0, 0.9, 0.8), 1.5, False))
    cam = camera_at(1.5, target=(0, 0.05, 0))
    d = r.render_debug(scene, cam)
    mask = d["hair"] == 0
    assert mask.sum() > 100
    p = d["position"][mask].astype(np.float64)
    t = d["normal"][mask].astype(np.float64)
    strand = np.rint(d["uv"][mask][:, 0]).astype(np.uint32)
    diffuse = d["albedo"][mask].astype(np.float64)
    v = np.array(cam.position) - p
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    l = np.tile(-light_dir / np.linalg.norm(light_dir), (len(p), 1))
    params = R.HairParams.from_material(material)
    expected = np.empty_like(p)
    for i in range(len(p)):  # per-pixel diffuse colour (material diffuse x strand colour)
        params_i = dataclasses.replace(params, diffuse=tuple(diffuse[i]))
        expected[i] = R.shade(params_i, t[i:i + 1], l[i:i + 1], v[i:i + 1], strand[i:i + 1])[0]
    radiance = np.array([1.0, 0.9, 0.8]) * 1.5
    expected = expected * radiance + np.array(scene.ambient) * diffuse
    got = d["linear"][mask][:, :3]
    np.testing.assert_allclose(got, expected, rtol=2e-3, atol=2e-3)


def test_bad_hair_input_raises(small):
    scene = weft.Scene()
    with pytest.raises((ValueError, TypeError)):
        scene.add_hair(None)
    strands = strands_along_x([0.0], [0.0])
    with pytest.raises(ValueError):
        scene.add_hair(strands, transform=np.zeros((4, 4)))
    hid = scene.add_hair(strands)
    with pytest.raises(ValueError):
        scene.set_hair_material(hid, weft.HairMaterial(eta=0.5))
    with pytest.raises(ValueError):
        scene.set_hair_transform(hid + 1, np.eye(4))
    for name, value in [("hair_primitive", "tubes"), ("hair_oit_weight", "eq11"),
                        ("hair_dom_spacing", "cubic"), ("hair_width", float("nan")),
                        ("hair_width", 0.0), ("hair_dom_layer_size", -1.0), ("hair_dom_size", 4)]:
        with pytest.raises(ValueError):
            setattr(small, name, value)
    small.render(scene, camera_at())
    with pytest.raises(ValueError):
        small.hair_dom_map(0)  # no light, no deep opacity map
    assert scene.hair_count == 1


def test_add_fur_grows_fur_on_a_mesh_instance(small):
    scene = weft.Scene()
    mesh = weft.Mesh.uv_sphere(0.3, 8, 6)
    move = np.eye(4)
    move[1, 3] = 0.2
    scene.add_mesh(mesh, transform=move)
    hid = weft.add_fur(scene, mesh, weft.HairMaterial("kajiya_kay"), move, segments=4,
                       length=0.1)
    assert hid == 0 and scene.hair_count == 1
    lo, hi = scene.bounds()
    assert hi[1] > 0.2 + 0.3 + 0.05  # the fur sticks out of the moved sphere
    small.render(scene, camera_at(2.0, target=(0, 0.2, 0)))
    assert hair_passes(small) == OPAQUE
    with pytest.raises(ValueError):
        weft.add_fur(scene, mesh, segments=0)


def test_constant_environment_lights_hair_analytically():
    """A constant environment of radiance L gives E = pi L for every direction, so a fibre with
    no light but the environment shows (I_A + L) * diffuse exactly (SPEC §4.4 on hair)."""
    import weft.ibl as ibl

    scene = weft.Scene()
    fur = weft.generate_fur(weft.Mesh.uv_sphere(0.3, 16, 8), level=3, length=0.08)
    mat = weft.HairMaterial("kajiya_kay")
    mat.diffuse = (0.5, 0.3, 0.2)
    scene.add_hair(fur, mat)
    scene.ambient = (0.1, 0.1, 0.1)
    camera = weft.Camera(position=(0, 0.3, 1.5), target=(0, 0, 0))
    r = weft.Renderer(48, 48)
    scene.set_environment(ibl.CubeMap(np.full((6, 16, 16, 3), 0.8, np.float32)))
    d = r.render_debug(scene, camera)
    hair = d["hair"] >= 0
    assert hair.sum() > 200
    expected = (0.1 + 0.8) * np.array([0.5, 0.3, 0.2])
    np.testing.assert_allclose(d["linear"][hair][:, :3], np.broadcast_to(expected, (hair.sum(), 3)),
                               atol=2e-3)
