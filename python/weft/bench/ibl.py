"""IBL benchmark: time against error for the offline IBL tools (SPEC §4, issue 6).

Environments are analytic (a sky gradient with a 2 degree sun of 5000 times the sky's radiance),
so every error has an independent reference:

- conversion: equirectangular and mirror-ball sphere map -> cube map (time; mean relative error
  against the analytic environment at the texel centres), push-pull fill;
- irradiance: exact cosine convolution (CPU, and as a Vulkan compute shader on the selected
  device), SH9 (alone, and of the sky with the extracted sun added back as a directional light)
  and the seed's blurs at several input cube sizes, on the sky alone and with the sun (per-texel
  relative errors are large on the sun's dark side), error against the exact convolution of the
  64^2 source at 32^2 output (the reference); the reference itself timed on the CPU and as the
  compute shader with their difference; and the SH9 projection alone (target <= 5 ms for
  6 x 256^2 on 2 CPU cores);
- glossy: Phong lobe by filtered importance sampling (samples x output size) against the exact
  Phong convolution, and the 5-level GGX chain: time at 256^2 on the CPU and as a Vulkan compute
  shader on the selected device (target 0.5 s for the compute version on lavapipe; the dispatch
  time excludes the upload and pipeline creation, the call time includes them) and per-level
  error at 32^2 against the exact GGX lobe (weft.reference.ibl);
- light extraction: threshold + components and median cut: time, sun direction error (degrees)
  and power error against the planted sun;
- shadow-light dome: build time and visibility-weighted irradiance error at ground points under a
  sphere occluder against the ray-cast reference, for 16 / 64 / 256 lights.

- frames: the demo scene lit by the sky (SH9 diffuse, GGX reflections) with 0 / 16 / 64 dome
  shadow lights (256^2 maps), at 640x480 and 1280x1024: frame time with the dome maps reused
  (nothing moves) and with every map re-rendered each frame (the sphere moves), as the seed's
  table 4.1 (41 / 28 / 14 fps at 640x480, GeForce of 2006) measured.
- seed options: the blur of the dome's shadows (radius 0 / 2 / 4 / 8 pixels) on a sphere above a
  ground plane with 16 dome lights: frame time and the ground's error against the ray-cast
  visibility-weighted irradiance; the eye-space sphere-map path against the cube path (frame
  time, bake time, difference on the sphere where R is within 120 degrees of the eye); a phantom
  ground over a background image against the same ground drawn normally (frame time).
"""

from __future__ import annotations

import argparse
import statistics
import time
from typing import Any, Callable, Dict, List, Sequence, Tuple

import numpy as np

from weft.bench import Progress, machine_info, markdown_table, write_report
from weft.reporting import add_progress_arguments

DESCRIPTION = ("IBL: conversion, irradiance (exact / SH9 / seed blurs), glossy prefilter, light "
               "extraction and shadow dome: time against error")

LUMA = np.array([0.2126, 0.7152, 0.0722])
SUN_DIR = np.array([0.35, 0.8, -0.45]) / np.linalg.norm([0.35, 0.8, -0.45])
SUN_RADIUS = np.radians(2.0)
SUN_RADIANCE = 5000.0
SH9_TARGET_MS = 5.0
GLOSSY_TARGET_S = 0.5


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--quick", action="store_true", help="tiny sizes for CI (a few seconds)")
    parser.add_argument("--out", default="out/bench/ibl",
                        help="output folder for bench.json and bench.md (out/bench/ibl)")
    add_progress_arguments(parser)


def sky(d: np.ndarray) -> np.ndarray:
    up = d[:, 1:2]
    zenith = np.array([0.35, 0.55, 1.0]) * (0.4 + 0.6 * np.maximum(up, 0.0))
    ground = np.array([0.2, 0.17, 0.12]) * (1.0 + 0.2 * d[:, 0:1])
    return np.where(up > 0, zenith, ground) + 0.05


def sun_sky(d: np.ndarray) -> np.ndarray:
    inside = (d @ SUN_DIR) >= np.cos(SUN_RADIUS)
    return sky(d) + inside[:, None] * SUN_RADIANCE * np.array([1.0, 0.95, 0.85])


def cube_faces(env: Callable[[np.ndarray], np.ndarray], size: int, ss: int = 2) -> np.ndarray:
    from weft.reference import ibl as ref

    d = ref.texel_directions(size * ss).reshape(-1, 3)
    return env(d).reshape(6, size, ss, size, ss, 3).mean(axis=(2, 4)).astype(np.float32)


def timed(fn: Callable[[], Any], min_repeats: int = 3, budget_s: float = 0.5) -> Tuple[float, Any]:
    """Median wall time (ms) over at least `min_repeats` runs (more while within budget)."""
    times, out = [], None
    start = time.perf_counter()
    while len(times) < min_repeats or (time.perf_counter() - start < budget_s and len(times) < 50):
        t0 = time.perf_counter()
        out = fn()
        times.append(1e3 * (time.perf_counter() - t0))
    return statistics.median(times), out


def rel_error(got: np.ndarray, want: np.ndarray) -> Tuple[float, float]:
    """Mean and max of the per-texel relative luminance error."""
    g = np.asarray(got, np.float64).reshape(-1, 3) @ LUMA
    w = np.asarray(want, np.float64).reshape(-1, 3) @ LUMA
    e = np.abs(g - w) / np.maximum(w, 1e-12)
    return float(e.mean()), float(e.max())


def norm_error(got: np.ndarray, want: np.ndarray) -> float:
    """Mean absolute luminance error over the mean luminance (how Ramamoorthi & Hanrahan quote
    SH9 errors; unlike the per-texel relative error it does not blow up on a sun's dark side)."""
    g = np.asarray(got, np.float64).reshape(-1, 3) @ LUMA
    w = np.asarray(want, np.float64).reshape(-1, 3) @ LUMA
    return float(np.abs(g - w).mean() / w.mean())


def angle_deg(a: Sequence[float], b: np.ndarray) -> float:
    a = np.asarray(a, np.float64)
    return float(np.degrees(np.arccos(np.clip(a @ b / np.linalg.norm(a), -1.0, 1.0))))


def bench_conversion(sizes: Sequence[int]) -> List[Dict[str, Any]]:
    import weft.ibl as ibl
    from weft.reference import ibl as ref

    rows = []
    for size in sizes:
        w = 8 * size
        h = w // 2
        theta = np.pi * (np.arange(h) + 0.5) / h
        phi = 2 * np.pi * ((np.arange(w) + 0.5) / w - 0.5)
        t, p = np.meshgrid(theta, phi, indexing="ij")
        d = np.stack([np.sin(t) * np.sin(p), np.cos(t), -np.sin(t) * np.cos(p)], -1)
        eq = sky(d.reshape(-1, 3)).reshape(h, w, 3).astype(np.float32)
        truth = sky(ref.texel_directions(size).reshape(-1, 3))
        ms, cube = timed(lambda: ibl.equirect_to_cube(eq, size))
        rows.append(dict(step="equirect -> cube", input=f"{w}x{h}", size=size, ms=ms,
                         mean_err=rel_error(cube.faces, truth)[0]))
        n = 4 * size
        c = 2.0 * (np.arange(n) + 0.5) / n - 1.0
        x, y = np.meshgrid(c, -c, indexing="xy")
        nrm = np.stack([x, y, np.sqrt(np.maximum(0.0, 1 - x * x - y * y))], -1).reshape(-1, 3)
        nrm /= np.linalg.norm(nrm, axis=1, keepdims=True)
        refl = 2.0 * nrm[:, 2:3] * nrm - np.array([0.0, 0.0, 1.0])
        sphere = sky(refl).reshape(n, n, 3).astype(np.float32)
        ms, (cube, valid) = timed(lambda: ibl.sphere_to_cube(sphere, size, wrap=0.9))
        seen = valid.reshape(-1)
        rows.append(dict(step="sphere map -> cube (wrap 0.9)", input=f"{n}x{n}", size=size, ms=ms,
                         mean_err=rel_error(np.asarray(cube.faces).reshape(-1, 3)[seen],
                                            truth[seen])[0]))
        ms, filled = timed(lambda: ibl.fill_unseen(cube, valid))
        rows.append(dict(step="fill unseen (push-pull)",
                         input=f"{100 * (1 - seen.mean()):.1f}% unseen", size=size, ms=ms,
                         mean_err=rel_error(np.asarray(filled.faces).reshape(-1, 3)[~seen],
                                            truth[~seen])[0] if (~seen).any() else 0.0))
    return rows


ENVIRONMENTS = {"sky": sky, "sun + sky": sun_sky}


def bench_irradiance(sizes: Sequence[int], out_size: int, ref_source: int) -> Dict[str, Any]:
    import weft.ibl as ibl

    ibl.irradiance_exact_gpu(np.ones((6, 4, 4, 3), np.float32), 4, 4)  # the driver compiles
    rows, compute = [], []
    for env_name, env in ENVIRONMENTS.items():
        env_rows, env_compute = _irradiance_rows(env_name, env, sizes, out_size, ref_source)
        rows += env_rows
        compute.append(env_compute)
    projection = []
    for size in sizes:
        cube = ibl_cube(cube_faces(sky, size, 1))
        projection.append(dict(cube=size, ms=timed(lambda: _project(cube), 10, 0.5)[0]))
    return dict(rows=rows, sh9_projection=projection, output_size=out_size,
                reference=f"exact cosine convolution of the {ref_source}^2 source at {out_size}^2",
                exact_compute=compute)


def ibl_cube(faces: np.ndarray):
    import weft.ibl as ibl

    return ibl.CubeMap(faces)


def _project(cube):
    import weft.ibl as ibl

    return ibl.project_sh9(cube)


def sh9_with_lights(cube, size: int):
    """Lights split off (weft.ibl.split_lights), SH9 of the residual sky, lights added back as
    directional lights: E(n) = E_sh(n) + sum colour max(0, n.l)."""
    import weft.ibl as ibl

    lights, residual = ibl.split_lights(cube)
    irr = np.asarray(ibl.irradiance_from_sh(ibl.project_sh9(residual), size).faces)
    if lights:
        n = ibl.cube_texel_directions(size)
        for l in lights:
            irr = irr + np.maximum(n @ np.asarray(l.direction, np.float32), 0.0)[..., None] * \
                np.asarray(l.colour, np.float32)
    return ibl.CubeMap(np.ascontiguousarray(irr, np.float32))


def _irradiance_rows(env_name: str, env: Callable[[np.ndarray], np.ndarray], sizes: Sequence[int],
                     out_size: int, ref_source: int) -> Tuple[List[Dict[str, Any]], Dict[str, Any]]:
    """The table's rows, and the reference itself timed on the CPU and as the compute shader
    (medians of the same run) with their difference."""
    import weft.ibl as ibl

    base = ibl.CubeMap(cube_faces(env, max(max(sizes), ref_source)))
    cpu_ms, ref_cube = timed(lambda: ibl.irradiance_exact(base, out_size, ref_source), 3, 0.0)
    gpu_ms, gpu_cube = timed(lambda: ibl.irradiance_exact_gpu(base, out_size, ref_source), 3, 0.0)
    reference = np.asarray(ref_cube.faces)
    mean_diff, max_diff = rel_error(gpu_cube.faces, reference)
    compute = dict(env=env_name, size=out_size, source=ref_source, cpu_ms=cpu_ms,
                   compute_ms=gpu_ms, mean_diff=mean_diff, max_diff=max_diff)
    rows = []
    for size in sizes:
        cube = ibl.CubeMap(cube_faces(env, size))
        methods = {
            "SH9 (project + evaluate)": lambda: ibl.irradiance_from_sh(ibl.project_sh9(cube),
                                                                       out_size),
            "SH9 of the sky + extracted lights": lambda: sh9_with_lights(cube, out_size),
            "exact (source 32^2)": lambda: ibl.irradiance_exact(cube, out_size, 32),
            "exact (compute, source 32^2)": lambda: ibl.irradiance_exact_gpu(cube, out_size, 32),
            "seed box blur (sphere map)": lambda: ibl.irradiance_box_blur(cube, out_size),
            "seed 3-axis rotational blur": lambda: ibl.irradiance_rotational_blur(cube, out_size),
        }
        for name, fn in methods.items():
            ms, out = timed(fn, 2, 0.3)
            mean, worst = rel_error(out.faces, reference)
            rows.append(dict(env=env_name, method=name, cube=size, ms=ms, mean_err=mean,
                             max_err=worst, norm_err=norm_error(out.faces, reference)))
    return rows, compute


def bench_glossy(samples: Sequence[int], sizes: Sequence[int], chain_size: int,
                 chain_samples: Sequence[int]) -> Dict[str, Any]:
    import weft.ibl as ibl
    from weft.reference import ibl as ref

    phong_rows, chain_rows = [], []
    for env_name, env in ENVIRONMENTS.items():
        cube = ibl.CubeMap(cube_faces(env, 64))
        for size in sizes:
            exact = np.asarray(ibl.phong_exact(cube, 32.0, size, 64).faces)
            for n in samples:
                ms, out = timed(lambda: ibl.phong_sampled(cube, 32.0, size, n), 2, 0.3)
                mean, worst = rel_error(out.faces, exact)
                phong_rows.append(dict(env=env_name, shininess=32, size=size, samples=n, ms=ms,
                                       mean_err=mean, max_err=worst))
        big = ibl.CubeMap(cube_faces(env, chain_size))
        small_src = cube_faces(env, 32)
        ibl.prefilter_ggx_gpu(small_src, 8, 2, 4)  # warm-up: the driver compiles the shader
        for n in chain_samples:
            ms, _ = timed(lambda: ibl.prefilter_ggx(big, chain_size, 5, n), 1, 0.0)
            gpu_total, (gpu_cube, gpu_ms) = timed(
                lambda: ibl.prefilter_ggx_gpu(big, chain_size, 5, n), 1, 0.0)
            chain = ibl.prefilter_ggx(small_src, 32, 5, n)
            gpu_chain, _ = ibl.prefilter_ggx_gpu(small_src, 32, 5, n)
            errs, gpu_errs = [], []
            for level in range(1, 5):
                got = np.asarray(chain.level(level))
                s = got.shape[1]
                want = ref.ggx_prefilter(small_src, level / 4,
                                         ref.texel_directions(s).reshape(-1, 3))
                errs.append(rel_error(got, want)[0])
                gpu_errs.append(rel_error(np.asarray(gpu_chain.level(level)), want)[0])
            chain_rows.append(dict(env=env_name, size=chain_size, levels=5, samples=n,
                                   cpu_s=ms / 1e3, gpu_dispatch_s=gpu_ms / 1e3,
                                   gpu_total_s=gpu_total / 1e3, level_mean_err_32=errs,
                                   gpu_level_mean_err_32=gpu_errs))
    return dict(phong=phong_rows, ggx_chain=chain_rows)


def bench_lights(sizes: Sequence[int]) -> List[Dict[str, Any]]:
    import weft.ibl as ibl

    power = SUN_RADIANCE * 2 * np.pi * (1 - np.cos(SUN_RADIUS)) * np.array([1.0, 0.95, 0.85]) @ LUMA
    rows = []
    for size in sizes:
        cube = ibl.CubeMap(cube_faces(sun_sky, size, 3))
        ms, lights = timed(lambda: ibl.extract_lights(cube))
        rows.append(dict(method="threshold + components", cube=size, ms=ms, lights=len(lights),
                         dir_err_deg=angle_deg(lights[0].direction, SUN_DIR),
                         power_err=abs(lights[0].power - power) / power))
        ms, lights = timed(lambda: ibl.median_cut(cube, 16), 1, 0.2)
        # the sun may be cut into several regions: their power-weighted direction and power
        near = [l for l in lights if angle_deg(l.direction, SUN_DIR) < 5.0]
        weighted = np.sum([l.power * np.asarray(l.direction) for l in near], axis=0)
        near_power = sum(l.power for l in near)
        rows.append(dict(method="median cut (16): lights within 5 deg", cube=size, ms=ms,
                         lights=len(lights),
                         dir_err_deg=angle_deg(weighted, SUN_DIR) if near else 180.0,
                         power_err=abs(near_power - power) / power))
    return rows


def bench_dome(counts: Sequence[int], size: int) -> List[Dict[str, Any]]:
    import weft.ibl as ibl
    from weft.reference import ibl as ref

    faces = cube_faces(sky, size, 1)
    cube = ibl.CubeMap(faces)
    centre, radius, up = np.array([0.0, 1.0, 0.0]), 0.6, np.array([0.0, 1.0, 0.0])
    points = [np.array([x, 0.0, z]) for x in (-1.2, -0.4, 0.0, 0.5, 1.5) for z in (-0.8, 0.0, 0.7)]
    exact = np.array([ref.visible_irradiance(faces, p, up, centre, radius, 2) for p in points])
    rows = []
    for n in counts:
        ms, dome = timed(lambda: ibl.ShadowDome(cube, n))
        est = [dome.diffuse_visible(up, ~ref.ray_hits_sphere(p, dome.directions.astype(float),
                                                             centre, radius)) for p in points]
        rows.append(dict(lights=n, build_ms=ms,
                         err=float(np.abs(np.array(est) - exact).mean() / exact.mean())))
    return rows


def bench_frames(resolutions: Sequence[Tuple[int, int]], counts: Sequence[int],
                 frames: int) -> List[Dict[str, Any]]:
    import weft
    import weft.ibl as ibl

    env = ibl.Environment(cube_faces(sky, 32, 1))
    rows = []
    for width, height in resolutions:
        renderer = weft.Renderer(width, height)
        for n in counts:
            scene, camera = weft.default_scene()
            for i in range(scene.instance_count):
                m = scene.material(i)
                m.environment_diffuse = 1.0
                m.reflectivity = (0.04, 0.04, 0.04)
                scene.set_material(i, m)
            scene.ambient = (0.0, 0.0, 0.0)
            scene.set_environment(env, dome_lights=n)
            renderer.render(scene, camera)  # bake, first maps
            row: Dict[str, Any] = dict(size=f"{width}x{height}", lights=n)
            for mode in ("reused", "rerendered"):
                times = []
                base = scene.transform(1)
                for k in range(frames):
                    if mode == "rerendered":  # the sphere moves: every dome map is stale
                        t = base.copy()
                        t[0, 3] += 0.01 * (k + 1)
                        scene.set_transform(1, t)
                    t0 = time.perf_counter()
                    renderer.render(scene, camera)
                    times.append(1000.0 * (time.perf_counter() - t0))
                ms = statistics.median(times)
                row[f"{mode}_ms"] = ms
                row[f"{mode}_fps"] = 1000.0 / ms
            rows.append(row)
    return rows


def _median_ms(fn: Callable[[], Any], frames: int) -> float:
    times = []
    for _ in range(frames):
        t0 = time.perf_counter()
        fn()
        times.append(1000.0 * (time.perf_counter() - t0))
    return statistics.median(times)


def bench_seed_options(size: Tuple[int, int], frames: int, samples: int) -> Dict[str, Any]:
    import weft
    import weft.ibl as ibl
    from weft.reference import ibl as ref

    width, height = size
    faces = cube_faces(sky, 32, 1)
    env = ibl.Environment(faces)
    renderer = weft.Renderer(width, height)
    centre, radius = np.array([0.0, 0.8, 0.0]), 0.5
    camera = weft.Camera(position=(0.0, 3.0, 3.0), target=(0.0, 0.0, 0.0), fov_y=0.9)

    def ground_scene(blur: float, phantom: bool = False):
        scene = weft.Scene()
        scene.ambient = (0.0, 0.0, 0.0)
        mat = weft.Material(kd=(1.0, 1.0, 1.0), environment_diffuse=1.0)
        ground = weft.Material(kd=(1.0, 1.0, 1.0), environment_diffuse=1.0, phantom=phantom)
        scene.add_mesh(weft.Mesh.plane(4.0, 4.0), ground)
        m = np.eye(4, dtype=np.float32)
        m[:3, :3] *= radius
        m[:3, 3] = centre
        scene.add_mesh(weft.Mesh.uv_sphere(1.0, 48, 24), mat, transform=m)
        scene.set_environment(env, dome_lights=16, dome_map_size=256, dome_blur=blur)
        return scene

    # the ground's reference: visibility-weighted irradiance / pi, ray-cast per pixel
    debug = renderer.render_debug(ground_scene(0.0), camera)
    ground = debug["mask"] & (debug["instance"] == 0)
    idx = np.flatnonzero(ground.reshape(-1))
    idx = idx[np.linspace(0, len(idx) - 1, min(samples, len(idx))).astype(int)]
    pos = debug["position"].reshape(-1, 3)[idx]
    nrm = debug["normal"].reshape(-1, 3)[idx]
    want = np.stack([ref.visible_irradiance(faces, p, n, centre, radius) for p, n in zip(pos, nrm)])
    want_l = want @ LUMA / np.pi
    blur_rows = []
    for blur in (0.0, 2.0, 4.0, 8.0):
        scene = ground_scene(blur)
        image = renderer.render_linear(scene, camera)  # maps rendered, then reused
        ms = _median_ms(lambda: renderer.render(scene, camera), frames)
        got_l = image[..., :3].reshape(-1, 3)[idx] @ LUMA
        blur_rows.append(dict(blur=blur, ms=ms,
                              mean_err=float(np.mean(np.abs(got_l - want_l)) / np.mean(want_l))))
    background = np.zeros((height, width, 4), np.uint8)
    background[..., :3] = 140
    background[..., 3] = 255
    phantom_scene = ground_scene(0.0, phantom=True)
    phantom_scene.background_image = weft.Texture(background)
    renderer.render(phantom_scene, camera)
    phantom_ms = _median_ms(lambda: renderer.render(phantom_scene, camera), frames)
    plain_ms = blur_rows[0]["ms"]

    # eye-space sphere maps vs world-space cube lookups of the same (eye = world) environment
    eye = (0.0, 0.0, 3.0)  # looks down -Z with Y up: eye space is world space
    cam = weft.Camera(position=eye, target=(0.0, 0.0, 0.0), fov_y=0.8)
    mat = weft.Material(kd=(0.8, 0.8, 0.8), shininess=32.0, reflectivity=(0.5, 0.5, 0.5),
                        environment_diffuse=1.0)
    lookup_rows, images = [], {}
    for lookup in ("cube", "sphere_map"):
        scene = weft.Scene()
        scene.ambient = (0.0, 0.0, 0.0)
        scene.add_mesh(weft.Mesh.uv_sphere(1.0, 64, 32), mat)
        scene.set_environment(ibl.Environment(faces), lookup=lookup, sphere_map_size=128)
        images[lookup] = renderer.render_debug(scene, cam)
        bake_ms = renderer.stats.get("environment_bake_ms", 0.0)
        ms = _median_ms(lambda: renderer.render(scene, cam), frames)
        lookup_rows.append(dict(lookup=lookup, ms=ms, bake_ms=bake_ms))
    c, s = images["cube"], images["sphere_map"]
    mask = c["mask"] & s["mask"]
    v = np.asarray(eye) - c["position"][mask]
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    front = np.einsum("nk,nk->n", c["normal"][mask], v) > 0.5
    a, b = s["linear"][mask][front, :3] @ LUMA, c["linear"][mask][front, :3] @ LUMA
    rel = np.abs(a - b) / np.maximum(b, 1e-12)
    lookup_rows[1].update(mean_diff=float(rel.mean()), max_diff=float(rel.max()))
    lookup_rows[0].update(mean_diff=0.0, max_diff=0.0)
    return dict(size=f"{width}x{height}", dome_blur=blur_rows, lookups=lookup_rows,
                phantom_ms=phantom_ms, plain_ms=plain_ms)


def to_markdown(r: Dict[str, Any]) -> str:
    f3 = lambda v: f"{v:.3f}"  # noqa: E731
    pct = lambda v: f"{100 * v:.2f}%"  # noqa: E731
    lines = ["# IBL benchmark", "", f"`{r['command']}` on {r['machine'].get('processor', '?')} "
             f"({r['machine'].get('cpu_count')} CPUs)", "", "## Conversion", ""]
    lines.append(markdown_table(["step", "input", "cube", "ms", "mean rel. error"],
                                [[x["step"], x["input"], x["size"], f3(x["ms"]), pct(x["mean_err"])]
                                 for x in r["conversion"]]))
    irr = r["irradiance"]
    lines += ["", f"## Irradiance (reference: {irr['reference']})", ""]
    lines.append(markdown_table(
        ["environment", "method", "input cube", "ms", "mean rel. error", "max rel. error",
         "mean abs. error / mean"],
        [[x["env"], x["method"], x["cube"], f3(x["ms"]), pct(x["mean_err"]), pct(x["max_err"]),
          pct(x["norm_err"])] for x in irr["rows"]]))
    lines += ["", f"SH9 projection alone (target <= {SH9_TARGET_MS} ms at 256^2): " + ", ".join(
        f"{x['cube']}^2: {x['ms']:.3f} ms" for x in irr["sh9_projection"])]
    device = r["machine"].get("device", {}).get("name", "?")
    lines += ["", f"The reference itself, CPU vs Vulkan compute on {device} (median ms; per-texel "
              "relative difference of the compute result to the CPU one):", ""]
    lines.append(markdown_table(
        ["environment", "output", "source", "CPU ms", "compute ms", "mean rel. difference",
         "max rel. difference"],
        [[x["env"], x["size"], x["source"], f3(x["cpu_ms"]), f3(x["compute_ms"]),
          f"{x['mean_diff']:.1e}", f"{x['max_diff']:.1e}"] for x in irr["exact_compute"]]))
    g = r["glossy"]
    lines += ["", "## Glossy: Phong lobe (s = 32) by filtered importance sampling vs exact", ""]
    lines.append(markdown_table(
        ["environment", "output", "samples", "ms", "mean rel. error", "max rel. error"],
        [[x["env"], x["size"], x["samples"], f3(x["ms"]), pct(x["mean_err"]), pct(x["max_err"])]
         for x in g["phong"]]))
    device = r["machine"].get("device", {}).get("name", "?")
    lines += ["", f"## Glossy: GGX chain, 5 levels (CPU, and Vulkan compute on {device}; "
              f"target {GLOSSY_TARGET_S} s for the compute version)", ""]
    lines.append(markdown_table(
        ["environment", "size", "samples", "CPU s", "compute s (dispatch)", "compute s (call)",
         "mean rel. error, levels 1-4 (32^2 chain): CPU", "compute"],
        [[x["env"], x["size"], x["samples"], f3(x["cpu_s"]), f3(x["gpu_dispatch_s"]),
          f3(x["gpu_total_s"]), ", ".join(pct(e) for e in x["level_mean_err_32"]),
          ", ".join(pct(e) for e in x["gpu_level_mean_err_32"])]
         for x in g["ggx_chain"]]))
    lines += ["", "## Light extraction (planted 2 degree sun)", ""]
    lines.append(markdown_table(["method", "cube", "ms", "lights", "direction error",
                                 "power error"],
                                [[x["method"], x["cube"], f3(x["ms"]), x["lights"],
                                  f"{x['dir_err_deg']:.2f} deg", pct(x["power_err"])]
                                 for x in r["lights"]]))
    lines += ["", "## Shadow-light dome (visibility-weighted irradiance vs ray-cast reference)", ""]
    lines.append(markdown_table(["lights", "build ms", "mean rel. error"],
                                [[x["lights"], f3(x["build_ms"]), pct(x["err"])]
                                 for x in r["dome"]]))
    lines += ["", "## Frames: demo scene under the sky with N dome shadow lights "
              f"({r['machine'].get('device', {}).get('name', '?')}; seed table 4.1: 41 / 28 / 14 "
              "fps at 640x480 for 0 / 16 / 64)", ""]
    lines.append(markdown_table(["size", "dome lights", "ms (maps reused)", "fps",
                                 "ms (all maps re-rendered)", "fps"],
                                [[x["size"], x["lights"], f"{x['reused_ms']:.1f}",
                                  f"{x['reused_fps']:.1f}", f"{x['rerendered_ms']:.1f}",
                                  f"{x['rerendered_fps']:.1f}"] for x in r["frames"]]))
    s = r["seed_options"]
    lines += ["", f"## Seed options at {s['size']}: blurred dome shadows (16 lights; ground error "
              "vs the ray-cast visibility-weighted irradiance)", ""]
    lines.append(markdown_table(["blur radius (px)", "ms per frame", "ground mean rel. error"],
                                [[f"{x['blur']:g}", f"{x['ms']:.1f}", pct(x["mean_err"])]
                                 for x in s["dome_blur"]]))
    lines += ["", "Eye-space sphere maps (the seed's path) vs world-space cube lookups, same "
              "environment (difference on the sphere where R is within 120 deg of the eye):", ""]
    lines.append(markdown_table(["lookup", "ms per frame", "bake ms", "mean rel. difference",
                                 "max rel. difference"],
                                [[x["lookup"], f"{x['ms']:.1f}", f"{x['bake_ms']:.1f}",
                                  pct(x["mean_diff"]), pct(x["max_diff"])] for x in s["lookups"]]))
    lines += ["", f"Phantom ground over a background image: {s['phantom_ms']:.1f} ms per frame "
              f"(the same ground drawn normally: {s['plain_ms']:.1f} ms)."]
    return "\n".join(lines) + "\n"


def run(args: argparse.Namespace) -> int:
    if args.quick:
        conv, irr, out_size, ref_source = (32,), (32,), 8, 32
        samples, gsizes, chain, chain_samples = (8, 32), (8,), 32, (16,)
        light_sizes, dome_counts, dome_size = (64,), (16, 64), 16
        resolutions, frame_counts, frames = ((64, 48),), (0, 16), 2
        seed_size, seed_samples = (64, 48), 40
    else:
        conv, irr, out_size, ref_source = (128, 256), (64, 128, 256), 32, 64
        samples, gsizes, chain, chain_samples = (8, 32, 128), (16, 32), 256, (16, 64)
        light_sizes, dome_counts, dome_size = (128, 256), (16, 64, 256), 32
        resolutions, frame_counts, frames = ((640, 480), (1280, 1024)), (0, 16, 64), 5
        seed_size, seed_samples = (640, 480), 400
    progress = Progress(8, enabled=args.progress)
    command = "python -m weft.bench ibl" + (" --quick" if args.quick else "")
    report: Dict[str, Any] = {"benchmark": "ibl", "command": command}
    progress.update("conversion")
    report["conversion"] = bench_conversion(conv)
    progress.step("irradiance")
    report["irradiance"] = bench_irradiance(irr, out_size, ref_source)
    progress.step("glossy")
    report["glossy"] = bench_glossy(samples, gsizes, chain, chain_samples)
    progress.step("lights")
    report["lights"] = bench_lights(light_sizes)
    progress.step("dome")
    report["dome"] = bench_dome(dome_counts, dome_size)
    progress.step("frames")
    report["frames"] = bench_frames(resolutions, frame_counts, frames)
    progress.step("seed options")
    report["seed_options"] = bench_seed_options(seed_size, frames, seed_samples)
    progress.step("report")
    progress.close()
    report["machine"] = machine_info()
    sh = [x for x in report["irradiance"]["sh9_projection"] if x["cube"] == 256]
    report["summary"] = {
        "sh9_projection_256_ms": sh[0]["ms"] if sh else None,
        "sh9_target_ms": SH9_TARGET_MS,
        "sh9_target_met": (sh[0]["ms"] <= SH9_TARGET_MS) if sh else None,
        "irradiance_exact_ms": {x["env"]: dict(cpu=x["cpu_ms"], compute=x["compute_ms"])
                                for x in report["irradiance"]["exact_compute"]},
        "ggx_chain_cpu_s": {f'{x["env"]}, {x["samples"]} samples': x["cpu_s"]
                            for x in report["glossy"]["ggx_chain"]},
        "ggx_chain_compute_dispatch_s": {f'{x["env"]}, {x["samples"]} samples': x["gpu_dispatch_s"]
                                         for x in report["glossy"]["ggx_chain"]},
        "ggx_chain_target_s": GLOSSY_TARGET_S,
        "shadow_light_frame_times": {f'{x["size"]}, {x["lights"]} lights':
                                     dict(reused_fps=x["reused_fps"],
                                          rerendered_fps=x["rerendered_fps"])
                                     for x in report["frames"]},
    }
    markdown = to_markdown(report)
    paths = write_report(args.out, report, markdown)
    print(markdown)
    print("wrote " + " and ".join(paths))
    return 0
