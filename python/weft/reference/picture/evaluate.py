"""One reference scene rendered by weft and by Mitsuba, and compared (what the test and the
benchmark share)."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Dict, Optional

import numpy as np

from weft.reference.picture import compare as cmp
from weft.reference.picture.mitsuba_export import render_mitsuba
from weft.reference.picture.scenes import ReferenceScene


@dataclass
class Evaluation:
    name: str
    weft_linear: np.ndarray
    reference: np.ndarray
    debug: Dict[str, np.ndarray]
    result: Dict[str, object]
    regions: Dict[str, np.ndarray]
    reference_seconds: float = 0.0
    info: Dict[str, object] = field(default_factory=dict)


def render_reference(ref: ReferenceScene, width: int, height: int, spp: int,
                     integrator: str = "path", seed: int = 0) -> np.ndarray:
    """The Mitsuba truth of a reference scene, linear RGB (H, W, 3)."""
    return render_mitsuba(ref.scene, ref.camera, width, height, spp, integrator, seed,
                          environment=ref.reference_environment, lights=ref.reference_lights)


def render_weft(ref: ReferenceScene, renderer) -> Dict[str, np.ndarray]:
    """weft's frame of a reference scene: ``render_debug``'s outputs (one surface per pixel:
    the region masks) with ``linear`` replaced by what ``render_linear`` returns at the
    renderer's settings (MSAA included), which is the picture a user sees and is scored."""
    renderer.render(ref.scene, ref.camera)  # warm-up: shadow maps, bakes
    debug = dict(renderer.render_debug(ref.scene, ref.camera))
    debug["linear"] = np.asarray(renderer.render_linear(ref.scene, ref.camera))
    return debug


def evaluate(ref: ReferenceScene, renderer, spp: int, reference: Optional[np.ndarray] = None,
             integrator: str = "path") -> Evaluation:
    """Renders ``ref`` with ``renderer`` (its size is the comparison's) and compares it with
    Mitsuba's path-traced frame (rendered here unless ``reference`` is given)."""
    w, h = int(renderer.width), int(renderer.height)
    seconds = 0.0
    if reference is None:
        start = time.perf_counter()
        reference = render_reference(ref, w, h, spp, integrator)
        seconds = time.perf_counter() - start
    debug = render_weft(ref, renderer)
    linear = np.asarray(debug["linear"], np.float64)[..., :3]
    regions = cmp.masks(debug, ref.ground, ref.key_light, ref.background_drawn)
    result = cmp.compare(linear, reference, regions, ref.exposure)
    return Evaluation(ref.name, linear, reference, debug, result, regions, seconds,
                      {"background_drawn": ref.background_drawn})


def noise_floor(ref: ReferenceScene, width: int, height: int, spp: int,
                reference: np.ndarray, regions: Dict[str, np.ndarray]) -> Dict[str, float]:
    """Mean FLIP per region between ``reference`` and a second Mitsuba frame of another seed:
    how much of a score is the reference's own noise."""
    other = render_reference(ref, width, height, spp, seed=1)
    r = cmp.compare(other, reference, regions, ref.exposure)["regions"]
    return {k: v["flip"] for k, v in r.items()}
