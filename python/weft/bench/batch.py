"""Batch benchmark (issue 16): BTF fits and frames, serial against Ray with 1 and 2 workers.

Each configuration runs the same batch into a fresh folder:

- ``serial``: :class:`weft.batch.SerialExecutor` in this process (no Ray), one fit thread;
- ``ray 1`` / ``ray 2``: a local Ray cluster with 1 or 2 CPUs (one task or render worker per
  CPU, one fit thread per task), started before the clock runs; Ray's worker processes are
  started by a warm-up task each, as they stay up in a real batch.

Every worker gets one CPU: one fit thread, and lavapipe (Vulkan on the CPU) one rasteriser
thread (``LP_NUM_THREADS=1``, set here unless given), so that 2 workers can gain what 2 CPUs
give instead of two renderers each spreading over every core.

Figures: wall seconds, throughput (texels/s for BTF: texels x datasets; frames/s), the
overhead per task (``(wall x workers - time inside the tasks) / tasks``: what a task costs
besides its own work, for serialising, scheduling, moving results and writing them, and idle
workers; measured inside each run, so it does not depend on the other runs' load), scaling
efficiency (throughput with 2 workers / (2 x with 1)), and the error: files whose bytes differ
from the serial run (must be 0). The machine's load average is recorded before and after:
on a shared machine it decides what 2 workers can gain.
"""

from __future__ import annotations

import argparse
import os
import shutil
import tempfile
import time
from typing import Any, Dict, List, Tuple

from weft.bench import Progress, machine_info, markdown_table, write_report

DESCRIPTION = ("batch: BTF datasets and render frames on Ray (1 and 2 workers) against the "
               "serial run: throughput, overhead per task, scaling efficiency, identical bytes")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--quick", action="store_true", help="small sizes: about a minute")
    parser.add_argument("--out", default="out/bench/batch",
                        help="output folder for bench.json and bench.md (out/bench/batch)")
    parser.add_argument("--datasets", type=int, default=None,
                        help="BTF datasets (quick 4, else 8)")
    parser.add_argument("--size", type=int, default=None,
                        help="texels per side of each dataset (quick 24, else 64)")
    parser.add_argument("--tiles", type=int, default=4, help="bands of rows per dataset (4)")
    parser.add_argument("--frames", type=int, default=None, help="frames (quick 8, else 32)")
    parser.add_argument("--frame-size", type=int, nargs=2, default=None, metavar=("W", "H"),
                        help="frame size (quick 96 72, else 320 240)")


def _inputs(root: str, datasets: int, size: int, frames: int, w: int,
            h: int) -> Tuple[List[str], str]:
    import json

    import weft.btf.synth as synth

    paths = []
    for i in range(datasets):
        samples, _ = synth.synthesize_random(i, size, noise=0.002)
        path = os.path.join(root, f"d{i}")
        os.makedirs(path)
        synth.write(path, samples, fmt="png")
        paths.append(path)
    jobs = {"jobs": [{"name": "orbit", "scene": "default", "frames": frames,
                      "camera": {"orbit": {"target": [0, 0.4, 0], "radius": 4.0, "height": 1.5}},
                      "settings": {"width": w, "height": h}}]}
    job_file = os.path.join(root, "jobs.json")
    with open(job_file, "w", encoding="utf-8") as f:
        json.dump(jobs, f)
    return paths, job_file


def _tree(root: str) -> Dict[str, bytes]:
    out = {}
    for d, _, names in os.walk(root):
        for n in names:
            if n != "manifest.json":
                with open(os.path.join(d, n), "rb") as f:
                    out[os.path.relpath(os.path.join(d, n), root)] = f.read()
    return out


def _warm(ex: Any, workers: int) -> None:
    """Starts Ray's worker processes (and imports weft in them) before the clock runs."""
    import weft.batch.btf_stages as stages

    for _ in range(workers):
        ex.submit(stages.bands, 8, 2)
    for _ in ex.finished():
        pass


def _configs() -> List[Tuple[str, str, int]]:
    return [("serial", "serial", 1), ("ray 1", "ray", 1), ("ray 2", "ray", 2)]


def run(args: argparse.Namespace) -> int:
    import weft.batch as wb
    from weft.batch.btf_batch import _stages

    os.environ.setdefault("LP_NUM_THREADS", "1")  # before any Vulkan device; workers inherit it
    quick = bool(args.quick)
    datasets = args.datasets or (4 if quick else 8)
    size = args.size or (24 if quick else 64)
    frames = args.frames or (8 if quick else 32)
    w, h = args.frame_size or ((96, 72) if quick else (320, 240))
    root = tempfile.mkdtemp(prefix="weft-bench-batch-")
    load_before = os.getloadavg()
    rows: List[Dict[str, Any]] = []
    progress = Progress(2 * len(_configs()))
    try:
        paths, job_file = _inputs(root, datasets, size, frames, w, h)
        btf_jobs = wb.make_jobs(paths, dict(figures=False, threads=1), tiles=args.tiles,
                                times=False)
        render_jobs = wb.load_render_jobs(job_file)
        reference: Dict[str, Dict[str, bytes]] = {}
        for name, mode, workers in _configs():
            t0 = time.perf_counter()
            with wb.executor(mode, workers=workers) as ex:
                start_s = time.perf_counter() - t0
                if mode == "ray":
                    _warm(ex, workers)
                for kind in ("btf", "render"):
                    progress.update(f"{name}: {kind}")
                    out = os.path.join(root, f"{kind}-{mode}-{workers}")
                    if kind == "btf":
                        s = wb.fit_btf_batch(btf_jobs, out, ex, progress=False)
                        tasks, amount = sum(len(_stages(j)) for j in btf_jobs), s["texels"]
                    else:
                        s = wb.render_batch(render_jobs, out, ex, workers=workers,
                                            progress=False)
                        tasks, amount = frames, s["done"]
                    files = _tree(out)
                    if mode == "serial":
                        reference[kind] = files
                    differ = sum(1 for k in set(files) | set(reference[kind])
                                 if files.get(k) != reference[kind].get(k))
                    busy = workers * s["seconds"]
                    rows.append(dict(kind=kind, config=name, workers=workers,
                                     seconds=s["seconds"], tasks=tasks, amount=amount,
                                     task_seconds=s["task_seconds"],
                                     overhead_per_task_s=(busy - s["task_seconds"]) / tasks,
                                     throughput=amount / s["seconds"], failed=len(s["failed"]),
                                     files=len(files), error=differ, cluster_start_s=start_s))
                    progress.step(f"{name}: {kind}")
    finally:
        progress.close()
        shutil.rmtree(root, ignore_errors=True)
    _derive(rows)
    command = "python -m weft.bench batch" + (" --quick" if quick else "")
    report = {"benchmark": "batch", "command": command, "machine": machine_info(),
              "lp_num_threads": os.environ.get("LP_NUM_THREADS"),
              "load_average": {"before": load_before, "after": os.getloadavg()},
              "inputs": dict(datasets=datasets, size=size, tiles=args.tiles, frames=frames,
                             frame_size=[w, h]),
              "results": rows}
    markdown = _markdown(report)
    paths = write_report(args.out, report, markdown)
    print(markdown)
    print("written: " + ", ".join(paths))
    return 0 if all(r["error"] == 0 and r["failed"] == 0 for r in rows) else 1


def _derive(rows: List[Dict[str, Any]]) -> None:
    """Speed-up against serial and scaling efficiency (2 workers against 1)."""
    for kind in ("btf", "render"):
        by = {r["config"]: r for r in rows if r["kind"] == kind}
        serial, one, two = by["serial"], by["ray 1"], by["ray 2"]
        for r in (one, two):
            r["speedup_vs_serial"] = serial["seconds"] / r["seconds"]
        two["scaling_efficiency"] = two["throughput"] / (2 * one["throughput"])


def _markdown(report: Dict[str, Any]) -> str:
    i = report["inputs"]
    m = report["machine"]
    load = report["load_average"]
    unit = {"btf": "texels/s", "render": "frames/s"}
    rows = []
    for r in report["results"]:
        rows.append([r["kind"], r["config"], f"{r['seconds']:.2f}",
                     f"{r['throughput']:.4g} {unit[r['kind']]}", r["tasks"],
                     f"{r['overhead_per_task_s'] * 1000:.0f} ms",
                     "–" if "speedup_vs_serial" not in r else f"{r['speedup_vs_serial']:.2f}x",
                     "–" if "scaling_efficiency" not in r else
                     f"{r['scaling_efficiency'] * 100:.0f}%",
                     f"{r['error']} of {r['files']}"])
    return "\n".join([
        "# Batch benchmark", "",
        f"`{report['command']}` on {m.get('processor') or m.get('machine')} "
        f"({m.get('cpu_count')} cores), load average {load['before'][0]:.2f} before, "
        f"{load['after'][0]:.2f} after.", "",
        f"BTF: {i['datasets']} synthetic datasets of {i['size']}x{i['size']} texels x 81 "
        f"samples, {i['tiles']} bands each (tasks per dataset: prepare, Blinn-Phong bands, "
        f"choose, Lafortune bands, assemble), every model, no "
        f"figures, one fit thread per task. Render: {i['frames']} frames of the default scene "
        f"at {i['frame_size'][0]}x{i['frame_size'][1]} on an orbit, one render worker per CPU "
        f"(LP_NUM_THREADS={report.get('lp_num_threads')}). "
        "Ray clusters are local and started (and their workers warmed) before the clock runs. "
        "Overhead / task = (wall x workers - time inside the tasks) / tasks.",
        "",
        markdown_table(["batch", "run", "wall s", "throughput", "tasks", "overhead / task",
                        "speed-up vs serial", "scaling 1->2", "files differing from serial"],
                       rows), ""])
