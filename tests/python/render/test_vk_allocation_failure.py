"""A Vulkan device-memory allocation that fails (issue 13) becomes a clear weft.Error, and the
renderer works again afterwards. WEFT_VK_FAIL_ALLOCATION=N (test hook in vk/Allocator.cpp)
fails the N-th allocation of the process once: a small Renderer takes two 64 MiB blocks, so
N = 1 and 2 fail its first and its second block."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import pytest

SCRIPT = textwrap.dedent("""
    import numpy as np, weft
    scene, camera = weft.default_scene()
    failures = 0
    for attempt in range(4):
        try:
            r = weft.Renderer(32, 24, shadow_map_size=128, msaa=1)
            image = r.render(scene, camera)
            break
        except weft.Error as e:
            assert "out of GPU memory" in str(e), e
            failures += 1
    print("failures", failures)
    image = np.asarray(image)
    print("rendered", image.shape, int(image[..., :3].max()) > 0)
    again = weft.Renderer(32, 24, shadow_map_size=128, msaa=1).render(scene, camera)
    print("same", np.array_equal(np.asarray(again), image))
    if weft.validation_enabled():
        print("validation", len(weft.validation_messages()))
""")


@pytest.mark.parametrize("n", [1, 2])
def test_a_failed_allocation_is_an_error_and_rendering_recovers(n):
    env = dict(os.environ, WEFT_VK_FAIL_ALLOCATION=str(n))
    proc = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True,
                          timeout=300, env=env)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, out[-3000:]
    assert "failures 1" in out, out[-3000:]
    assert "rendered (24, 32, 4) True" in out and "same True" in out, out[-3000:]
    if "validation" in out:
        assert "validation 0" in out, out[-3000:]
