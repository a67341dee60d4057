"""``fit_btf_batch``: many BTF datasets, each split into tasks by bands of texels or by views.

Per dataset (``split="tiles"``): prepare -> ``tiles`` band fits -> assemble
(:mod:`weft.batch.btf_stages`); with ``split="views"`` every view of the dataset is fitted on
its own (the same as ``btf fit --views T,P``) into ``NAME/views/tvTTT_pvPPP/``, with
``NAME/views.json`` listing them. Outputs go to ``out/NAME/`` exactly as ``btf fit --out``
writes them, and ``out/manifest.json`` records each job.
"""

from __future__ import annotations

import json
import os
import time
import zipfile
from dataclasses import replace
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import weft
from weft.batch import btf_stages
from weft.batch.btf_stages import BtfJob
from weft.batch.manifest import Manifest, key_of, write_bytes
from weft.bench import Progress

Event = Dict[str, Any]


def dataset_name(path: str) -> str:
    base = os.path.basename(os.path.normpath(path))
    return base[:-4] if base.lower().endswith(".zip") else base


def dataset_views(path: str) -> List[Tuple[float, float]]:
    """The (θ_v, φ_v) of a Bonn-layout folder or zip, from its file names."""
    from weft import _core

    if os.path.isdir(path):
        names = [n for _, _, files in os.walk(path) for n in files]
    elif zipfile.is_zipfile(path):
        with zipfile.ZipFile(path) as z:
            names = [os.path.basename(n) for n in z.namelist()]
    else:
        raise weft.IoError(f"{path}: not a BTF folder or zip")
    views = set()
    for n in names:
        a = _core.btf_parse_file_name(n)
        if a is not None:
            views.add((float(a[2]), float(a[3])))
    if not views:
        raise weft.IoError(f"{path}: no Bonn-layout images (…_tlTTT_plPPP_tvTTT_pvPPP.jpg)")
    return sorted(views)


def view_name(view: Tuple[float, float]) -> str:
    return f"tv{int(round(view[0])):03d}_pv{int(round(view[1])):03d}"


def make_jobs(paths: Sequence[str], options: Optional[Dict[str, Any]] = None, tiles: int = 4,
              split: str = "tiles", memory: int = 2 << 30, times: bool = True) -> List[BtfJob]:
    """The jobs for ``paths`` (folders or zips); ``split="views"`` gives one job per view."""
    if split not in ("tiles", "views"):
        raise weft.InvalidArgument(f"split must be 'tiles' or 'views', got {split!r}")
    if isinstance(tiles, bool) or int(tiles) < 1:
        raise weft.InvalidArgument(f"tiles must be >= 1, got {tiles}")
    if int(memory) <= 0:
        raise weft.InvalidArgument(f"memory must be > 0 bytes, got {memory}")
    names: Dict[str, str] = {}
    jobs: List[BtfJob] = []
    for p in paths:
        path = os.path.abspath(os.fspath(p))
        if not os.path.exists(path):
            raise weft.IoError(f"{p}: no such BTF folder or zip")
        name = dataset_name(path)
        if name in names:
            raise weft.InvalidArgument(f"two datasets named {name!r}: {names[name]} and {path}")
        names[name] = path
        job = BtfJob(name, path, dict(options or {}), int(tiles), int(memory), bool(times))
        job.args()  # rejects unknown options before anything runs
        if split == "tiles":
            jobs.append(job)
            continue
        if "views" in job.options:
            raise weft.InvalidArgument("split='views' fits every view on its own: leave out "
                                       "the 'views' option")
        for v in dataset_views(path):
            jobs.append(replace(job, name=f"{name}/views/{view_name(v)}",
                                options={**job.options, "views": f"{v[0]:g},{v[1]:g}"}))
    return jobs


def _job_key(job: BtfJob) -> str:
    st = os.stat(job.path)
    return key_of("btf", job.args().__dict__, job.tiles, job.times, st.st_size, st.st_mtime_ns)


def fit_btf_batch(jobs: Sequence[BtfJob], out: str, executor: Any,
                  progress: Optional[bool] = None,
                  on_event: Optional[Callable[[Event], None]] = None) -> Dict[str, Any]:
    """Fits ``jobs`` (:func:`make_jobs`) on ``executor`` (:func:`weft.batch.executor`) into
    ``out``. Finished jobs (same key in the manifest, metrics.json present) are skipped; a
    failing job is recorded and the others go on. Returns the summary (also in the manifest):
    done, skipped, failed {name: error}, seconds, texels, texels_per_s, task_seconds (time
    spent inside the tasks of the finished jobs, summed)."""
    os.makedirs(out, exist_ok=True)
    manifest = Manifest(out, "btf")
    t0 = time.perf_counter()
    todo, skipped = [], []
    for job in jobs:
        key = _job_key(job)
        (skipped if manifest.finished(job.name, "fit", key, out) else todo).append((job, key))
    bar = Progress(sum(len(_stages(j)) for j, _ in todo), enabled=progress)
    owner: Dict[int, Tuple[BtfJob, str, str]] = {}
    for job, key in todo:
        for handle, stage in _submit(executor, job):
            owner[handle.id] = (job, key, stage)
    failed: Dict[str, str] = {}
    texels, task_seconds = 0, 0.0
    for handle, value, error in executor.finished():
        job, key, stage = owner[handle.id]
        bar.step(handle.label)
        if error is not None:
            if job.name not in failed:
                failed[job.name] = f"{type(error).__name__}: {error}"
                manifest.fail(job.name, "fit", error)
            _emit(on_event, stage="failed", job=job.name, error=failed[job.name])
            continue
        _emit(on_event, stage=stage, job=job.name, worker=_worker(value))
        if stage != "assemble":
            continue
        files = value["files"]
        for rel in sorted(files, key=lambda r: (r == "metrics.json", r)):
            write_bytes(os.path.join(out, job.name, rel), files[rel])
        texels += value["texels"]
        task_seconds += value["task_seconds"]
        manifest.record(job.name, "fit", dict(
            file=os.path.join(job.name, "metrics.json"), key=key, files=len(files),
            best=value["best"], deviation=value["deviation"], texels=value["texels"],
            samples=value["samples"], tile_seconds=value["tile_seconds"],
            task_seconds=value["task_seconds"],
            workers=value["workers"], device="cpu"))
    bar.close()
    _write_view_indexes(out, jobs, manifest)
    seconds = time.perf_counter() - t0
    summary = dict(jobs=len(jobs), done=len(todo) - len(failed), skipped=len(skipped),
                   failed=failed, seconds=seconds, texels=texels, task_seconds=task_seconds,
                   texels_per_s=texels / seconds if seconds > 0 else None,
                   executor=executor.kind, workers=executor.workers)
    manifest.save(force=True, **summary)
    return summary


def _stages(job: BtfJob) -> List[str]:
    """The tasks of a job, in order: prepare, Blinn-Phong bands, choose, Lafortune bands,
    assemble (the nonlinear ones as the options ask)."""
    from weft.btf.fit_report import lafortune_lobes

    args = job.args()
    bp = ["blinn_phong"] * job.tiles if args.nonlinear else []
    laf = ["lafortune"] * job.tiles if lafortune_lobes(args) else []
    return ["prepare"] + bp + (["choose"] if bp and laf else []) + laf + ["assemble"]


def _submit(executor: Any, job: BtfJob) -> List[Tuple[Any, str]]:
    """Submits a job's task graph; returns (handle, stage) of every task that reports."""
    stages = _stages(job)
    n, mem = job.tiles, job.memory
    parts = executor.submit(btf_stages.prepare, job, num_returns=n + 1, memory=mem,
                            label=f"{job.name} prepare", track=[0], spread=True)
    out: List[Tuple[Any, str]] = [(parts[0], "prepare")]

    def bands(kind: str, seeds: List[Any]) -> List[Any]:
        hs = [executor.submit(btf_stages.fit_tile, job, parts[k + 1], kind, seeds[k],
                              memory=mem, label=f"{job.name} {kind} band {k}")
              for k in range(n)]
        out.extend((h, kind) for h in hs)
        return hs

    bp = bands("blinn_phong", [None] * n) if "blinn_phong" in stages else []
    chosen, seeds = None, [None] * n
    if "choose" in stages:
        c = executor.submit(btf_stages.choose, job, parts[0], *bp, num_returns=n + 1,
                            memory=mem, label=f"{job.name} choose", track=[0])
        out.append((c[0], "choose"))
        chosen, seeds = c[0], c[1:]
    laf = bands("lafortune", seeds) if "lafortune" in stages else []
    h = executor.submit(btf_stages.assemble, job, parts[0], chosen, *bp, *laf, memory=mem,
                        label=f"{job.name} assemble")
    out.append((h, "assemble"))
    return out


def _worker(value: Any) -> Any:
    if isinstance(value, tuple):
        value = value[0]
    return value.get("worker") if isinstance(value, dict) else None


def _emit(on_event: Optional[Callable[[Event], None]], **event: Any) -> None:
    if on_event is not None:
        on_event(event)


def _write_view_indexes(out: str, jobs: Sequence[BtfJob], manifest: Manifest) -> None:
    """``NAME/views.json`` per dataset fitted by views: each view's best model and deviation."""
    per: Dict[str, Dict[str, Any]] = {}
    for job in jobs:
        if "/views/" not in job.name:
            continue
        name, view = job.name.split("/views/")
        entry = manifest.data["jobs"].get(job.name, {}).get("outputs", {}).get("fit")
        per.setdefault(name, {})[view] = (
            {"best": entry["best"], "deviation": entry["deviation"],
             "report": f"views/{view}/report.md"} if entry else None)
    for name, views in per.items():
        text = json.dumps({"views": views}, indent=2, sort_keys=True) + "\n"
        write_bytes(os.path.join(out, name, "views.json"), text.encode("utf-8"))
