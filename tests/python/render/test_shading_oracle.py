"""The GPU's Blinn-Phong shading (SPEC §1.3 eq. 2.5, 2.8–2.10) against the NumPy oracle of
weft.reference.shading, evaluated from the debug outputs of the same frame."""

from __future__ import annotations

import dataclasses
import math
from types import SimpleNamespace
from typing import Dict, List, Tuple

import numpy as np
import pytest
import weft
from weft import reference as ref

LINEAR_TOL = 1e-3
U8_TOL = 1
# The shading oracle takes T (base colour x texture sample) from the frame's albedo output and is
# held to LINEAR_TOL on every covered pixel. Texture sampling itself is checked separately against
# NumPy: its precision is the Vulkan implementation's choice. lavapipe (llvmpipe) approximates the
# sRGB decode (texel values off by up to 1.2e-3) and filters UNORM8 textures in 8-bit fixed point
# (results on the 1/255 grid); NVIDIA's driver (580, on an H200) decodes sRGB texels to within
# 3.75e-3 (just under one 8-bit step in linear); test_texture_sampling_precision measures both
# and the filter's weights too. The allowance is one 8-bit step either way: a missing or doubled
# sRGB decode is off by 0.2 and more.
TEXTURE_TOL = {True: 1.0 / 255.0 + 1e-4, False: 1.0 / 255.0 + 1e-4}  # by Texture.srgb


def translation(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = (x, y, z)
    return m


def rotation_y(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    m = np.eye(4, dtype=np.float32)
    m[0, 0], m[0, 2], m[2, 0], m[2, 2] = c, s, -s, c
    return m


# --------------------------------------------------------------------------------------------
# The oracle itself, on synthetic data
# --------------------------------------------------------------------------------------------

def test_srgb_round_trip_and_known_values() -> None:
    x = np.linspace(0.0, 1.0, 1001)
    assert np.allclose(ref.srgb_decode(ref.srgb_encode(x)), x, atol=1e-12)
    assert ref.srgb_encode(0.0031308) == pytest.approx(12.92 * 0.0031308)
    assert ref.srgb_encode(0.5) == pytest.approx(1.055 * 0.5 ** (1 / 2.4) - 0.055)
    assert int(ref.encode_u8(0.5)) == 188
    assert int(ref.encode_u8(2.0)) == 255 and int(ref.encode_u8(-1.0)) == 0


def test_bilinear_repeat_synthetic() -> None:
    rng = np.random.default_rng(1)
    tex = rng.random((4, 5, 3))
    j, i = np.meshgrid(np.arange(4), np.arange(5), indexing="ij")
    centres = np.stack([(i + 0.5) / 5, (j + 0.5) / 4], axis=-1)
    assert np.allclose(ref.sample_bilinear_repeat(tex, centres), tex)
    assert np.allclose(ref.sample_bilinear_repeat(tex, centres + 2.0), tex)
    assert np.allclose(ref.sample_bilinear_repeat(tex, centres - 1.0), tex)
    # halfway between the last and the first column wraps around
    edge = ref.sample_bilinear_repeat(tex, np.array([1.0, 0.5 / 4]))
    assert np.allclose(edge, 0.5 * (tex[0, 0] + tex[0, 4]))
    # a quarter of the way between two texel centres
    q = ref.sample_bilinear_repeat(tex, np.array([(1.5 + 0.25) / 5, (2.5 + 0.5) / 4]))
    top = 0.75 * tex[2, 1] + 0.25 * tex[2, 2]
    bottom = 0.75 * tex[3, 1] + 0.25 * tex[3, 2]
    assert np.allclose(q, 0.5 * (top + bottom))


def test_texture_to_linear_channels() -> None:
    grey = np.array([[0, 255]], dtype=np.uint8)
    lin = ref.texture_to_linear(grey)
    assert lin.shape == (1, 2, 4)
    assert np.allclose(lin[0, 1], 1.0) and np.allclose(lin[0, 0, :3], 0.0)
    rgb = np.full((1, 1, 3), 128, dtype=np.uint8)
    assert np.allclose(ref.texture_to_linear(rgb)[0, 0, :3], ref.srgb_decode(128 / 255))
    assert np.allclose(ref.texture_to_linear(rgb, srgb=False)[0, 0, :3], 128 / 255)
    grey_alpha = np.array([[[255, 7]]], dtype=np.uint8)
    assert np.allclose(ref.texture_to_linear(grey_alpha)[0, 0], [1.0, 1.0, 1.0, 7 / 255])
    with pytest.raises(ValueError):
        ref.texture_to_linear(np.zeros((2, 2, 5), dtype=np.uint8))


def test_mip_chain_trilinear_and_lod_synthetic() -> None:
    rng = np.random.default_rng(2)
    tex = rng.random((4, 4, 3))
    levels = ref.build_mip_chain(tex, quantize=False)
    assert [lvl.shape[:2] for lvl in levels] == [(4, 4), (2, 2), (1, 1)]
    box = tex.reshape(2, 2, 2, 2, 3).mean(axis=(1, 3))
    assert np.allclose(levels[1], box)
    assert np.allclose(levels[2][0, 0], tex.reshape(-1, 3).mean(axis=0))
    assert [lvl.shape[:2] for lvl in ref.build_mip_chain(rng.random((2, 8, 3)))] == [
        (2, 8), (1, 4), (1, 2), (1, 1)]
    quantized = ref.build_mip_chain(np.full((2, 2, 3), ref.srgb_decode(0.5)), srgb=True)
    assert np.allclose(quantized[1], ref.srgb_decode(np.rint(0.5 * 255) / 255))
    uv = rng.random((50, 2))
    at0 = ref.sample_trilinear_repeat(levels, uv, 0.0)
    assert np.allclose(at0, ref.sample_bilinear_repeat(levels[0], uv))
    at1 = ref.sample_trilinear_repeat(levels, uv, 1.0)
    assert np.allclose(at1, ref.sample_bilinear_repeat(levels[1], uv))
    half = ref.sample_trilinear_repeat(levels, uv, np.full(50, 0.5))
    assert np.allclose(half, 0.5 * (at0 + at1))
    assert np.allclose(ref.sample_trilinear_repeat(levels, uv, 9.0), levels[2][0, 0])
    assert np.allclose(ref.sample_trilinear_repeat(levels, uv, -3.0), at0)
    # uv advancing 1/32 per pixel in x and 1/64 in y on a 128x128 texture: rho = 4 -> lod 2
    ys, xs = np.mgrid[0:16, 0:24].astype(np.float64)
    uv_img = np.stack([xs / 32.0, ys / 64.0], axis=-1)
    labels = np.zeros((16, 24), dtype=int)
    assert np.allclose(ref.texture_lod(uv_img, labels, 128, 128), 2.0)
    # a second object on the right: its pixels must not leak into the derivatives
    labels[:, 13:] = 1
    uv_img[:, 13:] = 0.5
    lod = ref.texture_lod(uv_img, labels, 128, 128)
    assert np.allclose(lod[:, :13], 2.0)


def test_blinn_phong_synthetic() -> None:
    p = np.zeros((1, 3))
    n = np.array([[0.0, 1.0, 0.0]])
    overhead = ref.LightDesc(direction=(0, -1, 0), color=(1, 0.5, 0.25), intensity=2.0)
    c = ref.blinn_phong(p, n, (0, 2, 0), [overhead], (0.1, 0.2, 0.3), albedo=np.full((1, 3), 0.5),
                        ka=(1, 1, 0.5), kd=0.8, ks=0.25, shininess=40)
    radiance = np.array([2.0, 1.0, 0.5])
    expected = np.array([0.1, 0.2, 0.15]) * 0.5 + radiance * 0.8 * 0.5 + radiance * 0.25
    assert np.allclose(c, expected)
    # 45-degree light, viewer along the normal
    l = np.array([0.0, 1.0, 1.0]) / math.sqrt(2.0)
    h = (l + np.array([0.0, 1.0, 0.0]))
    h /= np.linalg.norm(h)
    c = ref.blinn_phong(p, n, (0, 3, 0), [dict(direction=-l, color=(1, 1, 1), intensity=1.0,
                                               cast_shadows=False)],
                        0.0, albedo=np.ones((1, 3)), ks=1.0, shininess=40)
    assert np.allclose(c, math.cos(math.pi / 4) + h[1] ** 40)
    # a light from below contributes nothing, not even specular
    c = ref.blinn_phong(p, n, (0, 2, 0), [ref.LightDesc(direction=(0, 1, 0))], 0.0,
                        albedo=np.ones((1, 3)), ks=1.0)
    assert np.allclose(c, 0.0)
    # shadow only affects the first shadow-casting light
    lights = [ref.LightDesc((0, -1, 0), cast_shadows=False), ref.LightDesc((0, -1, 0))]
    c = ref.blinn_phong(p, n, (0, 2, 0), lights, 0.0, albedo=np.ones((1, 3)), shadow=[0.25])
    assert np.allclose(c, 1.0 + 0.25)


def test_pcf_synthetic() -> None:
    # orthographic light straight down: x -> u, z -> v, depth = 0.5 - 0.5 y
    view_proj = np.array([[1, 0, 0, 0], [0, 0, 1, 0], [0, -0.5, 0, 0.5], [0, 0, 0, 1.0]])
    smap = np.full((8, 8), 0.5)
    smap[:, :4] = 0.25  # an occluder above x < 0
    info = dict(view_proj=view_proj, normal_offset_world=0.0, bias_constant=0.001,
                bias_slope=0.0, bias_max=0.01, pcf_radius=1, active=True, size=8)
    xs = (np.arange(8) + 0.5) / 4.0 - 1.0
    pos = np.stack([xs, np.zeros(8), np.zeros(8)], axis=-1)
    nrm = np.tile([0.0, 1.0, 0.0], (8, 1))
    look = ref.shadow_lookup(pos, nrm, (0, -1, 0), smap, info)
    assert np.allclose(look.visibility, [0, 0, 0, 1 / 3, 2 / 3, 1, 1, 1])
    assert np.allclose(look.depth, 0.5)
    hard = ref.pcf_visibility(pos, nrm, (0, -1, 0), smap, dict(info, pcf_radius=0))
    assert np.allclose(hard, [0, 0, 0, 0, 1, 1, 1, 1])
    # outside the map: lit
    assert ref.pcf_visibility(np.array([[3.0, 0.0, 0.0]]), nrm[:1], (0, -1, 0), smap, info)[0] == 1
    # normal offset moves the receiver along n by offset * sin(angle(n, l))
    tilted = np.tile([1.0, 0.0, 0.0], (1, 1))
    look = ref.shadow_lookup(np.zeros((1, 3)), tilted, (0, -1, 0), smap,
                             dict(info, normal_offset_world=0.5))
    assert look.u[0] == pytest.approx(0.75)


# --------------------------------------------------------------------------------------------
# Oracle vs the renderer
# --------------------------------------------------------------------------------------------

SPHERE_CENTRE = np.array([-0.8, 0.9, 0.1])
SPHERE_RADIUS = 0.6
BOX_CENTRE = np.array([0.9, 0.55, 0.3])
BOX_SIZE = np.array([0.8, 0.8, 0.8])
BOX_ANGLE = 0.5
PLANE_HALF = 3.0


def build_scene(smooth_texture, srgb: bool = False) -> Tuple[
        weft.Scene, weft.Camera, List[ref.SurfaceMaterial]]:
    """Plane, floating sphere and floating rotated box; three lights, the second one casting
    shadows; textured materials with mipmaps=False (sRGB-encoded texels or UNORM data),
    specular highlights with shininess 40."""
    scene = weft.Scene()
    plane_img = smooth_texture(64, 64, 3)
    sphere_img = smooth_texture(32, 64, 4, phase=1.0)
    plane_mat = weft.Material(ka=(0.9, 0.8, 1.0), kd=(0.8, 0.85, 0.9), ks=(0.2, 0.2, 0.2),
                              shininess=40.0, base_color=(1.0, 0.95, 0.9),
                              texture=weft.Texture(plane_img, srgb=srgb, mipmaps=False))
    sphere_mat = weft.Material(ka=(1.0, 1.0, 1.0), kd=(0.9, 0.7, 0.6), ks=(0.5, 0.5, 0.5),
                               shininess=40.0, base_color=(1.0, 1.0, 1.0),
                               texture=weft.Texture(sphere_img, srgb=srgb, mipmaps=False))
    box_mat = weft.Material(ka=(0.5, 0.5, 0.5), kd=(1.0, 1.0, 1.0), ks=(0.3, 0.3, 0.3),
                            shininess=12.0, base_color=(0.3, 0.6, 0.9))
    scene.add_mesh(weft.Mesh.plane(2 * PLANE_HALF, 2 * PLANE_HALF, 4, 4), plane_mat)
    scene.add_mesh(weft.Mesh.uv_sphere(SPHERE_RADIUS, 48, 24), sphere_mat,
                   translation(*SPHERE_CENTRE))
    box_transform = translation(*BOX_CENTRE) @ rotation_y(BOX_ANGLE)
    scene.add_mesh(weft.Mesh.box(tuple(BOX_SIZE)), box_mat, box_transform)
    scene.add_light(weft.DirectionalLight(direction=(0.6, -0.5, 0.4), color=(0.4, 0.5, 0.8),
                                          intensity=0.6, cast_shadows=False))
    scene.add_light(weft.DirectionalLight(direction=(-0.4, -1.0, -0.3), color=(1.0, 0.95, 0.9),
                                          intensity=1.1, cast_shadows=True))
    scene.add_light(weft.DirectionalLight(direction=(0.0, 0.3, -1.0), color=(0.3, 0.2, 0.1),
                                          intensity=0.8, cast_shadows=False))
    scene.ambient = (0.15, 0.12, 0.1)
    scene.background = (0.2, 0.3, 0.5)
    camera = weft.Camera(position=(0.6, 2.6, 5.0), target=(0.0, 0.4, 0.0), up=(0.0, 1.0, 0.0),
                         fov_y=0.8, near=0.1, far=50.0)
    materials = [ref.SurfaceMaterial.from_weft(plane_mat, plane_img, texture_srgb=srgb),
                 ref.SurfaceMaterial.from_weft(sphere_mat, sphere_img, texture_srgb=srgb),
                 ref.SurfaceMaterial.from_weft(box_mat)]
    return scene, camera, materials


def label_pixels(debug: Dict[str, np.ndarray]) -> np.ndarray:
    """Which instance (0 plane, 1 sphere, 2 box) each covered pixel shows, from its world
    position (the objects do not touch, so this is unambiguous)."""
    mask = debug["mask"]
    p = debug["position"].astype(np.float64)
    labels = np.full(mask.shape, -1, dtype=np.int64)
    on_plane = (np.abs(p[..., 1]) < 1e-3) & (np.abs(p[..., 0]) <= PLANE_HALF + 1e-3) \
        & (np.abs(p[..., 2]) <= PLANE_HALF + 1e-3)
    on_sphere = np.abs(np.linalg.norm(p - SPHERE_CENTRE, axis=-1) - SPHERE_RADIUS) < 0.02
    local = (p - BOX_CENTRE) @ rotation_y(BOX_ANGLE)[:3, :3].astype(np.float64)
    on_box = np.all(np.abs(local) <= BOX_SIZE / 2 + 1e-3, axis=-1)
    for index, sel in enumerate((on_plane, on_sphere, on_box)):
        labels[mask & sel] = index
    hits = on_plane.astype(int) + on_sphere.astype(int) + on_box.astype(int)
    assert not np.any(mask & (hits != 1)), "pixels that match no or several objects"
    return labels


@pytest.fixture(params=[False, True], ids=["unorm_texture", "srgb_texture"])
def oracle_frame(request, smooth_texture):
    srgb = request.param
    scene, camera, materials = build_scene(smooth_texture, srgb=srgb)
    renderer = weft.Renderer(192, 144, shadow_map_size=1024, pcf_radius=1, msaa=1,
                             bounce=False, ambient_occlusion=0)  # the oracle shades locally
    debug = renderer.render_debug(scene, camera)
    labels = label_pixels(debug)
    if "instance" in debug:
        assert np.array_equal(np.where(debug["mask"], debug["instance"], -1), labels)
    # The shading equation with T taken from the frame (strict), and the whole pipeline with T
    # sampled in NumPy (within the sampler's precision, see TEXTURE_TOL).
    oracle = ref.shade_debug_frame(debug, camera.position, scene.lights, scene.ambient,
                                   scene.background, materials, labels=labels, frame_albedo=True)
    sampled = ref.shade_debug_frame(debug, camera.position, scene.lights, scene.ambient,
                                    scene.background, materials, labels=labels)
    # d(colour)/d(T) = I_A K_A + sum vis (n.l) L K_D: the untextured, non-specular colour
    plain = [dataclasses.replace(m, ks=(0.0, 0.0, 0.0), texture=None, base_color=(1.0, 1.0, 1.0))
             for m in materials]
    sensitivity = ref.shade_debug_frame(debug, camera.position, scene.lights, scene.ambient,
                                        (0.0, 0.0, 0.0), plain, labels=labels)[..., :3]
    textured = np.isin(labels, [i for i, m in enumerate(materials) if m.texture is not None])
    tol = LINEAR_TOL + TEXTURE_TOL[srgb] * sensitivity * textured[..., None]
    return SimpleNamespace(scene=scene, camera=camera, renderer=renderer, debug=debug,
                           labels=labels, oracle=oracle, sampled=sampled, materials=materials,
                           srgb=srgb, tol=tol)


def test_debug_outputs_shapes(oracle_frame) -> None:
    debug = oracle_frame.debug
    h, w = 144, 192
    expected = {"color": ((h, w, 4), np.uint8), "linear": ((h, w, 4), np.float32),
                "position": ((h, w, 3), np.float32), "mask": ((h, w), np.bool_),
                "normal": ((h, w, 3), np.float32), "shadow": ((h, w), np.float32),
                "uv": ((h, w, 2), np.float32), "light_depth": ((h, w), np.float32)}
    for key, (shape, dtype) in expected.items():
        assert key in debug, key
        assert debug[key].shape == shape, (key, debug[key].shape)
        assert debug[key].dtype == dtype, (key, debug[key].dtype)
    mask = debug["mask"]
    if "instance" in debug:  # optional: which scene instance covers each pixel, -1 = none
        assert debug["instance"].shape == (h, w)
        assert np.all(debug["instance"][~mask] == -1) and np.all(debug["instance"][mask] >= 0)
    assert 0.3 < mask.mean() < 0.99
    assert np.all(debug["color"][..., 3] == 255)
    assert np.allclose(np.linalg.norm(debug["normal"][mask], axis=-1), 1.0, atol=1e-4)
    shadow = debug["shadow"][mask]
    assert np.all((shadow >= 0.0) & (shadow <= 1.0))
    assert np.any(shadow == 0.0) and np.any(shadow == 1.0)


def test_every_object_is_visible(oracle_frame) -> None:
    labels = oracle_frame.labels
    for index, name in enumerate(("plane", "sphere", "box")):
        assert np.count_nonzero(labels == index) > 200, f"{name} barely visible"


def test_linear_matches_oracle(oracle_frame) -> None:
    """The shading equation (eq. 2.5, 2.8-2.10 with PCF shadows) evaluated in NumPy from the
    frame's debug outputs agrees with the rendered linear colour to 1e-3 on every covered
    pixel, textured or not."""
    debug, oracle = oracle_frame.debug, oracle_frame.oracle
    mask = debug["mask"]
    diff = np.abs(debug["linear"][..., :3].astype(np.float64) - oracle[..., :3])
    err = diff[mask]
    worst = np.unravel_index(np.argmax(np.where(mask[..., None], diff, 0)), diff.shape)
    assert err.max() <= LINEAR_TOL, (
        f"max |linear - oracle| = {err.max():.3g} at pixel {worst[:2]} "
        f"(gpu {debug['linear'][worst[:2]]}, oracle {oracle[worst[:2]]}), mean {err.mean():.3g}")
    assert np.allclose(debug["linear"][..., 3][mask], 1.0)


def test_albedo_matches_numpy_texture_sampling(oracle_frame) -> None:
    """T from the frame equals base colour times NumPy's bilinear (REPEAT, texel centres at
    (i+0.5)/W) sample of the texture, within the sampler precision Vulkan leaves to the
    implementation (TEXTURE_TOL); untextured materials give their base colour exactly."""
    fr = oracle_frame
    debug, labels = fr.debug, fr.labels
    mask = debug["mask"]
    maps = ref.material_maps(fr.materials, np.where(mask, labels, -1), debug["uv"])
    err = np.abs(debug["albedo"].astype(np.float64) - maps["albedo"])[mask]
    assert err.max() <= TEXTURE_TOL[fr.srgb], f"max albedo error {err.max():.3g}"
    untextured = labels[mask] == 2
    assert err[untextured].max() <= 1e-6


def test_whole_pipeline_with_numpy_sampling(oracle_frame) -> None:
    """Texture sampling in NumPy too: within 1e-3 plus the sampler allowance scaled by how
    strongly each pixel's colour depends on T."""
    fr = oracle_frame
    debug, sampled = fr.debug, fr.sampled
    mask = debug["mask"]
    err = np.abs(debug["linear"][..., :3].astype(np.float64) - sampled[..., :3])[mask]
    over = err > fr.tol[mask]
    assert not over.any(), f"max error {err.max():.3g}, {np.mean(over.any(axis=-1)):.2%} over"


def test_srgb8_matches_oracle(oracle_frame) -> None:
    debug, oracle = oracle_frame.debug, oracle_frame.oracle
    mask = debug["mask"]
    expected = ref.encode_u8(oracle[..., :3]).astype(np.int64)
    diff = np.abs(debug["color"][..., :3].astype(np.int64) - expected)[mask]
    assert diff.max() <= U8_TOL, f"max 8-bit error {diff.max()}, " \
                                 f"{np.mean(diff.max(axis=-1) > U8_TOL):.2%} of pixels over"


def test_specular_highlights_and_shadows_present(oracle_frame) -> None:
    """The scene really exercises the specular and shadow terms the oracle checks."""
    fr = oracle_frame
    scene, camera, debug = fr.scene, fr.camera, fr.debug
    labels, oracle, materials = fr.labels, fr.oracle, fr.materials
    matte = [dataclasses.replace(m, ks=(0.0, 0.0, 0.0)) for m in materials]
    no_spec = ref.shade_debug_frame(debug, camera.position, scene.lights, scene.ambient,
                                    scene.background, matte, labels=labels)
    spec = np.abs(oracle - no_spec)[..., :3].max(axis=-1)[debug["mask"]]
    assert spec.max() > 0.05, "no visible specular highlight"
    assert np.mean(debug["shadow"][debug["mask"]] < 1.0) > 0.02, "no visible shadow"


def test_background_pixels(oracle_frame) -> None:
    fr = oracle_frame
    scene, debug = fr.scene, fr.debug
    bg = ~debug["mask"]
    assert bg.any()
    background = np.asarray(scene.background, dtype=np.float64)
    assert ref.storage_excess(debug["linear"][bg][:, :3], background).max() <= 1e-6
    assert np.all(debug["linear"][bg][:, 3] == 1.0)
    expected = ref.encode_u8(background)
    assert np.all(np.abs(debug["color"][bg][:, :3].astype(int) - expected.astype(int)) <= U8_TOL)
    assert np.all(debug["color"][bg][:, 3] == 255)


def test_render_and_render_linear_match_debug_frame(oracle_frame) -> None:
    fr = oracle_frame
    scene, camera, renderer, debug = fr.scene, fr.camera, fr.renderer, fr.debug
    color = renderer.render(scene, camera)
    linear = renderer.render_linear(scene, camera)
    assert color.dtype == np.uint8 and color.shape == debug["color"].shape
    assert linear.dtype == np.float32 and linear.shape == debug["linear"].shape
    assert np.abs(color.astype(int) - debug["color"].astype(int)).max() <= 1
    assert np.abs(linear - debug["linear"]).max() <= 1e-5


def test_untextured_single_material_with_one_light(make_renderer) -> None:
    """Simplest case: one untextured material everywhere, one light without shadows."""
    scene = weft.Scene()
    material = weft.Material(ka=(0.2, 0.3, 0.4), kd=(0.7, 0.6, 0.5), ks=(0.4, 0.4, 0.4),
                             shininess=40.0, base_color=(0.9, 0.8, 0.7))
    scene.add_mesh(weft.Mesh.uv_sphere(1.0, 64, 32), material)
    scene.add_light(weft.DirectionalLight(direction=(-1.0, -1.0, -1.0), color=(1.0, 1.0, 1.0),
                                          intensity=1.5, cast_shadows=False))
    scene.ambient = (0.2, 0.2, 0.2)
    scene.background = (0.0, 0.0, 0.0)
    camera = weft.Camera(position=(0.0, 0.5, 3.5), target=(0.0, 0.0, 0.0))
    renderer = make_renderer(128, 96, shadow_map_size=512)
    debug = renderer.render_debug(scene, camera)
    assert np.all(debug["shadow"] == 1.0)
    oracle = ref.shade_debug_frame(debug, camera.position, scene.lights, scene.ambient,
                                   scene.background, ref.SurfaceMaterial.from_weft(material))
    errors = ref.compare_frame(debug, oracle)
    assert errors.covered > 1000
    assert errors.max_abs <= LINEAR_TOL, errors
    assert errors.max_u8 <= U8_TOL, errors


@pytest.mark.parametrize("srgb", [False, True], ids=["unorm", "srgb"])
def test_texture_sampling_precision(make_renderer, srgb: bool) -> None:
    """How exactly the sampler returns texture colour (what TEXTURE_TOL allows for): a plane
    textured with all 256 values in 4x4-texel blocks, read from the debug frame's albedo T (32-bit
    floats; the linear colour is stored in half floats, LINEAR_STORAGE_RTOL). Inside
    the blocks bilinear filtering returns the texel itself (decode precision: UNORM exact, sRGB
    within the allowance); everywhere the result is within the allowance of the oracle's
    float64 bilinear filter, plus what the filter's weights may be off by: Vulkan quantizes
    them to 2^-subTexelPrecisionBits (lavapipe reports 8 bits, and NVIDIA's errors fit 8), so up
    to 2^-8 of the spread of the four texels filtered (1.0 across the texture's wrap: NVIDIA's
    filter was 4.7e-3 off there, lavapipe's UNORM 4.0e-3)."""
    blocks = np.arange(256).reshape(16, 16)
    grey = np.repeat(np.repeat(blocks, 4, axis=0), 4, axis=1).astype(np.uint8)
    image = np.stack([grey, 255 - grey, grey[::-1]], axis=-1)
    scene = weft.Scene()
    material = weft.Material(ka=(1.0, 1.0, 1.0), kd=(0.0, 0.0, 0.0),
                             texture=weft.Texture(image, srgb=srgb, mipmaps=False))
    scene.add_mesh(weft.Mesh.plane(2.0, 2.0), material)
    scene.ambient = (1.0, 1.0, 1.0)
    camera = weft.Camera(position=(0.0, 2.3, 0.001), target=(0.0, 0.0, 0.0), up=(0.0, 0.0, -1.0),
                         fov_y=0.9)
    debug = make_renderer(256, 256, shadow_map_size=256).render_debug(scene, camera)
    mask = debug["mask"]
    uv = debug["uv"][mask].astype(np.float64)
    linear = debug["albedo"][mask][:, :3].astype(np.float64)
    tx, ty = uv[:, 0] * 64.0, uv[:, 1] * 64.0
    inner = (np.abs(tx % 4.0 - 2.0) < 1.4) & (np.abs(ty % 4.0 - 2.0) < 1.4)
    bx, by = (tx[inner] // 4).astype(int), (ty[inner] // 4).astype(int)
    assert len(np.unique(by * 16 + bx)) == 256, "not every texel value was sampled"
    texel = image[by * 4 + 1, bx * 4 + 1].astype(np.float64) / 255.0
    expected = ref.srgb_decode(texel) if srgb else texel
    decode_err = np.abs(linear[inner] - expected).max()
    decode_limit = TEXTURE_TOL[True] if srgb else 1e-5
    assert decode_err <= decode_limit, f"texel decode error {decode_err:.3g} > {decode_limit:g}"
    oracle = ref.SurfaceMaterial.from_weft(material, image, texture_srgb=srgb).albedo(uv)
    # the four texels each sample filters (REPEAT), decoded: their spread per channel
    decoded = ref.srgb_decode(image / 255.0) if srgb else image / 255.0
    x0 = np.floor(uv * 64.0 - 0.5).astype(int)
    quad = np.stack([decoded[(x0[:, 1] + dy) % 64, (x0[:, 0] + dx) % 64]
                     for dy in (0, 1) for dx in (0, 1)])
    allowance = TEXTURE_TOL[srgb] + (quad.max(axis=0) - quad.min(axis=0)) / 256.0
    excess = (np.abs(linear - oracle) - allowance).max()
    assert excess <= 0.0, f"filtered texture error exceeds its allowance by {excess:.3g}"
    # the weights' allowance matters only where neighbouring texels differ: inside the blocks
    # the filter returns the texel within the decode's allowance alone (checked above)


def test_mipmapped_texture_oracle(make_renderer, smooth_texture) -> None:
    """A mip-mapped texture on a plane receding to the horizon. Vulkan lets an implementation
    approximate the scale factor rho within a factor of sqrt(2) (LOD +-0.5) and compute
    derivatives per 2x2 quad (coarse) or per pixel (fine), which near the horizon moves the LOD
    by up to about another 0.5. So the GPU colour must lie inside the envelope of the
    oracle's colours for LODs within +-1 of the estimate, plus LINEAR_TOL and the 8-bit
    sampling allowance, on 99% of the pixels."""
    image = smooth_texture(128, 128, 3)
    material = weft.Material(kd=(0.9, 0.9, 0.9), texture=weft.Texture(image, mipmaps=True))
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(40.0, 40.0, 8, 8), material)
    scene.add_light(weft.DirectionalLight(direction=(-0.3, -1.0, -0.4), cast_shadows=False))
    scene.ambient = (0.2, 0.2, 0.2)
    camera = weft.Camera(position=(0.0, 1.5, 8.0), target=(0.0, 0.0, -10.0), fov_y=1.0)
    debug = make_renderer(192, 128, shadow_map_size=256).render_debug(scene, camera)
    surface = ref.SurfaceMaterial.from_weft(material)
    assert surface.texture_mipmaps and surface.texture_size == (128, 128)
    mask = debug["mask"]
    assert mask.sum() > 5000

    def shade(bias: float, mip: bool = True) -> np.ndarray:
        return ref.shade_debug_frame(debug, camera.position, scene.lights, scene.ambient,
                                     scene.background, surface, mip_lod=mip,
                                     lod_bias=bias)[..., :3][mask]

    candidates = np.stack([shade(b) for b in np.linspace(-1.0, 1.0, 9)])
    low, high = candidates.min(axis=0), candidates.max(axis=0)
    gpu = debug["linear"][..., :3][mask].astype(np.float64)
    allowance = LINEAR_TOL + TEXTURE_TOL[False] * 1.1  # colour = T * (0.2 + 0.9 n.l) <= 1.1 T
    outside = ((gpu < low - allowance) | (gpu > high + allowance)).any(axis=-1)
    assert outside.mean() < 0.01, f"{outside.mean():.2%} of pixels outside the LOD envelope"
    # and the LOD model matters: where the texture is minified, level-0 sampling is clearly
    # further off
    lod = ref.texture_lod(debug["uv"], np.where(mask, 0, -1), 128, 128)[mask]
    far = lod > 1.0
    assert far.sum() > 200
    modelled = np.abs(gpu - shade(0.0))[far].mean()
    assert np.abs(gpu - shade(0.0, mip=False))[far].mean() > 1.5 * modelled
