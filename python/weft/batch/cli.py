"""``python -m weft batch {btf,render}``: the batch functions on the command line.

    python -m weft batch btf DATASET... --out DIR [--tiles 4] [--split tiles|views]
                                        [btf fit options] [--serial | --address HOST:PORT]
                                        [--workers N] [--retries 3] [--memory-gb 2] [--no-times]
    python -m weft batch render JOBS.json --out DIR [--serial | --address HOST:PORT]
                                           [--workers N] [--retries 3]
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any, Dict

from weft.reporting import add_progress_arguments

_EPILOG = ("Without --address a private local Ray cluster is started for the batch (all cores, "
           "or --workers) and stopped after it; --address joins a running cluster (ray start "
           "--head on one machine, ray start --address HEAD:6379 on the others; docs/batch.md). "
           "--serial runs everything in this process without Ray, with the same outputs. "
           "Re-running a batch into the same --out skips finished outputs (out/manifest.json).")


def _common(p: argparse.ArgumentParser) -> None:
    where = p.add_mutually_exclusive_group()
    where.add_argument("--serial", action="store_true",
                       help="run in this process without Ray (the reference; same bytes)")
    where.add_argument("--address", default=None, metavar="HOST:PORT",
                       help="an existing Ray cluster ('auto': the one on this machine)")
    p.add_argument("--workers", type=int, default=None, metavar="N",
                   help="CPUs of the local cluster (default all cores); render: workers "
                        "(renderers) to start (default one per CPU)")
    p.add_argument("--retries", type=int, default=3,
                   help="re-runs of a task whose worker process or node was lost (3)")
    add_progress_arguments(p)
    p.add_argument("--json", action="store_true", help="print the summary as JSON")


def add_parser(sub: Any) -> None:
    """Adds ``batch`` with ``btf`` and ``render`` to ``python -m weft``."""
    from weft.btf.cli import add_fit_options

    batch = sub.add_parser(
        "batch", help="fit many BTF datasets or render many frames, locally or on a Ray cluster",
        description="Batch work as tasks on Ray (issue 16): 'btf' fits BTF datasets split by "
                    "bands of texels or by views into the outputs of 'btf fit'; 'render' renders "
                    "the frames of render jobs on workers that keep one renderer each. Both "
                    "write out/manifest.json and resume.", epilog=_EPILOG)
    cmds = batch.add_subparsers(dest="batch_command", metavar="{btf,render}")
    cmds.required = True

    b = cmds.add_parser(
        "btf", help="fit BTF datasets (folders or zips) into maps, metrics and reports",
        description="Fits every dataset as 'python -m weft btf fit' does, into OUT/NAME/ (NAME: "
                    "the folder or zip name). --split tiles: one model over the chosen views, its "
                    "per-texel fits split into --tiles bands of rows; --split views: every view "
                    "fitted on its own into OUT/NAME/views/tvTTT_pvPPP/ (NAME/views.json lists "
                    "them).", epilog=_EPILOG)
    b.add_argument("datasets", nargs="+", metavar="DATASET", help="BTF folders or zips")
    b.add_argument("--out", required=True, help="output folder")
    b.add_argument("--tiles", type=int, default=4, help="bands of texel rows per fit (4)")
    b.add_argument("--split", choices=("tiles", "views"), default="tiles",
                   help="tasks by bands of texels of one fit (default) or one fit per view")
    b.add_argument("--memory-gb", type=float, default=2.0,
                   help="memory a task may use, GiB (2): reserved on the cluster; a dataset "
                        "that needs more (4 x its float samples) fails with a message")
    b.add_argument("--cpus-per-task", type=float, default=1.0,
                   help="CPUs a task reserves on the cluster, and its native fit threads (1)")
    b.add_argument("--no-times", dest="times", action="store_false",
                   help="write fit times as not measured (nan), so that reports of repeated "
                        "runs are byte-identical (times stay in the manifest)")
    add_fit_options(b, truth=False)
    _common(b)
    b.set_defaults(handler=cmd_btf)

    r = cmds.add_parser(
        "render", help="render the frames of render jobs (JSON) into PNGs",
        description="Renders every frame of the jobs in JOBS (JSON: scene, frames, camera path, "
                    "settings; see weft.batch.render_jobs) into OUT/JOB/frame_NNNN.png.",
        epilog=_EPILOG)
    r.add_argument("jobs", metavar="JOBS", help="job file (JSON)")
    r.add_argument("--out", required=True, help="output folder")
    r.add_argument("--gpus-per-worker", type=float, default=0.0, metavar="G",
                   help="GPUs a render worker reserves on a cluster's GPU nodes (0)")
    _common(r)
    r.set_defaults(handler=cmd_render)


def _options(args: argparse.Namespace) -> Dict[str, Any]:
    keys = ("views", "gamma", "robust", "max_exponent", "per_texel_exponent", "nonlinear",
            "solver", "luminance_normals", "visibility", "lafortune", "figures")
    opts = {k: getattr(args, k) for k in keys}
    if args.split == "views":
        if args.views != "frontal":
            raise ValueError("--split views fits each view on its own: leave out --views")
        del opts["views"]
    opts["threads"] = 0 if args.serial else max(1, int(round(args.cpus_per_task)))
    return opts


def _finish(summary: Dict[str, Any], args: argparse.Namespace, what: str) -> int:
    if args.json:
        print(json.dumps(summary, indent=2, default=str))
    else:
        rate = summary.get(f"{what}_per_s")
        print(f"{summary['done']} done, {summary['skipped']} skipped (finished before), "
              f"{len(summary['failed'])} failed in {summary['seconds']:.1f} s on "
              f"{summary['executor']} ({summary['workers']} workers)"
              + (f", {rate:.3g} {what}/s" if rate else "") + f"; manifest in {args.out}")
    for name, error in summary["failed"].items():
        print(f"weft: failed: {name}: {error}", file=sys.stderr)
    return 1 if summary["failed"] else 0


def cmd_btf(args: argparse.Namespace) -> int:
    import weft.batch as wb

    jobs = wb.make_jobs(args.datasets, _options(args), tiles=args.tiles, split=args.split,
                        memory=int(args.memory_gb * 2**30), times=args.times)
    with wb.executor("serial" if args.serial else "ray", args.address, args.workers,
                     retries=args.retries, cpus_per_task=args.cpus_per_task) as ex:
        summary = wb.fit_btf_batch(jobs, args.out, ex, progress=args.progress)
    return _finish(summary, args, "texels")


def cmd_render(args: argparse.Namespace) -> int:
    import weft.batch as wb

    jobs = wb.load_render_jobs(args.jobs)
    with wb.executor("serial" if args.serial else "ray", args.address, args.workers,
                     retries=args.retries) as ex:
        summary = wb.render_batch(jobs, args.out, ex, workers=args.workers,
                                  progress=args.progress, gpus=args.gpus_per_worker)
    return _finish(summary, args, "frames")
