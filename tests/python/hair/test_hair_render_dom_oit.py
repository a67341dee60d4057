"""The renderer's deep opacity maps and weighted blended OIT against the NumPy references
weft.reference.hair_shadow and weft.reference.hair_oit (SPEC §5.3, §5.4)."""

from __future__ import annotations

import numpy as np
import pytest
import weft
from weft.reference import hair_oit as O
from weft.reference import hair_shadow as S
from weft.reference import storage_excess

ROWS, PER_ROW, THICK, ALPHA = 16, 40, 0.2, 0.05


def slab_scene():
    """reference slab: ROWS x PER_ROW straight strands along X filling y in [0, THICK], each of
    opacity ALPHA, lit from above by a shadow-casting directional light."""
    points, offsets, _ = S.slab_scene(PER_ROW, ROWS, THICK)
    strands = weft.HairStrands(points.astype(np.float32), default_segments=1,
                               default_transparency=1.0 - ALPHA)
    scene = weft.Scene()
    scene.ambient = (0.0, 0.0, 0.0)
    scene.add_hair(strands, weft.HairMaterial("kajiya_kay", diffuse=(0.5, 0.5, 0.5)))
    scene.add_light(weft.DirectionalLight((0, -1, 0), (1, 1, 1), 1.0, True))
    return scene, points, offsets


def slab_renderer(spacing):
    r = weft.Renderer(64, 64, shadow_map_size=64)
    r.hair_dom_size = ROWS
    r.hair_dom_spacing = spacing
    r.hair_transparency = False  # opaque strands in the camera view; the DOM uses their alpha
    return r


def reference_fragments(points, offsets, dom):
    grid = S.LightGrid(direction=dom["direction"], center=dom["center"], extent=dom["extent"],
                       resolution=dom["resolution"])
    pix, dep, alp = S.rasterize_segments(points, offsets, np.full(len(points), ALPHA), grid)
    return grid, pix, dep, alp


@pytest.mark.parametrize("spacing", ["linear", "log"])
def test_deep_opacity_layers_equal_the_reference(spacing):
    scene, points, offsets = slab_scene()
    r = slab_renderer(spacing)
    r.render(scene, weft.Camera((0, 0.1, 2.0), (0, 0.1, 0), (0, 1, 0), 0.8))
    assert "hair_dom_opacity" in [p["name"] for p in r.stats["passes"]]
    dom = r.hair_dom_map(0)
    assert dom["spacing"] == spacing
    grid, pix, dep, alp = reference_fragments(points, offsets, dom)
    z0 = S.depth_pass(pix, dep, ROWS * ROWS)
    bounds = S.layer_bounds(dom["layer_size"], 3, spacing)
    ref = S.opacity_layers(pix, dep, alp, z0, bounds).reshape(ROWS, ROWS, 3)
    got = dom["opacity"]
    # Lines cover the pixels between their ends; the end pixels depend on the rasteriser's rule.
    inner = (slice(None), slice(1, ROWS - 1))
    np.testing.assert_allclose(got[..., :3][inner], ref[inner], atol=1.0 / 255.0)
    stored = (z0.reshape(ROWS, ROWS) - dom["near"]) / (dom["far"] - dom["near"])
    np.testing.assert_allclose(got[..., 3][inner], stored[inner], atol=1e-5)


def test_slab_transmittance_follows_the_layers_and_exp_minus_k_depth():
    scene, points, offsets = slab_scene()
    r = slab_renderer("linear")
    d = r.render_debug(scene, weft.Camera((0, 0.1, 2.0), (0, 0.1, 0), (0, 1, 0), 0.7))
    dom = r.hair_dom_map(0)
    mask = d["hair"] == 0
    p = d["position"][mask].astype(np.float64)
    vis = d["shadow"][mask].astype(np.float64)
    assert mask.sum() > 200
    grid, pix, dep, alp = reference_fragments(points, offsets, dom)
    q = grid.to_light(p)
    qp = np.floor(q[:, 1]).astype(int) * ROWS + np.floor(q[:, 0]).astype(int)
    inside = (q[:, 0] >= 1) & (q[:, 0] < ROWS - 1)
    # pass 3 = reference lookup on the GPU's own layers
    layers = dom["opacity"][..., :3].reshape(-1, 3).astype(np.float64)
    z0 = dom["opacity"][..., 3].reshape(-1).astype(np.float64) * (dom["far"] - dom["near"]) \
        + dom["near"]
    z0[dom["opacity"][..., 3].reshape(-1) >= 1.0] = np.inf
    bounds = S.layer_bounds(dom["layer_size"], 3, "linear")
    lookup = S.transmittance(S.occlusion_at(layers, z0, bounds, qp[inside], q[inside, 2]))
    np.testing.assert_allclose(vis[inside], lookup, atol=2e-3)
    # a uniform slab: transmittance ~ exp(-k depth), k = alpha n / thickness
    k = ALPHA * PER_ROW / THICK
    analytic = np.exp(-k * (THICK - p[inside, 1]))
    err = np.abs(vis[inside] - analytic)
    assert err.mean() < 0.03 and err.max() < 0.12


def test_deep_opacity_darkens_the_hair_below():
    scene, _, _ = slab_scene()
    r = slab_renderer("linear")
    cam = weft.Camera((0, 0.1, 2.0), (0, 0.1, 0), (0, 1, 0), 0.7)
    d = r.render_debug(scene, cam)
    mask = d["hair"] == 0
    y = d["position"][mask][:, 1]
    top, bottom = d["linear"][mask][y > 0.17, 0].mean(), d["linear"][mask][y < 0.03, 0].mean()
    assert bottom < 0.5 * top


def layer_scene(colors, alphas, zs):
    """One wide ribbon per layer facing a camera on +Z: strands along X at depth z."""
    scene = weft.Scene()
    scene.ambient = (1.0, 1.0, 1.0)  # no lights: a layer's colour is its diffuse colour
    scene.background = (0.2, 0.3, 0.4)
    for c, a, z in zip(colors, alphas, zs):
        points = np.array([[-1.0, 0.0, z], [1.0, 0.0, z]], np.float32)
        strands = weft.HairStrands(points, default_segments=1, default_transparency=1.0 - a)
        scene.add_hair(strands, weft.HairMaterial("kajiya_kay", diffuse=tuple(c),
                                                  specular=(0.0, 0.0, 0.0)))
    return scene


@pytest.mark.parametrize("weight", ["eq7", "eq8", "eq9", "eq10"])
def test_wboit_composite_equals_the_reference(weight):
    colors = np.array([[0.9, 0.1, 0.1], [0.1, 0.8, 0.2], [0.2, 0.3, 0.9], [0.7, 0.7, 0.1]])
    alphas = np.array([0.3, 0.5, 0.6, 0.25])
    zs = np.array([0.5, -0.3, 0.1, -1.0])  # drawn in this (unsorted) order
    scene = layer_scene(colors, alphas, zs)
    r = weft.Renderer(32, 32, shadow_map_size=64)
    r.hair_primitive = "ribbons"
    r.hair_width = 0.5
    r.hair_oit_weight = weight
    cam = weft.Camera((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), (0, 1, 0), 0.6)
    img = r.render_linear(scene, cam)
    assert [p["name"] for p in r.stats["passes"]][-3:-1] == ["hair_oit", "hair_composite"]
    view_z = 3.0 - zs
    clip = cam.projection_matrix(1.0) @ cam.view_matrix() @ np.c_[np.zeros((4, 2)), zs,
                                                                   np.ones(4)].T
    z_ndc = clip[2] / clip[3]
    expected = O.wboit_composite(colors, alphas, view_z, z_ndc, np.array(scene.background), weight)
    got = img[14:18, 14:18, :3].reshape(-1, 3)
    np.testing.assert_allclose(got, np.tile(expected, (16, 1)), atol=2e-3)
    # no hair: background kept (to the linear target's half-float rounding)
    assert storage_excess(img[0, 0, :3], scene.background).max() <= 1e-6


@pytest.mark.parametrize("name,alias", [("near_quadratic", "eq7"), ("near_cubic", "eq8"),
                                        ("far_quartic", "eq9"), ("ndc_cubic", "eq10")])
def test_oit_weights_are_named_for_their_shape(name, alias):
    """The weights' names (what Renderer.hair_oit_weight reads back) draw exactly what the
    equation-number aliases draw, and each weight differs from the default's image."""
    scene = layer_scene(np.array([[0.9, 0.1, 0.1], [0.1, 0.8, 0.2]]), np.array([0.5, 0.6]),
                        np.array([0.5, -8.0]))
    cam = weft.Camera((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), (0, 1, 0), 0.6)
    images = {}
    for w in (name, alias, "near_quadratic"):
        r = weft.Renderer(16, 16, shadow_map_size=64)
        r.hair_primitive, r.hair_width = "ribbons", 0.5
        r.hair_oit_weight = w
        assert r.hair_oit_weight == (name if w != "near_quadratic" else w)
        images[w] = r.render_linear(scene, cam)
    assert weft.Renderer(8, 8).hair_oit_weight == "near_quadratic"
    assert np.array_equal(images[name], images[alias])
    if name != "near_quadratic":
        assert not np.array_equal(images[name], images["near_quadratic"])


def test_one_renderer_switching_oit_weights_draws_what_fresh_ones_draw():
    """Each weight has its own pipelines (kOitWeight): switching must pick them up."""
    scene = layer_scene(np.array([[0.9, 0.1, 0.1], [0.1, 0.8, 0.2]]), np.array([0.5, 0.6]),
                        np.array([0.5, -8.0]))
    cam = weft.Camera((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), (0, 1, 0), 0.6)

    def renderer():
        r = weft.Renderer(16, 16, shadow_map_size=64)
        r.hair_primitive, r.hair_width = "ribbons", 0.5
        return r

    one = renderer()
    weights = ["near_quadratic", "near_cubic", "far_quartic", "ndc_cubic"]
    for w in weights + weights[::-1]:
        one.hair_oit_weight = w
        fresh = renderer()
        fresh.hair_oit_weight = w
        np.testing.assert_array_equal(one.render_linear(scene, cam),
                                      fresh.render_linear(scene, cam))


def test_meshes_shadow_hair_under_a_deep_opacity_map():
    """A board between the light and half of the slab: with the DOM on, the hair under it is in
    its shadow (visibility 0) while the other half keeps the DOM's transmittance; a board that
    casts no shadow changes nothing, and without mesh casters the pass is skipped."""
    cam = weft.Camera((0, 0.1, 2.0), (0, 0.1, 0), (0, 1, 0), 0.7)
    r = slab_renderer("linear")
    scene, _, _ = slab_scene()
    bare = r.render_debug(scene, cam)
    assert "hair_dom_meshes" not in [p["name"] for p in r.stats["passes"]]
    board = np.eye(4, dtype=np.float32)
    board[:3, 3] = (-0.35, 0.6, 0.0)  # above the slab's x < 0 half, well before the DOM's near
    scene.add_mesh(weft.Mesh.box((0.7, 0.05, 1.4)), transform=board)
    d = r.render_debug(scene, cam)
    assert "hair_dom_meshes" in [p["name"] for p in r.stats["passes"]]
    hair = (d["hair"] == 0) & (bare["hair"] == 0)
    x = d["position"][..., 0]
    under, free = hair & (x < -0.1), hair & (x > 0.1)
    assert under.sum() > 50 and free.sum() > 50
    assert d["shadow"][under].max() == 0.0
    np.testing.assert_allclose(d["shadow"][free], bare["shadow"][free], atol=1e-6)
    assert bare["shadow"][under].mean() > 0.3  # the DOM alone lets light through there
    # the same board not casting shadows: the hair is lit as without it
    scene, _, _ = slab_scene()
    scene.add_mesh(weft.Mesh.box((0.7, 0.05, 1.4)), transform=board, cast_shadows=False)
    d = r.render_debug(scene, cam)
    assert "hair_dom_meshes" not in [p["name"] for p in r.stats["passes"]]
    np.testing.assert_allclose(d["shadow"][under], bare["shadow"][under], atol=1e-6)
