"""``render_batch``: frames of many render jobs as tasks on workers that keep a renderer each.

Frames go to ``out/JOB/frame_NNNN.png`` (written by this process from the PNG bytes a worker
returns, atomically) and ``out/manifest.json`` records, per frame, its key, the settings, the
timings, the worker and the Vulkan device. Finished frames (file present, same key) are
skipped on a re-run; a failing frame is recorded and the rest go on; a worker process that
dies is restarted and its frames re-run (Ray), so the batch still completes.
"""

from __future__ import annotations

import os
import time
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

from weft.batch.manifest import Manifest, key_of, write_bytes
from weft.batch.render_jobs import RenderJob, frame_tasks
from weft.batch.render_worker import FrameRenderer
from weft.bench import Progress

#: Bytes a render worker reserves: its renderer's images at the largest job size (colour,
#: depth, MSAA, shadow and dome maps, probes) stay well under this at 1920x1080 on lavapipe;
#: weft's share of a process is about 0.3 GiB at 320x240 (measured, docs/batch.md).
WORKER_MEMORY = 1 << 30


def frame_file(job: RenderJob, frame: int) -> str:
    return os.path.join(job.name, f"frame_{frame:04d}.png")


def render_batch(jobs: Sequence[RenderJob], out: str, executor: Any, workers: Optional[int] = None,
                 progress: Optional[bool] = None, memory: int = WORKER_MEMORY, gpus: float = 0.0,
                 on_event: Optional[Callable[[Dict[str, Any]], None]] = None) -> Dict[str, Any]:
    """Renders every frame of ``jobs`` (:func:`~weft.batch.render_jobs.load_render_jobs`) into
    ``out`` on ``workers`` render workers (default: one per CPU the executor has), each
    reserving ``memory`` bytes and ``gpus`` GPUs on its node (Ray). Returns the
    summary (also in the manifest): frames done, skipped, failed {"job/frame": error}, seconds,
    frames_per_s, task_seconds (inside the workers, summed), workers, the devices used."""
    os.makedirs(out, exist_ok=True)
    manifest = Manifest(out, "render")
    t0 = time.perf_counter()
    keys = {j.name: key_of("render", j.spec()) for j in jobs}
    todo: List[Tuple[RenderJob, int]] = []
    skipped = 0
    for job, frame in frame_tasks(jobs):
        entry = manifest.job(job.name)
        entry["spec"] = {k: v for k, v in job.spec().items() if k != "source"}
        if manifest.finished(job.name, f"{frame:04d}", _frame_key(keys, job, frame), out):
            skipped += 1
        else:
            todo.append((job, frame))
    bar = Progress(len(todo), enabled=progress)
    failed: Dict[str, str] = {}
    devices: Dict[str, int] = {}
    done, task_seconds = 0, 0.0
    if todo:
        size = max(1, min(len(todo), workers or executor.workers))
        pool = executor.pool(FrameRenderer, size, memory=memory, gpus=gpus)
        try:
            for (job, frame), value, error in pool.map_unordered("render", todo):
                name = f"{job.name}/{frame:04d}"
                bar.step(name)
                if error is not None:
                    failed[name] = f"{type(error).__name__}: {error}"
                    manifest.fail(job.name, f"{frame:04d}", error)
                    _emit(on_event, stage="failed", job=job.name, frame=frame,
                          error=failed[name])
                    continue
                write_bytes(os.path.join(out, frame_file(job, frame)), value["png"])
                devices[value["device"]] = devices.get(value["device"], 0) + 1
                task_seconds += sum(value["timings"][k] for k in
                                    ("setup_s", "scene_s", "render_s", "encode_s"))
                done += 1
                manifest.record(job.name, f"{frame:04d}", dict(
                    file=frame_file(job, frame), key=_frame_key(keys, job, frame),
                    bytes=len(value["png"]), device=value["device"], worker=value["worker"],
                    worker_frames=value["worker_frames"], timings=value["timings"],
                    validation_messages=value["validation_messages"]))
                _emit(on_event, stage="frame", job=job.name, frame=frame,
                      worker=value["worker"])
        finally:
            pool.close()
    bar.close()
    seconds = time.perf_counter() - t0
    summary = dict(frames=len(todo) + skipped, done=done, skipped=skipped, failed=failed,
                   seconds=seconds, frames_per_s=done / seconds if seconds > 0 else None,
                   task_seconds=task_seconds,
                   executor=executor.kind, workers=executor.workers, devices=devices)
    manifest.save(force=True, **summary)
    return summary


def _frame_key(keys: Dict[str, str], job: RenderJob, frame: int) -> str:
    return key_of(keys[job.name], frame)


def _emit(on_event: Optional[Callable[[Dict[str, Any]], None]], **event: Any) -> None:
    if on_event is not None:
        on_event(event)
