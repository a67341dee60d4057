"""The worker that renders frames: one per process (a Ray actor, or the serial run's own).

It keeps one Vulkan device and :class:`weft.Renderer` for as long as the settings stay the same
(a new size or MSAA count replaces it), and the last static scene, so a job's frames pay for
the device, pipelines and scene upload once. Frames do not depend on what the worker rendered
before (checked by the tests: any order, any worker gives the same bytes).
"""

from __future__ import annotations

import os
import tempfile
import time
from typing import Any, Dict, Optional, Tuple

import weft
from weft.batch.manifest import where
from weft.batch.render_jobs import RenderJob, camera_at


def _run_script(job: RenderJob, frame: int) -> Tuple[Any, Any]:
    namespace: Dict[str, Any] = {"__name__": f"weft_batch_scene_{job.name}"}
    exec(compile(job.source, job.scene, "exec"), namespace)  # the user's own scene script
    build = namespace.get("build")
    if not callable(build):
        raise weft.InvalidArgument(f"{job.scene}: a scene script must define "
                                   "build(frame, params) -> (weft.Scene, weft.Camera)")
    out = build(frame, dict(job.params))
    if not (isinstance(out, tuple) and len(out) == 2 and isinstance(out[0], weft.Scene)):
        raise weft.InvalidArgument(f"{job.scene}: build() must return (weft.Scene, "
                                   f"weft.Camera), got {type(out).__name__}")
    return out


def build_scene(job: RenderJob, frame: int) -> Tuple[Any, Any]:
    """(scene, camera) of ``frame``: the camera path's camera, else the scene's."""
    if job.scene == "default":
        scene, camera = weft.default_scene()
    elif job.scene == "cloth":
        from weft import scenes

        s = job.scene_settings()
        scene, camera, _ = scenes.cloth_scene(
            steps=int(s["steps"]) + frame * int(s["steps_per_frame"]))
    else:
        scene, camera = _run_script(job, frame)
    path_camera = camera_at(job.camera, frame, job.frames)
    return scene, path_camera if path_camera is not None else camera


def _static(job: RenderJob) -> bool:
    """Whether every frame of the job shows the same scene (then it is built once)."""
    return job.scene == "default" or (job.scene == "cloth" and
                                      int(job.scene_settings()["steps_per_frame"]) == 0)


class FrameRenderer:
    """``render((job, frame))`` -> {"png": bytes, timings, device, worker}."""

    def __init__(self) -> None:
        self.renderer: Optional[Any] = None
        self.settings: Optional[Tuple[Any, ...]] = None
        self.scene_key: Optional[Tuple[Any, ...]] = None
        self.scene: Any = None
        self.frames = 0

    def _renderer(self, job: RenderJob) -> Any:
        s = job.renderer_settings()
        key = tuple(sorted(s.items()))
        if self.renderer is None or key != self.settings:
            self.renderer = None  # free the old device objects before making new ones
            self.renderer = weft.Renderer(
                int(s["width"]), int(s["height"]), shadow_map_size=int(s["shadow_map_size"]),
                msaa=int(s["msaa"]), exposure=float(s["exposure"]), tone_map=str(s["tone_map"]),
                bounce=bool(s["bounce"]), ambient_occlusion=int(s["ao"]))
            self.settings = key
        return self.renderer

    def render(self, task: Tuple[RenderJob, int]) -> Dict[str, Any]:
        job, frame = task
        t0 = time.perf_counter()
        weft.clear_validation_messages()
        renderer = self._renderer(job)
        t1 = time.perf_counter()
        key = (job.name, repr(job.spec())) if _static(job) else None
        if key is not None and key == self.scene_key:
            scene, camera = self.scene
            moved = camera_at(job.camera, frame, job.frames)
            camera = camera if moved is None else moved
        else:
            scene, camera = build_scene(job, frame)
            self.scene, self.scene_key = ((scene, camera), key) if key else (None, None)
        t2 = time.perf_counter()
        image = renderer.render(scene, camera)
        t3 = time.perf_counter()
        fd, tmp = tempfile.mkstemp(suffix=".png")
        os.close(fd)
        try:
            weft.save_png(tmp, image)
            with open(tmp, "rb") as f:
                png = f.read()
        finally:
            os.unlink(tmp)
        self.frames += 1
        stats = renderer.stats
        return dict(png=png, device=renderer.device_name, worker=where(),
                    worker_frames=self.frames,
                    validation_messages=list(weft.validation_messages()),
                    timings=dict(setup_s=t1 - t0, scene_s=t2 - t1, render_s=t3 - t2,
                                 encode_s=time.perf_counter() - t3,
                                 gpu_ms=stats.get("gpu_ms"), cpu_ms=stats.get("cpu_ms")))
