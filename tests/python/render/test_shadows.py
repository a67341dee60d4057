"""Shadow mapping with PCF (SPEC §1.5): occluded points get exactly the unlit term, the GPU's
PCF equals the NumPy PCF, edges are monotone, no acne at grazing light, no shadow pass without
a shadow-casting light, and frame statistics list the passes."""

from __future__ import annotations

import math
from typing import Dict, Tuple

import numpy as np
import pytest
import weft
from weft import reference as ref


def translation(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = (x, y, z)
    return m


def occluder_scene(texture: np.ndarray, light_direction=(-0.5, -1.0, -0.3),
                   extra_lights: Tuple[weft.DirectionalLight, ...] = ()) -> Tuple[
                       weft.Scene, weft.Camera, weft.Material]:
    """A textured ground plane with a floating box and sphere casting shadows on it."""
    scene = weft.Scene()
    ground = weft.Material(ka=(0.8, 0.9, 1.0), kd=(0.9, 0.9, 0.9), ks=(0.1, 0.1, 0.1),
                           shininess=20.0, base_color=(1.0, 0.9, 0.8),
                           texture=weft.Texture(texture, srgb=True, mipmaps=False))
    scene.add_mesh(weft.Mesh.plane(6.0, 6.0, 2, 2), ground)
    scene.add_mesh(weft.Mesh.box((0.8, 0.5, 0.8)), weft.Material(kd=(0.7, 0.3, 0.2)),
                   translation(0.3, 1.0, 0.2))
    scene.add_mesh(weft.Mesh.uv_sphere(0.4, 32, 16), weft.Material(kd=(0.2, 0.5, 0.7)),
                   translation(-1.0, 0.8, -0.4))
    for light in extra_lights:
        scene.add_light(light)
    scene.add_light(weft.DirectionalLight(direction=light_direction, color=(1.0, 1.0, 1.0),
                                          intensity=1.0, cast_shadows=True))
    scene.ambient = (0.2, 0.15, 0.1)
    scene.background = (0.05, 0.05, 0.05)
    camera = weft.Camera(position=(0.5, 4.0, 4.5), target=(0.0, 0.0, 0.0), fov_y=0.9)
    return scene, camera, ground


def plane_pixels(debug: Dict[str, np.ndarray]) -> np.ndarray:
    return debug["mask"] & (np.abs(debug["position"][..., 1]) < 1e-3)


def test_occluded_pixels_get_exactly_the_ambient_term(make_renderer, smooth_texture) -> None:
    texture = smooth_texture(64, 64, 3)
    scene, camera, ground = occluder_scene(texture)
    renderer = make_renderer(160, 120, shadow_map_size=1024, pcf_radius=1)
    debug = renderer.render_debug(scene, camera)
    occluded = plane_pixels(debug) & (debug["shadow"] == 0.0)
    assert occluded.sum() > 100, "the occluders cast too small a shadow"
    material = ref.SurfaceMaterial.from_weft(ground, texture)
    albedo = material.albedo(debug["uv"][occluded].astype(np.float64))
    expected = np.asarray(scene.ambient) * np.asarray(ground.ka) * albedo
    err = np.abs(debug["linear"][occluded][:, :3] - expected)
    assert err.max() <= 1e-3, f"max |linear - ambient term| = {err.max():.3g}"


def _kernel_pixels(debug: Dict[str, np.ndarray], info) -> np.ndarray:
    """The pixels whose shadow test is the PCF kernel the NumPy oracle models: where a pixel
    covers more of the map than the kernel, the forward pass samples the pixel's footprint
    instead (shading.glsl, from the position's screen derivatives, which the oracle does not
    have). The footprint here is the largest step to a covered neighbour, with a margin."""
    m = np.asarray(info["view_proj"], np.float64).reshape(4, 4)
    p = debug["position"][..., :3].astype(np.float64)
    uv = 0.5 * (p @ m[:2, :3].T + m[:2, 3]) * info["size"]  # orthographic: w = 1
    covered = debug["mask"]
    step = np.zeros(covered.shape)
    for axis in (0, 1):
        d = np.linalg.norm(np.diff(uv, axis=axis), axis=-1)
        both = covered & np.roll(covered, -1, axis=axis)
        d = np.where(np.take(both, range(d.shape[axis]), axis=axis), d, 0.0)
        pad = [(0, 0), (0, 0)]
        pad[axis] = (0, 1)
        step = np.maximum(step, np.pad(d, pad))
        pad[axis] = (1, 0)
        step = np.maximum(step, np.pad(d, pad))
    # one tap (r = 0) is the same test either way
    return step * 1.1 < 2 * info["pcf_radius"] + 1 if info["pcf_radius"] > 0 else covered


def _pcf_agreement(renderer: weft.Renderer, scene: weft.Scene, debug: Dict[str, np.ndarray],
                   light_index: int) -> Tuple[float, float]:
    """(fraction of covered pixels whose PCF visibility agrees, max light-depth error)."""
    info = renderer.shadow_info(light_index)
    assert info["active"]
    smap = renderer.shadow_map(light_index)
    assert smap.dtype == np.float32 and smap.shape == (info["size"], info["size"])
    assert np.all((smap >= 0.0) & (smap <= 1.0))
    mask = debug["mask"] & _kernel_pixels(debug, info)
    assert mask.sum() > 0.5 * debug["mask"].sum()  # most pixels keep the kernel
    light = scene.lights[light_index]
    look = ref.shadow_lookup(debug["position"][mask], debug["normal"][mask], light.direction,
                             smap, info)
    taps = (2 * info["pcf_radius"] + 1) ** 2
    agree = np.abs(look.visibility - debug["shadow"][mask]) < 0.5 / taps
    depth_err = float(np.abs(look.depth - debug["light_depth"][mask]).max())
    return float(agree.mean()), depth_err


@pytest.mark.parametrize("pcf_radius,normal_offset,shadow_size", [
    (0, 1.5, 1024), (1, 1.5, 1024), (2, 0.0, 512), (3, 3.0, 2048)])
def test_numpy_pcf_matches_gpu(make_renderer, smooth_texture, pcf_radius, normal_offset,
                               shadow_size) -> None:
    scene, camera, _ = occluder_scene(smooth_texture(32, 32, 3))
    # large enough that a pixel covers less of the map than the kernel (_kernel_pixels)
    renderer = make_renderer(640, 480, shadow_map_size=shadow_size, pcf_radius=pcf_radius,
                             normal_offset=normal_offset)
    debug = renderer.render_debug(scene, camera)
    info = renderer.shadow_info(0)
    assert info["size"] == shadow_size and info["pcf_radius"] == pcf_radius
    assert info["bias_constant"] == pytest.approx(renderer.bias_constant)
    agreement, depth_err = _pcf_agreement(renderer, scene, debug, 0)
    assert agreement >= 0.99, f"PCF agrees on only {agreement:.2%} of covered pixels"
    assert depth_err < 1e-4, f"light_depth differs from the NumPy d by {depth_err:.3g}"
    assert np.any(debug["shadow"][debug["mask"]] < 1.0)


def test_shadow_of_second_light(make_renderer, smooth_texture) -> None:
    """With a non-shadowing light first, the shadow output and pass belong to light 1."""
    first = weft.DirectionalLight(direction=(1.0, -0.2, 0.0), color=(0.2, 0.2, 0.2),
                                  cast_shadows=False)
    scene, camera, _ = occluder_scene(smooth_texture(32, 32, 3), extra_lights=(first,))
    renderer = make_renderer(640, 480, shadow_map_size=1024)  # the kernel's scale (above)
    debug = renderer.render_debug(scene, camera)
    names = [p["name"] for p in renderer.stats["passes"]]
    assert "shadow[1]" in names and "shadow[0]" not in names, names
    assert not renderer.shadow_info(0)["active"]
    agreement, _ = _pcf_agreement(renderer, scene, debug, 1)
    assert agreement >= 0.99


def test_two_shadow_casting_lights(make_renderer, smooth_texture) -> None:
    """Each shadow-casting light gets its own shadow pass and map; shading with both NumPy
    PCF visibilities reproduces the frame."""
    second = weft.DirectionalLight(direction=(0.8, -1.0, 0.5), color=(0.5, 0.4, 0.3),
                                   cast_shadows=True)
    texture = smooth_texture(32, 32, 3)
    scene, camera, ground = occluder_scene(texture, extra_lights=(second,))
    renderer = make_renderer(128, 96, shadow_map_size=1024)
    debug = renderer.render_debug(scene, camera)
    names = [p["name"] for p in renderer.stats["passes"]]
    assert "shadow[0]" in names and "shadow[1]" in names, names
    mask = debug["mask"]
    visibility = {}
    for index in (0, 1):
        info = renderer.shadow_info(index)
        assert info["active"]
        vis = np.ones(mask.shape)
        vis[mask] = ref.pcf_visibility(debug["position"][mask], debug["normal"][mask],
                                       scene.lights[index].direction,
                                       renderer.shadow_map(index), info)
        visibility[index] = vis
    # the debug output reports the first shadow-casting light
    agree = np.abs(visibility[0][mask] - debug["shadow"][mask]) < 1e-3
    assert agree.mean() >= 0.99
    materials = [ref.SurfaceMaterial.from_weft(ground, texture),
                 ref.SurfaceMaterial.from_weft(scene.material(1)),
                 ref.SurfaceMaterial.from_weft(scene.material(2))]
    oracle = ref.shade_debug_frame(debug, camera.position, scene.lights, scene.ambient,
                                   scene.background, materials, labels=debug["instance"],
                                   shadow=visibility)
    err = np.abs(debug["linear"][..., :3] - oracle[..., :3]).max(axis=-1)[mask]
    # textured ground: allow the sampler's precision (see test_shading_oracle)
    close = err <= 5e-3
    assert close.mean() >= 0.99, f"only {close.mean():.2%} of pixels match"
    assert np.any(visibility[1][mask] < 1.0), "the second light casts no visible shadow"


def test_pcf_edge_is_monotone(make_renderer) -> None:
    """A floating axis-aligned box lit along (1,-1,0) casts a shadow with a straight edge at
    z = +0.3. Along the image column x = const (the camera sits at that x), visibility must
    not increase while walking from the lit plane into the shadow."""
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(8.0, 8.0), weft.Material())
    box_bottom, box_top = 0.8, 1.4
    scene.add_mesh(weft.Mesh.box((0.6, box_top - box_bottom, 0.6)), weft.Material(),
                   translation(0.0, 0.5 * (box_bottom + box_top), 0.0))
    scene.add_light(weft.DirectionalLight(direction=(1.0, -1.0, 0.0), cast_shadows=True))
    shadow_x = 0.5 * (box_bottom + box_top)  # centre of the shadow on the ground
    camera = weft.Camera(position=(shadow_x, 3.0, 2.5), target=(shadow_x, 0.0, 0.3), fov_y=0.7)
    width, height = 161, 121  # odd width: the centre column is exactly the plane x = shadow_x
    renderer = make_renderer(width, height, shadow_map_size=256, pcf_radius=2)
    debug = renderer.render_debug(scene, camera)
    col = width // 2
    on_plane = plane_pixels(debug)[:, col]
    pos = debug["position"][:, col]
    vis = debug["shadow"][:, col]
    assert np.allclose(pos[on_plane, 0], shadow_x, atol=0.02)
    # walk from the bottom of the image (large z, lit) up to the middle of the shadow (z = 0)
    rows = [r for r in range(height - 1, -1, -1) if on_plane[r] and pos[r, 2] >= 0.0]
    z = pos[rows, 2]
    assert np.all(np.diff(z) < 0), "rows do not move monotonically towards the shadow"
    line = vis[rows]
    assert line[0] == 1.0 and line[-1] == 0.0, f"line does not cross the edge: {line}"
    penumbra = line[(line > 0.0) & (line < 1.0)]
    assert penumbra.size >= 2, "no soft PCF penumbra"
    increases = np.diff(line)
    assert np.all(increases <= 1e-6), f"visibility increases into the shadow: {line}"


@pytest.mark.parametrize("angle_deg", [0.0, 45.0, 70.0, 80.0])
def test_no_acne_on_lit_plane(make_renderer, angle_deg: float) -> None:
    """A plane with no occluder must be fully lit, even at grazing light (< 0.1% shadowed)."""
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(10.0, 10.0, 8, 8), weft.Material(kd=(0.8, 0.8, 0.8)))
    a = math.radians(angle_deg)
    scene.add_light(weft.DirectionalLight(direction=(-math.sin(a), -math.cos(a), 0.0),
                                          cast_shadows=True))
    camera = weft.Camera(position=(0.0, 3.0, 5.0), target=(0.0, 0.0, -1.0), fov_y=1.0)
    renderer = make_renderer(200, 150, shadow_map_size=1024)
    debug = renderer.render_debug(scene, camera)
    mask = debug["mask"]
    assert mask.mean() > 0.5
    assert renderer.shadow_info(0)["active"]
    shadowed = float(np.mean(debug["shadow"][mask] < 1.0))
    assert shadowed < 1e-3, f"{shadowed:.3%} of the lit plane is shadowed at {angle_deg} deg"


def test_no_acne_on_curved_receiver(make_renderer) -> None:
    """A lone sphere must not shadow its own lit side (n.l > 0.2) anywhere."""
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.uv_sphere(1.0, 64, 32), weft.Material())
    direction = np.array([-0.3, -1.0, -0.5])
    scene.add_light(weft.DirectionalLight(direction=tuple(direction), cast_shadows=True))
    camera = weft.Camera(position=(0.0, 2.0, 3.5), target=(0.0, 0.0, 0.0))
    renderer = make_renderer(128, 128, shadow_map_size=1024)
    debug = renderer.render_debug(scene, camera)
    l = -direction / np.linalg.norm(direction)
    lit_side = debug["mask"] & (debug["normal"] @ l > 0.2)
    assert lit_side.sum() > 500
    shadowed = float(np.mean(debug["shadow"][lit_side] < 1.0))
    assert shadowed < 1e-3, f"{shadowed:.3%} of the sphere's lit side is shadowed"


def test_no_shadow_pass_without_shadow_casting_light(make_renderer) -> None:
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(4.0, 4.0), weft.Material())
    scene.add_mesh(weft.Mesh.box((0.5, 0.5, 0.5)), weft.Material(), translation(0, 0.6, 0))
    scene.add_light(weft.DirectionalLight(direction=(-0.3, -1.0, -0.2), cast_shadows=False))
    camera = weft.Camera(position=(0.0, 3.0, 3.0))
    renderer = make_renderer(96, 72, shadow_map_size=512)
    debug = renderer.render_debug(scene, camera)
    names = [p["name"] for p in renderer.stats["passes"]]
    assert not any(n.startswith("shadow") for n in names), names
    assert "forward" in names
    assert np.all(debug["shadow"] == 1.0)
    assert not renderer.shadow_info(0)["active"]


def test_stats_list_passes(make_renderer) -> None:
    scene, camera = weft.default_scene()
    renderer = make_renderer(96, 72, shadow_map_size=512)
    renderer.render(scene, camera)
    first = renderer.stats
    renderer.render(scene, camera)
    stats = renderer.stats
    assert stats["frame_index"] > first["frame_index"]
    first_names = [p["name"] for p in first["passes"]]
    shadow_pos = min(i for i, n in enumerate(first_names) if n.startswith("shadow["))
    assert shadow_pos < first_names.index("forward")
    # nothing the light sees changed: the second frame reuses the shadow map
    names = [p["name"] for p in stats["passes"]]
    assert not any(n.startswith("shadow[") for n in names), names
    assert stats["reused"] == ["shadow[0]"]
    assert "forward" in names and "output" in names, names
    assert names.index("forward") < names.index("output")
    assert stats["cpu_ms"] >= 0.0
    for p in stats["passes"]:
        assert p["cpu_ms"] >= 0.0, p
        assert p["gpu_ms"] is None or p["gpu_ms"] >= 0.0, p
    if stats["gpu_ms"] is not None:
        assert stats["gpu_ms"] >= 0.0
    assert isinstance(stats["culled"], list)
