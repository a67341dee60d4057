"""Renderers on several threads at once (the GIL is released while rendering): the shared
Vulkan queue and upload pool are locked, each renderer records from its own command pool."""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import weft


def test_parallel_renderers_match_sequential_renders() -> None:
    scene, camera = weft.default_scene()
    sizes = [(64, 48), (80, 60), (96, 72), (72, 54)]
    expected = [weft.Renderer(w, h, shadow_map_size=512).render(scene, camera) for w, h in sizes]

    def work(index: int) -> list:
        w, h = sizes[index]
        renderer = weft.Renderer(w, h, shadow_map_size=512)
        return [renderer.render(scene, camera) for _ in range(3)]

    with ThreadPoolExecutor(max_workers=len(sizes)) as pool:
        results = list(pool.map(work, range(len(sizes))))
    for ref, frames in zip(expected, results):
        for frame in frames:
            assert frame.shape == ref.shape
            assert np.array_equal(frame, ref)
