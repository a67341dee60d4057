"""Hair benchmark (SPEC §5, CPU and compute parts; the frame-time tables B / B+S / B+S+T at
800 x 800 need the renderer's hair passes and come with them).

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
               "deep-opacity-map and WBOIT error (renderer frame times come later)")

HAIR_SIZES: Tuple[Tuple[int, int], ...] = ((10_000, 160_000), (10_000, 687_532),
                                           (15_000, 1_031_268))
QUICK_HAIR_SIZES: Tuple[Tuple[int, int], ...] = ((500, 8_000), (500, 34_377))
#: (label, sphere segments, sphere rings, level): 2,088,900 and 22,977,900 points exactly.
FUR_SIZES = (("2.1M", 450, 212, 1), ("23M", 198, 212, 5))
QUICK_FUR_SIZES = (("quick", 32, 16, 2),)
SHADE_SAMPLES, QUICK_SHADE_SAMPLES = 262_144, 4_096


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--quick", action="store_true",
                        help="small sizes: a few seconds, for CI")
    parser.add_argument("--out", default="out/bench/hair",
                        help="output folder for bench.json and bench.md (out/bench/hair)")
    parser.add_argument("--no-23m", dest="fur_23m", action="store_false",
                        help="leave out the 22,977,900-point fur (needs ~0.6 GB of memory)")
    parser.add_argument("--threads", type=int, default=0, help="worker threads (0 = all cores)")


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
        body.append([r["part"], r["size"], f"{r['seconds']:.4f}", rate,
                     f"{r['error']:.3g}{extra}", r["reference"]])
    machine = report["machine"]
    device = machine.get("device", {}).get("name", "?")
    return "\n".join([
        "# Hair benchmark (CPU and compute parts)", "",
        f"- command: `{report['command']}`",
        f"- machine: {machine.get('processor', '?')} ({machine.get('cpu_count')} CPUs), "
        f"Vulkan device {device}", "",
        markdown_table(header, body), "",
        "Frame times (B / B+S / B+S+T at 800 x 800, SPEC §5.5) need the renderer's hair "
        "passes and are not measured yet.", ""])


def run(args: argparse.Namespace) -> int:
    quick = bool(args.quick)
    fur_sizes = QUICK_FUR_SIZES if quick else FUR_SIZES if args.fur_23m else FUR_SIZES[:1]
    steps = [("hair IO and generators", lambda r: _io_and_generators(
                 QUICK_HAIR_SIZES if quick else HAIR_SIZES, args.threads, r)),
             ("fur", lambda r: _fur(fur_sizes, args.threads, r)),
             ("shading", lambda r: _shading(QUICK_SHADE_SAMPLES if quick else SHADE_SAMPLES, r)),
             ("shadows and OIT", lambda r: _shadows_and_oit(quick, r))]
    progress = Progress(len(steps))
    rows: List[Dict[str, Any]] = []
    for label, step in steps:
        progress.update(label)
        step(rows)
        progress.step(label)
    progress.close()
    command = "python -m weft.bench hair" + (" --quick" if quick else "") + \
        ("" if args.fur_23m or quick else " --no-23m")
    report = {"benchmark": "hair", "command": command, "machine": machine_info(),
              "results": rows}
    markdown = _markdown(report)
    paths = write_report(args.out, report, markdown)
    print(markdown)
    print("written: " + ", ".join(paths))
    return 0
