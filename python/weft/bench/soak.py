"""Soak: the demo scene (cloth, furry ball, sky, an environment with a shadow dome) rendered
headless for many frames at a tiny size, recording resident memory (RSS), the device memory
weft's allocator holds (weft.device_memory) and the frame time at intervals. After a warm-up,
memory must stay flat: the slope of RSS and of device memory over frames (the median of three
consecutive windows' Theil-Sen slopes, see _steady_slope), extrapolated over the measured frames,
must stay within noise (--rss-tolerance-mib, device
memory exactly flat). The cloth must stay finite and Vulkan validation silent (when enabled).

    python -m weft.bench soak --frames 10000 --hot-reload glsl   # the long run (BENCHMARKS.md)
    python -m weft.bench soak --quick                   # 300 frames (the test suite)

``--hot-reload DIR`` soaks shader hot reload too: a copy of DIR (laid out like glsl/) is
watched (weft.set_shader_directory), and every ``--reload-every`` frames the forward shader in
it is edited (a comment line added), so the renderer recompiles it and swaps its pipelines.
"""

from __future__ import annotations

import argparse
import os
import shutil
import tempfile
import time
from typing import Any, Dict, List, Optional

import numpy as np

from weft.reporting import Progress, add_progress_arguments

DESCRIPTION = "memory and frame time stay flat over thousands of demo frames"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--frames", type=int, default=10000, help="frames to render (10000)")
    parser.add_argument("--quick", action="store_true", help="300 frames (CI)")
    parser.add_argument("--size", type=int, nargs=2, default=(64, 48), metavar=("W", "H"))
    parser.add_argument("--samples", type=int, default=50, help="measurements over the run")
    parser.add_argument("--warmup", type=float, default=0.2,
                        help="fraction of the run before the slope is measured (0.2)")
    parser.add_argument("--rss-tolerance-mib", type=float, default=8.0,
                        help="largest RSS growth extrapolated over the measured frames (8 MiB)")
    parser.add_argument("--scene", choices=("demo", "default"), default="demo",
                        help="demo (cloth, fur, sky, environment + dome) or default (the "
                             "seed's static scene: a control for the measurement)")
    parser.add_argument("--no-hair-transparency", action="store_true",
                        help="render the fur opaque (Renderer.hair_transparency = False)")
    parser.add_argument("--hot-reload", metavar="DIR", default=None,
                        help="watch a copy of this shader folder (glsl/) and edit its forward "
                             "shader every --reload-every frames")
    parser.add_argument("--reload-every", type=int, default=500,
                        help="frames between shader edits with --hot-reload (500)")
    parser.add_argument("--out", default="out/bench/soak")
    add_progress_arguments(parser)


def _rss_bytes() -> int:
    with open("/proc/self/status", encoding="utf-8") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    return 0


def _environment():
    from weft.ibl import CubeMap

    faces = np.full((6, 16, 16, 3), 0.3, np.float32)
    faces[2, 6:10, 6:10] = 20.0  # a bright patch overhead: the dome has a light to shadow
    return CubeMap(faces)


def _slope(frames: List[int], values: List[float]) -> float:
    """Slope of values over frames (units per frame): the Theil-Sen estimator, the median of
    the slopes between every pair of samples, so that one transient peak of the allocator's
    resident set does not read as growth (a 9-sample least-squares fit of a flat demo soak
    once gave 9 MiB over 80 frames from one peak) while a steady leak keeps its own slope."""
    x, y = np.asarray(frames, float), np.asarray(values, float)
    i, j = np.triu_indices(len(x), 1)
    keep = x[j] != x[i]
    if not keep.any():
        return 0.0
    return float(np.median((y[j] - y[i])[keep] / (x[j] - x[i])[keep]))


def _steady_slope(frames: List[int], values: List[float], windows: int = 3) -> float:
    """Growth that persists: the median of the Theil-Sen slopes (_slope) of `windows`
    consecutive windows of the samples. A leak grows in every window and keeps its slope; a
    one-off step of the allocator's resident set falls into one window only and is ignored
    (lavapipe's RSS can step up by ~10 MiB once in a run: in the middle of 18 samples, a
    whole-run Theil-Sen fit read that as 8.7 MiB growth over 170 frames in a clean-clone CI
    run). Fewer than 3 samples a window: the whole-run Theil-Sen slope."""
    n = len(frames)
    if n < 3 * windows:
        return _slope(frames, values)
    cuts = np.linspace(0, n, windows + 1).round().astype(int)
    return float(np.median([_slope(frames[a:b], values[a:b])
                            for a, b in zip(cuts[:-1], cuts[1:])]))


#: The shader --hot-reload edits (relative to the watched folder): every mesh draws with it.
RELOADED_SHADER = os.path.join("render", "forward.frag")


def soak(frames: int, size=(64, 48), samples: int = 50, warmup: float = 0.2,
         scene_name: str = "demo", hair_transparency: bool = True,
         hot_reload: str = None, reload_every: int = 500,
         progress: Optional[bool] = False) -> Dict[str, Any]:
    """Renders ``frames`` frames and measures memory and frame time (the module's docstring);
    ``progress``: a bar on stderr (True, False, or None = only on a terminal)."""
    import weft

    if hot_reload is None:
        return _soak(frames, size, samples, warmup, scene_name, hair_transparency, None, 0,
                     progress)
    if not os.path.isfile(os.path.join(hot_reload, RELOADED_SHADER)):
        raise weft.InvalidArgument(f"--hot-reload needs a folder laid out like glsl/ (no "
                                   f"{RELOADED_SHADER} in {hot_reload!r})")
    if not weft.shader_hot_reload_available():
        raise weft.InvalidArgument("this build has no shader hot reload (libshaderc)")
    if reload_every < 1:
        raise weft.InvalidArgument(f"--reload-every must be >= 1, got {reload_every}")
    with tempfile.TemporaryDirectory(prefix="weft-soak-glsl-") as tmp:
        watched = os.path.join(tmp, "glsl")
        shutil.copytree(hot_reload, watched)
        weft.set_shader_directory(watched)
        try:
            return _soak(frames, size, samples, warmup, scene_name, hair_transparency,
                         os.path.join(watched, RELOADED_SHADER), reload_every, progress)
        finally:
            weft.set_shader_directory("")


def _soak(frames: int, size, samples: int, warmup: float, scene_name: str,
          hair_transparency: bool, edited: str, reload_every: int,
          progress: Optional[bool]) -> Dict[str, Any]:
    import weft

    if scene_name == "default":
        scene, camera = weft.default_scene()
        cloth = weft.Cloth(8, 8)
        scene.add_cloth(cloth)
    else:
        scene, camera, cloth = weft.demo_scene()
    scene.set_environment(_environment(), intensity=0.5, specular_size=16, specular_levels=4,
                          specular_samples=16, dome_lights=8, dome_map_size=64)
    renderer = weft.Renderer(int(size[0]), int(size[1]), shadow_map_size=256, msaa=1)
    renderer.hair_transparency = bool(hair_transparency)
    every = max(1, frames // max(1, samples))
    rows: List[Dict[str, Any]] = []
    last, last_frame = time.perf_counter(), 0
    finite = True
    edits = recompiled = 0
    bar = Progress(frames, enabled=progress)
    for f in range(1, frames + 1):
        if edited and f % reload_every == 0:
            # mtime has a coarse clock on some file systems: the size changes too
            with open(edited, "a", encoding="utf-8") as shader:
                shader.write(f"// soak edit {f}\n")
            edits += 1
            recompiled += int(weft.poll_shader_changes())  # the frame swaps the pipelines
        cloth.step(1.0 / 60.0)
        renderer.render(scene, camera)
        if f % every == 0 or f == frames:
            now = time.perf_counter()
            positions = np.asarray(cloth.positions)
            finite = finite and bool(np.all(np.isfinite(positions)))
            mem = weft.device_memory()
            rows.append({"frame": f, "rss_mib": _rss_bytes() / 2 ** 20,
                         "device_reserved_mib": mem["reserved_bytes"] / 2 ** 20,
                         "device_used_mib": mem["used_bytes"] / 2 ** 20,
                         "frame_ms": 1000.0 * (now - last) / (f - last_frame)})
            last, last_frame = now, f
            bar.update(f"soak: {rows[-1]['rss_mib']:.1f} MiB RSS, "
                       f"{rows[-1]['frame_ms']:.0f} ms/frame")
        bar.step()
    bar.close()
    start = int(len(rows) * warmup)
    measured = rows[start:]
    span = measured[-1]["frame"] - measured[0]["frame"] if measured else 0
    fx = [r["frame"] for r in measured]
    result = {
        "frames": frames, "scene": scene_name, "size": list(size),
        "hair_transparency": bool(hair_transparency), "sample_every": every, "rows": rows,
        "warmup_frames": measured[0]["frame"] if measured else 0,
        "rss_slope_kib_per_1000_frames":
            1000 * _steady_slope(fx, [r["rss_mib"] for r in measured]) * 1024,
        "device_slope_kib_per_1000_frames":
            1000 * _steady_slope(fx, [r["device_reserved_mib"] for r in measured]) * 1024,
        "device_used_slope_kib_per_1000_frames":
            1000 * _steady_slope(fx, [r["device_used_mib"] for r in measured]) * 1024,
        "frame_ms_first": measured[0]["frame_ms"] if measured else None,
        "frame_ms_last": measured[-1]["frame_ms"] if measured else None,
        "frame_ms_median":
            float(np.median([r["frame_ms"] for r in measured])) if measured else None,
        "measured_frames": span,
        "cloth_finite": finite,
        "shader_edits": edits,
        "shader_recompiles": recompiled,
        "shader_errors": len(weft.shader_errors()) if edited else None,
        "validation_messages":
            len(weft.validation_messages()) if weft.validation_enabled() else None,
    }
    result["rss_growth_mib"] = result["rss_slope_kib_per_1000_frames"] * span / 1000 / 1024
    result["device_growth_mib"] = result["device_slope_kib_per_1000_frames"] * span / 1000 / 1024
    return result


def verdict(result: Dict[str, Any], rss_tolerance_mib: float) -> List[str]:
    """What is wrong with a soak result (empty: flat)."""
    problems = []
    if result["rss_growth_mib"] > rss_tolerance_mib:
        problems.append(f"RSS grows {result['rss_growth_mib']:.1f} MiB over "
                        f"{result['measured_frames']} frames (> {rss_tolerance_mib} MiB)")
    if abs(result["device_growth_mib"]) > 1e-9:
        problems.append(f"device memory grows {result['device_growth_mib']:.1f} MiB")
    if not result["cloth_finite"]:
        problems.append("the cloth holds NaN/inf")
    if result["validation_messages"]:
        problems.append(f"{result['validation_messages']} validation messages")
    if result.get("shader_errors"):
        problems.append(f"{result['shader_errors']} shader reload errors")
    if result.get("shader_recompiles", 0) < result.get("shader_edits", 0):
        problems.append(f"{result['shader_edits']} shader edits but only "
                        f"{result['shader_recompiles']} recompiles")
    return problems


def to_markdown(result: Dict[str, Any], problems: List[str]) -> str:
    from weft.bench import markdown_table

    rows = [[r["frame"], f"{r['rss_mib']:.1f}", f"{r['device_reserved_mib']:.1f}",
             f"{r['device_used_mib']:.2f}", f"{r['frame_ms']:.2f}"]
            for r in result["rows"][:: max(1, len(result["rows"]) // 10)]]
    return "\n".join([
        f"# soak: {result['frames']} frames of the {result['scene']} scene at "
        f"{result['size'][0]}x{result['size'][1]}"
        + ("" if result["hair_transparency"] else ", fur opaque"), "",
        f"- RSS slope after {result['warmup_frames']} warm-up frames: "
        f"{result['rss_slope_kib_per_1000_frames']:.1f} KiB / 1000 frames "
        f"({result['rss_growth_mib']:.2f} MiB over {result['measured_frames']} frames)",
        f"- device memory slope: {result['device_slope_kib_per_1000_frames']:.1f} KiB / 1000 "
        f"frames (reserved), {result['device_used_slope_kib_per_1000_frames']:.1f} (used)",
        f"- frame time: {result['frame_ms_first']:.2f} ms first, {result['frame_ms_last']:.2f} ms "
        f"last, {result['frame_ms_median']:.2f} ms median",
        f"- cloth finite: {result['cloth_finite']}; validation messages: "
        f"{result['validation_messages']}",
        "- shader hot reload: " + (f"{result['shader_edits']} edits of the forward shader, "
                                   f"{result['shader_recompiles']} shaders recompiled, "
                                   f"{result['shader_errors']} errors"
                                    if result.get("shader_errors") is not None else "off"),
        f"- verdict: {'flat' if not problems else '; '.join(problems)}", "",
        markdown_table(["frame", "RSS MiB", "device reserved MiB", "device used MiB",
                        "ms / frame"], rows), ""])


def run(args: argparse.Namespace) -> int:
    from weft.bench import machine_info, write_report

    frames = 300 if args.quick else int(args.frames)
    result = soak(frames, tuple(args.size), args.samples, args.warmup, args.scene,
                  not args.no_hair_transparency, args.hot_reload, args.reload_every,
                  args.progress)
    problems = verdict(result, args.rss_tolerance_mib)
    result["machine"] = machine_info()
    result["problems"] = problems
    paths = write_report(args.out, result, to_markdown(result, problems))
    print(to_markdown(result, problems))
    print("wrote " + ", ".join(paths))
    return 1 if problems else 0
