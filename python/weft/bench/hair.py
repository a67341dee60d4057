"""Hair benchmark (SPEC §5): CPU and compute parts, and renderer frame times.

Every row is a time and an error against a stated reference, measured in the same run:

- ``.hair`` save/load throughput for the seed's hair sizes; error: max |point difference|
  after a round trip (must be 0).
- hair generator time for 160,000 / 687,532 / 1,031,268 points (10,000 / 10,000 / 15,000
  strands); error: |point count - target| (must be 0).
- fur generation (CPU) for 2,088,900 points (sphere 450 x 212, level 1) and 22,977,900 points
  (sphere 198 x 212, level 5): the seed's fur sizes exactly; error: max |first step - normal *
  segment length| over the strands, against listing 1.
- shading evaluation in a Vulkan compute shader (samples/s, upload and readback included) with
  its relative error against the NumPy float64 reference (max and 99.9th percentile).
- deep opacity maps: mean |transmittance error| of 3 layers (linear, log) against the 64-layer
  map, the exact fragment sum and the analytic exp(-k z) of a uniform slab.
- weighted blended OIT: mean and max |colour error| of each weight function against exact
  depth-sorted "over" on random 8-layer stacks.
- frame time at 800 x 800 (SPEC §5.5) for lighting only (B: one directional light, no shadows),
  + shadows (B+S: shadow map and deep opacity map) and + transparency (B+S+T: strands of
  transparency 0.6 through weighted blended OIT) for the three hair sizes and the 2.1 M fur
  (23 M with --frames-23m); error: max |radiance - NumPy hair model| over the hair pixels of a
  debug frame of the same configuration (drawn opaque for B+S+T; the composite's own error is
  the WBOIT rows'), with the frame's visibility for B+S.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from typing import Any, Callable, Dict, List, Tuple

import numpy as np

from weft.bench import Progress, machine_info, markdown_table, write_report

DESCRIPTION = ("hair and fur: .hair IO, generators, fur, compute shading throughput vs NumPy, "
               "deep-opacity-map and WBOIT error, renderer frame times B / B+S / B+S+T")

HAIR_SIZES: Tuple[Tuple[int, int], ...] = ((10_000, 160_000), (10_000, 687_532),
                                           (15_000, 1_031_268))
QUICK_HAIR_SIZES: Tuple[Tuple[int, int], ...] = ((500, 8_000), (500, 34_377))
#: (label, sphere segments, sphere rings, level): 2,088,900 and 22,977,900 points exactly.
FUR_SIZES = (("2.1M", 450, 212, 1), ("23M", 198, 212, 5))
QUICK_FUR_SIZES = (("quick", 32, 16, 2),)
SHADE_SAMPLES, QUICK_SHADE_SAMPLES = 262_144, 4_096
FRAME_SIZE, QUICK_FRAME_SIZE = 800, 96
FRAME_CONFIGS = ("B", "B+S", "B+S+T")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--quick", action="store_true",
                        help="small sizes: a few seconds, for CI")
    parser.add_argument("--out", default="out/bench/hair",
                        help="output folder for bench.json and bench.md (out/bench/hair)")
    parser.add_argument("--no-23m", dest="fur_23m", action="store_false",
                        help="leave out the 22,977,900-point fur (needs ~0.6 GB of memory)")
    parser.add_argument("--threads", type=int, default=0, help="worker threads (0 = all cores)")
    parser.add_argument("--frames-23m", dest="frames_23m", action="store_true",
                        help="also time frames of the 22,977,900-point fur (minutes on lavapipe)")


def _timed(fn: Callable[[], Any], repeats: int = 1) -> Tuple[float, Any]:
    best, result = float("inf"), None
    for _ in range(repeats):
        start = time.perf_counter()
        result = fn()
        best = min(best, time.perf_counter() - start)
    return best, result


def _io_and_generators(sizes, threads: int, rows: List[Dict[str, Any]]) -> None:
    import weft

    for strands, points in sizes:
        seconds, hair = _timed(lambda: weft.generate_hair(strands, points, style="wavy",
                                                          threads=threads), 2)
        rows.append(dict(part="hair generator", size=f"{points:,} pts / {strands:,} strands",
                         seconds=seconds, rate=points / seconds, unit="points/s",
                         error=abs(hair.point_count - points), reference="target point count"))
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "h.hair")
            save_s, _ = _timed(lambda: weft.save_hair(path, hair), 2)
            size_mb = os.path.getsize(path) / 1e6
            load_s, back = _timed(lambda: weft.load_hair(path), 2)
        err = float(np.max(np.abs(back.points - hair.points)))
        rows.append(dict(part=".hair save", size=f"{size_mb:.1f} MB", seconds=save_s,
                         rate=size_mb / save_s, unit="MB/s", error=err,
                         reference="round trip, max abs dp"))
        rows.append(dict(part=".hair load", size=f"{size_mb:.1f} MB", seconds=load_s,
                         rate=size_mb / load_s, unit="MB/s", error=err,
                         reference="round trip, max abs dp"))


def _fur(sizes, threads: int, rows: List[Dict[str, Any]]) -> None:
    import weft

    for label, segments, rings, level in sizes:
        mesh = weft.Mesh.uv_sphere(0.5, segments, rings)
        seconds, fur = _timed(lambda: weft.generate_fur(mesh, level=level, threads=threads))
        off = fur.offsets[:-1]
        pts = fur.points
        step = pts[off + 1].astype(np.float64) - pts[off]
        # listing 1: the first step is the interpolated unit normal times the segment length
        lengths = np.linalg.norm(step, axis=1)
        err = float(np.max(np.abs(lengths - 0.03)))
        rows.append(dict(part="fur (CPU)", size=f"{fur.point_count:,} pts ({label})",
                         seconds=seconds, rate=fur.point_count / seconds, unit="points/s",
                         error=err, reference="listing 1: first step length 0.03"))
        del fur, pts, step


def _shading(samples: int, rows: List[Dict[str, Any]]) -> None:
    import weft
    from weft.reference import hair as R

    rng = np.random.default_rng(0)
    t, l, v = (rng.normal(size=(samples, 3)) for _ in range(3))
    ids = rng.integers(0, 2 ** 32, samples)
    for model in R.MODELS:
        mat = weft.HairMaterial(model, diffuse=(0.1, 0.1, 0.1))
        weft.hair_shade_eval(mat, t[:64], l[:64], v[:64], ids[:64])  # pipeline warm-up
        seconds, gpu = _timed(lambda: weft.hair_shade_eval(mat, t, l, v, ids), 2)
        ref = R.shade(R.HairParams.from_material(mat), t, l, v, ids)
        rel = (np.abs(gpu - ref) / np.maximum(np.abs(ref), 1e-3 * np.abs(ref).max())).max(axis=1)
        rows.append(dict(part=f"shading {model} (compute)", size=f"{samples:,} samples",
                         seconds=seconds, rate=samples / seconds, unit="samples/s",
                         error=float(rel.max()), error_p999=float(np.quantile(rel, 0.999)),
                         reference="NumPy float64, relative"))


def _shadows_and_oit(quick: bool, rows: List[Dict[str, Any]]) -> None:
    from weft.reference import hair_oit as O
    from weft.reference import hair_shadow as D

    for spacing in ("linear", "log"):
        seconds, (exact_err, dom_err, vs64, err64) = _timed(lambda: D.slab_errors(3, spacing))
        rows.append(dict(part=f"DOM 3 layers ({spacing})", size="16x16 slab, 640 strands",
                         seconds=seconds, rate=None, unit="", error=vs64,
                         reference="64-layer map, mean abs dT",
                         error_vs_exact=dom_err, error_64_vs_analytic=err64,
                         error_exact_vs_analytic=exact_err))
    stacks = 500 if quick else 20_000
    seconds, errors = _timed(lambda: O.random_stack_errors(stacks))
    for name, (mean, worst) in errors.items():
        rows.append(dict(part=f"WBOIT weight {name}", size=f"{stacks:,} stacks of 8",
                         seconds=seconds / len(errors), rate=None, unit="", error=mean,
                         error_max=worst, reference="sorted over, mean abs dC"))


def _frame_error(renderer, scene, camera, material, light_dir, radiance) -> float:
    """Max |radiance - NumPy model| over the hair pixels of a debug frame (visibility included)."""
    from weft.reference import hair as R

    d = renderer.render_debug(scene, camera)
    mask = d["hair"] >= 0
    if not mask.any():
        return float("nan")
    p = d["position"][mask].astype(np.float64)
    v = np.asarray(camera.position) - p
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    l = np.broadcast_to(-light_dir / np.linalg.norm(light_dir), p.shape)
    ids = np.rint(d["uv"][mask][:, 0]).astype(np.uint32)
    f = R.shade(R.HairParams.from_material(material), d["normal"][mask], l, v, ids)
    expected = np.asarray(scene.ambient) * d["albedo"][mask] + \
        d["shadow"][mask][:, None] * radiance * f
    return float(np.max(np.abs(d["linear"][mask][:, :3] - expected)))


def _frames(items, quick: bool, rows: List[Dict[str, Any]]) -> None:
    """Frame times of hair/fur strands (label, make strands) for B, B+S, B+S+T."""
    import weft

    size = QUICK_FRAME_SIZE if quick else FRAME_SIZE
    # the shadow maps and deep opacity maps drawn every frame, as the seed's S column times them
    # (the renderer would otherwise keep them while the strands and the light stand still)
    renderer = weft.Renderer(size, size, shadow_map_size=256 if quick else 2048,
                             reuse_shadow_maps=False)
    renderer.hair_dom_size = 64 if quick else 512
    material = weft.HairMaterial("sadeghi", diffuse=(0.08, 0.05, 0.03))
    light_dir = np.array([0.3, -1.0, -0.4])
    radiance = np.array([1.0, 0.95, 0.9]) * 2.0
    for label, make in items:
        strands = make()
        n = strands.point_count
        lo, hi = strands.points.min(axis=0), strands.points.max(axis=0)
        center, radius = (lo + hi) / 2, float(np.linalg.norm(hi - lo)) / 2
        camera = weft.Camera(tuple(center + np.array([0.0, 0.2, 2.6]) * radius), tuple(center),
                             (0, 1, 0), 0.8)
        see_through = weft.HairStrands(strands.points, strands.segments,
                                       transparency=np.full(n, 0.6, np.float32))
        for config in FRAME_CONFIGS:
            scene = weft.Scene()
            scene.ambient = (0.05, 0.05, 0.05)
            scene.add_light(weft.DirectionalLight(tuple(light_dir), (1.0, 0.95, 0.9), 2.0,
                                                  config != "B"))
            transparent = config == "B+S+T"
            scene.add_hair(see_through if transparent else strands, material)
            renderer.hair_transparency = transparent
            renderer.render_linear(scene, camera)  # upload and warm-up
            times, gpu = [], []
            for _ in range(2 if quick or n > 5_000_000 else 3):
                start = time.perf_counter()
                renderer.render_linear(scene, camera)
                times.append(time.perf_counter() - start)
                gpu.append(renderer.stats["gpu_ms"])
            passes = {p["name"]: p["gpu_ms"] for p in renderer.stats["passes"]
                      if p["name"].startswith(("hair", "shadow"))}
            renderer.hair_transparency = False
            error = _frame_error(renderer, scene, camera, material, light_dir, radiance)
            seconds = float(np.median(times))
            rows.append(dict(part=f"frame {config}", size=f"{label} {n:,} pts, {size}x{size}",
                             seconds=seconds, rate=1.0 / seconds, unit="fps",
                             gpu_ms=None if None in gpu else float(np.median(gpu)),
                             passes=passes, error=error,
                             reference="NumPy hair model on debug outputs, max abs dL"))
        del strands, see_through


def _frame_items(quick: bool, fur_23m: bool, threads: int):
    import weft

    hair = QUICK_HAIR_SIZES[:1] if quick else HAIR_SIZES
    items = [("hair", lambda s=s, p=p: weft.generate_hair(s, p, style="wavy", threads=threads))
             for s, p in hair]
    fur = QUICK_FUR_SIZES if quick else FUR_SIZES if fur_23m else FUR_SIZES[:1]
    items += [(f"fur {label}", lambda g=g, r=r, lv=lv: weft.generate_fur(
                   weft.Mesh.uv_sphere(0.5, g, r), level=lv, threads=threads))
              for label, g, r, lv in fur]
    return items


def _markdown(report: Dict[str, Any]) -> str:
    header = ["part", "size", "time (s)", "rate", "error", "reference"]
    body = []
    for r in report["results"]:
        rate = f"{r['rate']:.3g} {r['unit']}" if r.get("rate") else ""
        extra = ""
        if "error_p999" in r:
            extra = f" (99.9%: {r['error_p999']:.2g})"
        elif "error_vs_exact" in r:
            extra = (f" (vs exact {r['error_vs_exact']:.2g}; 64-layer vs exp(-kz) "
                     f"{r['error_64_vs_analytic']:.2g})")
        elif "error_max" in r:
            extra = f" (max {r['error_max']:.2g})"
        if r["part"].startswith("frame"):
            rate = f"{r['rate']:.3g} fps" + \
                (f", GPU {r['gpu_ms']:.0f} ms" if r.get("gpu_ms") is not None else "")
        body.append([r["part"], r["size"], f"{r['seconds']:.4f}", rate,
                     f"{r['error']:.3g}{extra}", r["reference"]])
    machine = report["machine"]
    device = machine.get("device", {}).get("name", "?")
    return "\n".join([
        "# Hair benchmark", "",
        f"- command: `{report['command']}`",
        f"- machine: {machine.get('processor', '?')} ({machine.get('cpu_count')} CPUs), "
        f"Vulkan device {device}", "",
        markdown_table(header, body), "",
        "Frame times: B lighting only, B+S + shadow map and deep opacity map, B+S+T + weighted "
        "blended OIT (SPEC §5.5; the seed's GTX 980 figures are in BENCHMARKS.md).", ""])


def run(args: argparse.Namespace) -> int:
    quick = bool(args.quick)
    fur_sizes = QUICK_FUR_SIZES if quick else FUR_SIZES if args.fur_23m else FUR_SIZES[:1]
    steps = [("hair IO and generators", lambda r: _io_and_generators(
                 QUICK_HAIR_SIZES if quick else HAIR_SIZES, args.threads, r)),
             ("fur", lambda r: _fur(fur_sizes, args.threads, r)),
             ("shading", lambda r: _shading(QUICK_SHADE_SAMPLES if quick else SHADE_SAMPLES, r)),
             ("shadows and OIT", lambda r: _shadows_and_oit(quick, r)),
             ("frame times", lambda r: _frames(
                 _frame_items(quick, args.frames_23m, args.threads), quick, r))]
    progress = Progress(len(steps))
    rows: List[Dict[str, Any]] = []
    for label, step in steps:
        progress.update(label)
        step(rows)
        progress.step(label)
    progress.close()
    command = "python -m weft.bench hair" + (" --quick" if quick else "") + \
        ("" if args.fur_23m or quick else " --no-23m") + \
        (" --frames-23m" if args.frames_23m and not quick else "")
    report = {"benchmark": "hair", "command": command, "machine": machine_info(),
              "results": rows}
    markdown = _markdown(report)
    paths = write_report(args.out, report, markdown)
    print(markdown)
    print("written: " + ", ".join(paths))
    return 0
