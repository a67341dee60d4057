"""Render jobs: a scene, a camera path and settings -> frames (``frame_NNNN.png``).

A job file is JSON, ``{"jobs": [JOB, ...]}`` (or a list of jobs), each::

    {"name": "orbit",                     # output folder out/orbit/
     "scene": "default",                  # default | cloth | a scene script (.py)
     "frames": 8,
     "camera": {"orbit": {"target": [0, 0.4, 0], "radius": 3, "height": 1.5,
                          "start_deg": 0, "turns": 1, "fov_y": 0.75}},
               # or {"keys": [{"position": [...], "target": [...], "fov_y": 0.75}, ...]}
               # (linear between keys spread evenly over the frames); none: the scene's camera
     "settings": {"width": 320, "height": 240, "msaa": 4, "exposure": 0, "tone_map": "clamp",
                  "ao": 8, "bounce": true, "shadow_map_size": 2048,
                  "steps": 180, "steps_per_frame": 0},     # cloth: simulation before frame k
                                                            # = steps + k * steps_per_frame
     "params": {...}}                     # handed to a scene script

A scene script defines ``build(frame, params)`` returning ``(weft.Scene, weft.Camera)``; its
source travels with the job (nodes need no copy of it). Every frame is a pure function of
(job, frame): that is what lets any worker render it, retry it, and match a serial run.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

import weft

BUILTIN_SCENES = ("default", "cloth")

#: Renderer settings a job may give, with the defaults of ``python -m weft render``.
RENDER_DEFAULTS: Dict[str, Any] = dict(width=320, height=240, msaa=4, exposure=0.0,
                                       tone_map="clamp", ao=8, bounce=True,
                                       shadow_map_size=2048)
#: Scene settings (cloth: simulation steps before frame 0 and per frame).
SCENE_DEFAULTS: Dict[str, Any] = dict(steps=180, steps_per_frame=0)


@dataclass
class RenderJob:
    name: str
    scene: str = "default"
    frames: int = 1
    camera: Optional[Dict[str, Any]] = None
    settings: Dict[str, Any] = field(default_factory=dict)
    params: Dict[str, Any] = field(default_factory=dict)
    source: str = ""  # a scene script's text (read by :func:`make_render_job`)

    def renderer_settings(self) -> Dict[str, Any]:
        return {k: self.settings.get(k, v) for k, v in RENDER_DEFAULTS.items()}

    def scene_settings(self) -> Dict[str, Any]:
        return {k: self.settings.get(k, v) for k, v in SCENE_DEFAULTS.items()}

    def spec(self) -> Dict[str, Any]:
        """Everything that decides the frames' bytes (for the manifest and resume keys)."""
        return dict(name=self.name, scene=self.scene, frames=self.frames, camera=self.camera,
                    settings={**self.renderer_settings(), **self.scene_settings()},
                    params=self.params, source=self.source)


def _vec3(value: Any, what: str) -> Tuple[float, float, float]:
    try:
        v = tuple(float(x) for x in value)
    except (TypeError, ValueError):
        raise weft.InvalidArgument(f"{what} must be three numbers, got {value!r}") from None
    if len(v) != 3 or not all(math.isfinite(x) for x in v):
        raise weft.InvalidArgument(f"{what} must be three finite numbers, got {value!r}")
    return v  # type: ignore[return-value]


def _number(spec: Dict[str, Any], key: str, default: float, what: str) -> float:
    v = spec.get(key, default)
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise weft.InvalidArgument(f"{what}.{key} must be a finite number, got {v!r}")
    return float(v)


def camera_at(camera: Optional[Dict[str, Any]], frame: int, frames: int) -> Optional[Any]:
    """The camera of ``frame`` on a path (None: the scene's own camera)."""
    if camera is None:
        return None
    if "orbit" in camera:
        o = camera["orbit"]
        target = _vec3(o.get("target", (0.0, 0.0, 0.0)), "camera.orbit.target")
        radius = _number(o, "radius", 3.0, "camera.orbit")
        height = _number(o, "height", 1.0, "camera.orbit")
        turns = _number(o, "turns", 1.0, "camera.orbit")
        a = math.radians(_number(o, "start_deg", 0.0, "camera.orbit")) + \
            2.0 * math.pi * turns * frame / max(frames, 1)
        pos = (target[0] + radius * math.sin(a), target[1] + height,
               target[2] + radius * math.cos(a))
        return weft.Camera(position=pos, target=target,
                           fov_y=_number(o, "fov_y", 0.75, "camera.orbit"))
    if "keys" in camera:
        keys = camera["keys"]
        if not isinstance(keys, list) or not keys:
            raise weft.InvalidArgument("camera.keys must be a non-empty list")
        u = 0.0 if frames <= 1 or len(keys) == 1 else frame / (frames - 1) * (len(keys) - 1)
        i = min(int(u), len(keys) - 2) if len(keys) > 1 else 0
        t = u - i
        a, b = keys[i], keys[min(i + 1, len(keys) - 1)]

        def mix(key: str, default: Any) -> Tuple[float, ...]:
            x = _vec3(a.get(key, default), f"camera.keys[{i}].{key}")
            y = _vec3(b.get(key, default), f"camera.keys[{i + 1}].{key}")
            return tuple(p + (q - p) * t for p, q in zip(x, y))

        fov = _number(a, "fov_y", 0.75, "camera.keys") * (1 - t) + \
            _number(b, "fov_y", 0.75, "camera.keys") * t
        return weft.Camera(position=mix("position", (0, 1, 4)), target=mix("target", (0, 0, 0)),
                           fov_y=fov)
    raise weft.InvalidArgument(f"camera must hold 'orbit' or 'keys', got {sorted(camera)}")


def make_render_job(spec: Dict[str, Any], base: str = ".") -> RenderJob:
    """A checked job from its JSON form; a scene script is read relative to ``base``."""
    if not isinstance(spec, dict):
        raise weft.InvalidArgument(f"a render job must be an object, got {spec!r}")
    known = {"name", "scene", "frames", "camera", "settings", "params"}
    if set(spec) - known:
        raise weft.InvalidArgument(f"unknown render job keys {sorted(set(spec) - known)}")
    name = spec.get("name")
    if not isinstance(name, str) or not name or name.startswith((".", "/")) or ".." in name:
        raise weft.InvalidArgument(f"job name must be a relative folder name, got {name!r}")
    frames = spec.get("frames", 1)
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 1:
        raise weft.InvalidArgument(f"{name}: frames must be an integer >= 1, got {frames!r}")
    settings = dict(spec.get("settings") or {})
    unknown = set(settings) - set(RENDER_DEFAULTS) - set(SCENE_DEFAULTS)
    if unknown:
        raise weft.InvalidArgument(f"{name}: unknown settings {sorted(unknown)}; known: "
                                   f"{sorted({**RENDER_DEFAULTS, **SCENE_DEFAULTS})}")
    scene = spec.get("scene", "default")
    source = ""
    if scene not in BUILTIN_SCENES:
        if not isinstance(scene, str) or not scene.endswith(".py"):
            raise weft.InvalidArgument(f"{name}: scene must be one of {BUILTIN_SCENES} or a "
                                       f"scene script (.py), got {scene!r}")
        path = scene if os.path.isabs(scene) else os.path.join(base, scene)
        try:
            with open(path, encoding="utf-8") as f:
                source = f.read()
        except OSError as exc:
            raise weft.IoError(f"{name}: cannot read scene script {path}: {exc}") from None
    job = RenderJob(name, scene, frames, spec.get("camera"), settings,
                    dict(spec.get("params") or {}), source)
    camera_at(job.camera, 0, frames)  # a bad path fails here, before anything runs
    return job


def load_render_jobs(path: str) -> List[RenderJob]:
    """The jobs of a JSON job file (scene scripts relative to the file)."""
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except OSError as exc:
        raise weft.IoError(f"cannot read job file {path}: {exc}") from None
    except ValueError as exc:
        raise weft.IoError(f"{path}: not JSON ({exc})") from None
    specs = data.get("jobs") if isinstance(data, dict) else data
    if not isinstance(specs, list) or not specs:
        raise weft.InvalidArgument(f"{path}: expected {{\"jobs\": [...]}} with at least one job")
    jobs = [make_render_job(s, os.path.dirname(os.path.abspath(path))) for s in specs]
    names = [j.name for j in jobs]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise weft.InvalidArgument(f"{path}: job names must be unique, repeated: {dup}")
    return jobs


def frame_tasks(jobs: Sequence[RenderJob]) -> List[Tuple[RenderJob, int]]:
    return [(job, k) for job in jobs for k in range(job.frames)]
