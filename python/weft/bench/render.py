"""Renderer benchmark: frame time (CPU, GPU per pass) vs resolution and shadow-map size, with
the shading-oracle error of the very frames that were timed.

For every resolution x shadow-map size the default scene is rendered once to warm up, then
``--frames`` times with ``Renderer.render_debug``; each of those frames is checked against the
NumPy oracle of :mod:`weft.reference.shading` (SPEC §1.3 eq. 2.5, 2.8–2.10, §1.5) and its
statistics are recorded. The oracle shades each point locally, so these frames are rendered
without the global terms (bounce light, ambient occlusion; their accuracy is measured against
the path tracer by ``weft.bench picture``). Times are medians over the frames; errors are the
worst frame's (max) or the average (mean). ``render()`` (colour only, no debug read-back) is
timed as well, both that way and at the renderer's defaults (global terms on).

The Filament peer (:mod:`weft.bench.render_peer`, issue 19) renders the matched default scene
at 1280x720 beside weft in the same run, with both renderers' defaults and with
post-processing off on both, and reports weft / Filament; it runs when open3d imports
(``--peer`` / ``--no-peer``; ``--quick`` skips it unless ``--peer``), and is reported as
skipped, with the reason, otherwise.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from weft.bench import Progress, machine_info, markdown_table, write_report
from weft.bench.render_peer import measure_peer
from weft.bench.render_peer import to_markdown as peer_markdown
from weft.reporting import add_progress_arguments

DESCRIPTION = ("frame time (CPU, GPU per pass) vs resolution and shadow-map size, with the "
               "shading-oracle error on the same frames")

RESOLUTIONS: Tuple[Tuple[int, int], ...] = ((640, 480), (1280, 720), (1920, 1080))
SHADOW_SIZES: Tuple[int, ...] = (1024, 2048, 4096)
QUICK_RESOLUTIONS: Tuple[Tuple[int, int], ...] = ((160, 120),)
QUICK_SHADOW_SIZES: Tuple[int, ...] = (512,)
PASS_GROUPS: Tuple[str, ...] = ("shadow", "forward", "output")
#: The Filament peer's resolution (issue 19), and with --quick.
PEER_RESOLUTION: Tuple[int, int] = (1280, 720)
PEER_QUICK_RESOLUTION: Tuple[int, int] = (160, 120)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--quick", action="store_true",
                        help="one tiny setting (160x120, shadow map 512, 1 frame) for CI")
    parser.add_argument("--out", default="out/bench/render",
                        help="output folder for bench.json and bench.md (out/bench/render)")
    parser.add_argument("--frames", type=int, default=None,
                        help="timed frames per setting after one warm-up frame "
                             "(default 5, 1 with --quick)")
    parser.add_argument("--peer", action=argparse.BooleanOptionalAction, default=None,
                        help="the Filament peer (Open3D's OffscreenRenderer, extra "
                             "weft[filament]) on the matched default scene at 1280x720, "
                             "160x120 with --quick; default: run it when open3d imports, "
                             "except with --quick")
    parser.add_argument("--peer-only", action="store_true",
                        help="run the Filament peer alone, without the resolution x shadow-map "
                             "settings")
    add_progress_arguments(parser)


# --------------------------------------------------------------------------------------------
# The oracle's view of a scene
# --------------------------------------------------------------------------------------------

class OracleUnavailable(RuntimeError):
    """The scene does not expose what the oracle needs (materials, texture images, labels)."""


def _instance_material(scene: Any, index: int) -> Any:
    if hasattr(scene, "material"):
        return scene.material(index)
    instances = getattr(scene, "instances", None)
    if instances is not None:
        inst = instances[index]
        return inst["material"] if isinstance(inst, dict) else inst.material
    raise OracleUnavailable("weft.Scene exposes no materials (needs Scene.material(id) or "
                            "Scene.instances)")


def scene_materials(scene: Any) -> List[Any]:
    """The oracle materials of every instance of a ``weft.Scene``, in id order."""
    from weft.reference import SurfaceMaterial

    out = []
    for index in range(int(scene.instance_count)):
        material = _instance_material(scene, index)
        texture = getattr(material, "texture", None)
        image = None
        srgb = True
        if texture is not None:
            image = getattr(texture, "image", None)
            if image is None:
                raise OracleUnavailable("weft.Texture exposes no image (needs Texture.image)")
            srgb = bool(getattr(texture, "srgb", True))
        out.append(SurfaceMaterial.from_weft(material, texture_image=np.asarray(image)
                                             if image is not None else None, texture_srgb=srgb))
    return out


def frame_oracle(renderer: Any, scene: Any, camera: Any, debug: Dict[str, np.ndarray],
                 materials: Sequence[Any]) -> Dict[str, Any]:
    """Oracle errors of one ``render_debug`` frame: the whole pipeline (texture sampled in
    NumPy) and the shading equation alone (T from the frame's albedo output), linear and 8-bit
    over all covered pixels; background; PCF visibility."""
    from weft import reference as ref

    lights = list(scene.lights)
    mask = np.asarray(debug["mask"], dtype=bool)
    if len(materials) == 1:
        labels = np.where(mask, 0, -1)
    elif "instance" in debug:
        labels = np.where(mask, np.asarray(debug["instance"]), -1)
    else:
        raise OracleUnavailable("render_debug() has no 'instance' output to tell the "
                                "scene's materials apart")
    camera_position = np.asarray(camera.position, dtype=np.float64)
    oracle = ref.shade_debug_frame(debug, camera_position, lights, scene.ambient,
                                   scene.background, list(materials), labels=labels)
    result: Dict[str, Any] = ref.compare_frame(debug, oracle).as_dict()
    shading = ref.shade_debug_frame(debug, camera_position, lights, scene.ambient,
                                    scene.background, list(materials), labels=labels,
                                    frame_albedo=True)
    result["shading"] = ref.compare_frame(debug, shading).as_dict()

    background = np.asarray(scene.background, dtype=np.float64)
    bg = ~mask
    result["background_max_abs"] = (float(ref.storage_excess(debug["linear"][..., :3][bg],
                                                             background).max())
                                    if bg.any() else 0.0)

    shadow_light = ref.first_shadow_light(lights)
    mismatch = 0.0
    if shadow_light is not None and mask.any():
        info = renderer.shadow_info(shadow_light)
        if info["active"]:
            direction = ref.as_light(lights[shadow_light]).direction
            vis = ref.pcf_visibility(debug["position"][mask], debug["normal"][mask], direction,
                                     renderer.shadow_map(shadow_light), info)
            taps = (2 * int(info["pcf_radius"]) + 1) ** 2
            diff = np.abs(vis - np.asarray(debug["shadow"], dtype=np.float64)[mask])
            mismatch = float(np.mean(diff > 0.5 / taps))
    result["shadow_mismatch"] = mismatch
    return result


# --------------------------------------------------------------------------------------------
# Measuring
# --------------------------------------------------------------------------------------------

def _pass_group(name: str) -> str:
    return "shadow" if name.startswith("shadow") else name


def _gpu(value: Optional[float]) -> Optional[float]:
    return None if value is None or value < 0 or not math.isfinite(value) else float(value)


def _median(values: Sequence[Optional[float]]) -> Optional[float]:
    vals = [v for v in values if v is not None]
    return float(statistics.median(vals)) if vals and len(vals) == len(values) else None


def _frame_times(stats: Dict[str, Any]) -> Dict[str, Any]:
    groups_cpu: Dict[str, float] = {}
    groups_gpu: Dict[str, Optional[float]] = {}
    for p in stats.get("passes", []):
        group = _pass_group(p["name"])
        groups_cpu[group] = groups_cpu.get(group, 0.0) + float(p.get("cpu_ms") or 0.0)
        gpu = _gpu(p.get("gpu_ms"))
        if group in groups_gpu and groups_gpu[group] is None:
            continue
        groups_gpu[group] = None if gpu is None else (groups_gpu.get(group) or 0.0) + gpu
    return {"cpu_ms": float(stats.get("cpu_ms", 0.0)), "gpu_ms": _gpu(stats.get("gpu_ms")),
            "pass_cpu_ms": groups_cpu, "pass_gpu_ms": groups_gpu,
            "passes": [p["name"] for p in stats.get("passes", [])]}


def measure_setting(width: int, height: int, shadow_size: int, frames: int,
                    progress: Optional[Progress] = None) -> Dict[str, Any]:
    """Benchmarks one resolution x shadow-map size on the default scene."""
    import weft

    label = f"{width}x{height} shadow {shadow_size}"
    scene, camera = weft.default_scene()
    # Shadow maps are re-rendered every frame so that their cost is measured (a static scene
    # would otherwise reuse them after the first frame).
    renderer = weft.Renderer(width, height, shadow_map_size=shadow_size, reuse_shadow_maps=False,
                             bounce=False, ambient_occlusion=0)
    defaults = weft.Renderer(width, height, shadow_map_size=shadow_size, reuse_shadow_maps=False)
    materials: Optional[List[Any]] = None
    oracle_error: Optional[str] = None
    try:
        materials = scene_materials(scene)
    except OracleUnavailable as exc:
        oracle_error = str(exc)

    if progress:
        progress.update(f"{label}: warm-up")
    renderer.render(scene, camera)

    debug_frames: List[Dict[str, Any]] = []
    oracle_frames: List[Dict[str, Any]] = []
    for i in range(frames):
        if progress:
            progress.update(f"{label}: frame {i + 1}/{frames}")
        debug = renderer.render_debug(scene, camera)
        debug_frames.append(_frame_times(renderer.stats))
        if materials is not None:
            try:
                oracle_frames.append(frame_oracle(renderer, scene, camera, debug, materials))
            except OracleUnavailable as exc:
                oracle_error, materials = str(exc), None

    color_cpu: List[float] = []
    color_wall: List[float] = []
    default_wall: List[float] = []
    defaults.render(scene, camera)  # warm-up
    for i in range(frames):  # alternating, so both see the same machine load
        if progress:
            progress.update(f"{label}: render() {i + 1}/{frames}")
        start = time.perf_counter()
        renderer.render(scene, camera)
        color_wall.append((time.perf_counter() - start) * 1e3)
        color_cpu.append(float(renderer.stats["cpu_ms"]))
        start = time.perf_counter()
        defaults.render(scene, camera)
        default_wall.append((time.perf_counter() - start) * 1e3)

    groups = sorted({g for f in debug_frames for g in f["pass_gpu_ms"]},
                    key=lambda g: (PASS_GROUPS.index(g) if g in PASS_GROUPS else 99, g))
    result: Dict[str, Any] = {
        "width": width,
        "height": height,
        "shadow_map_size": shadow_size,
        "frames": frames,
        "passes": debug_frames[-1]["passes"] if debug_frames else [],
        "frame_cpu_ms": _median([f["cpu_ms"] for f in debug_frames]),
        "frame_gpu_ms": _median([f["gpu_ms"] for f in debug_frames]),
        "pass_cpu_ms": {g: _median([f["pass_cpu_ms"].get(g) for f in debug_frames])
                        for g in groups},
        "pass_gpu_ms": {g: _median([f["pass_gpu_ms"].get(g) for f in debug_frames])
                        for g in groups},
        "render_cpu_ms": _median(color_cpu),
        "render_wall_ms": _median(color_wall),
        "render_defaults_wall_ms": _median(default_wall),
        "device": renderer.device_name,
    }
    if oracle_frames:
        worst = lambda key, frames=oracle_frames: max(o[key] for o in frames)  # noqa: E731
        mean = lambda key, frames=oracle_frames: float(np.mean([o[key] for o in frames]))  # noqa
        shading = [o["shading"] for o in oracle_frames]
        result["oracle"] = {
            "frames": len(oracle_frames),
            "max_abs": worst("max_abs"),
            "mean_abs": mean("mean_abs"),
            "p99_abs": worst("p99_abs"),
            "max_u8": worst("max_u8"),
            "u8_over_1": worst("u8_over_1"),
            "shading_max_abs": worst("max_abs", shading),
            "shading_max_u8": worst("max_u8", shading),
            "background_max_abs": worst("background_max_abs"),
            "shadow_mismatch": worst("shadow_mismatch"),
            "covered_pixels": oracle_frames[-1]["covered"],
        }
    else:
        result["oracle"] = None
        result["oracle_error"] = oracle_error or "no frames"
    return result


# --------------------------------------------------------------------------------------------
# Reporting
# --------------------------------------------------------------------------------------------

def _fmt_ms(value: Optional[float]) -> str:
    return "n/a" if value is None else f"{value:.2f}"


def _fmt_err(value: Optional[float], digits: int = 2) -> str:
    return "n/a" if value is None else f"{value:.{digits}e}"


def to_markdown(report: Dict[str, Any]) -> str:
    """The report as Markdown: a header naming the device and machine, then the table."""
    m = report["machine"]
    device = m.get("device") or {}
    lines = [
        "# weft render benchmark",
        "",
        f"- device: {device.get('name', report.get('device', '?'))} "
        f"({device.get('type', '?')}, Vulkan {device.get('api_version', '?')}, "
        f"driver {device.get('driver', '?')})",
        f"- machine: {m.get('platform')}, {m.get('cpu_count')} CPUs"
        + (f" ({m['processor']})" if m.get("processor") else ""),
        f"- weft {m.get('weft', '?')}, Python {m.get('python')}, NumPy {m.get('numpy')}, "
        f"validation layers {'on' if m.get('validation') else 'off'}",
        f"- command: `{report['command']}`",
        f"- {report['frames']} timed frame(s) per setting after 1 warm-up; times are medians in "
        "ms over the `render_debug` frames the oracle checked (all debug outputs read back); "
        "`render()` is the colour-only frame; these frames have no bounce light or ambient "
        "occlusion (the oracle shades locally), 'render() defaults ms' (wall) has them. GPU "
        "times from timestamp queries, n/a where the device cannot measure them.",
        "- oracle: NumPy Blinn-Phong + PCF from the same frame's debug outputs "
        "(weft.reference.shading), worst frame. Linear errors are |GPU - oracle| over all "
        "covered pixels (max, mean, 99th percentile) with the texture sampled in NumPy, which "
        "adds the sampler's own precision (sRGB decode, filtering, and a mip LOD the oracle "
        "estimates from the UV image, approximate along silhouettes); 'shading err' takes T "
        "from the frame's albedo output and so checks eq. 2.10 + PCF alone. 8-bit: max "
        "level difference and fraction of pixels more than 1 level off. Shadow mismatch: "
        "fraction of covered pixels whose PCF visibility differs from the NumPy PCF.",
        "",
    ]
    header = ["resolution", "shadow map", "frame CPU ms", "render() CPU ms",
              "render() defaults ms", "GPU shadow ms",
              "GPU forward ms", "GPU output ms", "GPU total ms", "max err", "mean err",
              "p99 err", "max shading err", "max 8-bit", "> 1 level", "shadow mismatch"]
    rows = []
    for r in report["results"]:
        gpu = r.get("pass_gpu_ms", {})
        o = r.get("oracle")
        rows.append([
            f"{r['width']}x{r['height']}", r["shadow_map_size"], _fmt_ms(r["frame_cpu_ms"]),
            _fmt_ms(r["render_cpu_ms"]), _fmt_ms(r.get("render_defaults_wall_ms")),
            _fmt_ms(gpu.get("shadow")), _fmt_ms(gpu.get("forward")),
            _fmt_ms(gpu.get("output")), _fmt_ms(r["frame_gpu_ms"]),
            _fmt_err(o["max_abs"]) if o else "n/a", _fmt_err(o["mean_abs"]) if o else "n/a",
            _fmt_err(o["p99_abs"]) if o else "n/a",
            _fmt_err(o["shading_max_abs"]) if o else "n/a",
            o["max_u8"] if o else "n/a",
            f"{100.0 * o['u8_over_1']:.3f}%" if o else "n/a",
            f"{100.0 * o['shadow_mismatch']:.3f}%" if o else "n/a",
        ])
    if rows:
        lines.append(markdown_table(header, rows))
    errors = sorted({r["oracle_error"] for r in report["results"] if r.get("oracle_error")})
    for e in errors:
        lines += ["", f"Oracle not evaluated: {e}"]
    if report.get("peer") is not None:
        lines += ["", peer_markdown(report["peer"]).rstrip("\n")]
    return "\n".join(lines) + "\n"


def _device_name() -> Optional[str]:
    import weft

    selected = [d for d in weft.devices() if d.get("selected")]
    return selected[0]["name"] if selected else None


def run(args: argparse.Namespace) -> int:
    if args.quick:
        resolutions, shadow_sizes = QUICK_RESOLUTIONS, QUICK_SHADOW_SIZES
        frames = 1 if args.frames is None else args.frames
    else:
        resolutions, shadow_sizes = RESOLUTIONS, SHADOW_SIZES
        frames = 5 if args.frames is None else args.frames
    if frames < 1:
        print("python -m weft.bench render: error: --frames must be >= 1", file=sys.stderr)
        return 2

    run_peer = args.peer if args.peer is not None else not args.quick
    if args.peer_only and args.peer is False:
        print("python -m weft.bench render: error: --peer-only with --no-peer",
              file=sys.stderr)
        return 2
    run_peer = run_peer or args.peer_only
    settings = [] if args.peer_only else \
        [(w, h, s) for (w, h) in resolutions for s in shadow_sizes]
    progress = Progress(len(settings) + int(run_peer), enabled=args.progress)
    results = []
    for w, h, s in settings:
        results.append(measure_setting(w, h, s, frames, progress))
        progress.step(f"{w}x{h} shadow {s} done")
    if run_peer:
        pw, ph = PEER_QUICK_RESOLUTION if args.quick else PEER_RESOLUTION
        peer = measure_peer(pw, ph, frames, progress,
                            picture_path=os.path.join(args.out, "peer.png"))
        progress.step("Filament peer done")
    else:
        peer = {"skipped": True,
                "note": "not asked for (--quick runs the Filament peer only with --peer)"
                if args.quick else "switched off with --no-peer"}
    progress.close()

    machine = machine_info()
    report = {
        "benchmark": "render",
        "command": "python -m weft.bench render" + (" --quick" if args.quick else "")
                   + (f" --frames {args.frames}" if args.frames is not None else "")
                   + ({True: " --peer", False: " --no-peer", None: ""}[args.peer])
                   + (" --peer-only" if args.peer_only else ""),
        "scene": "default_scene()",
        "frames": frames,
        "device": results[0]["device"] if results else _device_name(),
        "machine": machine,
        "results": results,
        "peer": peer,
    }
    markdown = to_markdown(report)
    paths = write_report(args.out, report, markdown)
    print(markdown)
    print("wrote " + " and ".join(paths))
    return 0
