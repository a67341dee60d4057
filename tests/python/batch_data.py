"""Small inputs shared by the batch tests: synthetic BTF datasets and render job files."""

from __future__ import annotations

import json
import os
from typing import Dict, List

import numpy as np
import weft.btf.synth as synth

SCENE_SCRIPT = '''import weft

def build(frame, params):
    scene, camera = weft.default_scene()
    scene.background = (0.1 * frame, 0.3, params["blue"])
    return scene, camera
'''


def write_datasets(root: str, count: int = 4, size: int = 16) -> List[str]:
    """``count`` synthetic datasets (random materials, one as a zip) with their truths."""
    paths = []
    for i in range(count):
        samples, truth = synth.synthesize_random(i, size, noise=0.002)
        zipped = i == count - 1
        path = os.path.join(root, f"m{i}.zip" if zipped else f"m{i}")
        truth_dir = path + ".truth" if zipped else os.path.join(path, "truth")
        if not zipped:
            os.makedirs(path, exist_ok=True)
        synth.write(path, samples, fmt="png", zip=zipped)
        truth.material.save(truth_dir)
        np.save(os.path.join(truth_dir, "height.npy"), truth.height)
        paths.append(path)
    return paths


def write_render_jobs(root: str, frames: int = 8) -> str:
    """A job file: an orbit of the default scene (``frames`` frames) and a scripted scene."""
    with open(os.path.join(root, "scene.py"), "w", encoding="utf-8") as f:
        f.write(SCENE_SCRIPT)
    jobs: Dict[str, object] = {"jobs": [
        {"name": "orbit", "scene": "default", "frames": frames,
         "camera": {"orbit": {"target": [0, 0.4, 0], "radius": 4.0, "height": 1.5}},
         "settings": {"width": 48, "height": 36, "msaa": 1, "ao": 0, "shadow_map_size": 512}},
        {"name": "script", "scene": "scene.py", "frames": 2, "params": {"blue": 0.9},
         "settings": {"width": 48, "height": 36, "msaa": 1, "ao": 0, "shadow_map_size": 512}},
    ]}
    path = os.path.join(root, "jobs.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(jobs, f)
    return path


def tree(root: str, skip: tuple = ("manifest.json",)) -> Dict[str, bytes]:
    """Every file under ``root`` (relative path -> bytes), the manifests left out."""
    out = {}
    for d, _, names in os.walk(root):
        for n in names:
            if n in skip:
                continue
            full = os.path.join(d, n)
            with open(full, "rb") as f:
                out[os.path.relpath(full, root)] = f.read()
    return out
