"""pytest configuration for weft's Python tests.

Validation layers are switched on (WEFT_VALIDATION=1) before weft is imported, and every test
fails if the Vulkan validation layers reported anything while it ran. The device is whatever
weft selects (lavapipe on CI, a GPU when present); WEFT_DEVICE overrides it.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import time

os.environ["WEFT_VALIDATION"] = "1"

from typing import Callable, Iterator  # noqa: E402

import numpy as np  # noqa: E402
import pytest  # noqa: E402
import weft  # noqa: E402


def pytest_report_header(config: pytest.Config) -> str:
    try:
        selected = [d for d in weft.devices() if d["selected"]]
        name = selected[0]["name"] if selected else "none selected"
    except Exception as exc:  # pragma: no cover - reported, the tests then fail on their own
        name = f"unavailable ({exc})"
    return f"weft {weft.__version__}: Vulkan device {name}, validation " \
           f"{'on' if weft.validation_enabled() else 'OFF'}"


@pytest.fixture(autouse=True)
def validation_clean(request: pytest.FixtureRequest) -> Iterator[None]:
    """Fails the test if the Vulkan validation layers reported any message during it."""
    weft.clear_validation_messages()
    yield
    messages = list(weft.validation_messages())
    weft.clear_validation_messages()
    if messages:
        text = "\n".join(f"  [{i}] {m}" for i, m in enumerate(messages))
        print(f"Vulkan validation messages during {request.node.nodeid}:\n{text}")
        pytest.fail(f"{len(messages)} Vulkan validation message(s) during the test:\n{text}",
                    pytrace=False)


@pytest.fixture
def renderer_small() -> "weft.Renderer":
    """A 96x72 renderer with a 512 shadow map (fast on lavapipe)."""
    return weft.Renderer(96, 72, shadow_map_size=512)


@pytest.fixture
def make_renderer() -> Callable[..., "weft.Renderer"]:
    """Factory: ``make_renderer(width, height, **settings)``. Without MSAA, bounce light and
    ambient occlusion unless asked for: the NumPy oracles evaluate one surface per pixel, as
    render_debug's outputs hold, lit by its own point's lights and ambient (the global terms
    have their own tests against analytic truths and the path tracer)."""
    def make(width: int = 128, height: int = 96, **settings: object) -> "weft.Renderer":
        settings.setdefault("msaa", 1)
        settings.setdefault("bounce", False)
        settings.setdefault("ambient_occlusion", 0)
        return weft.Renderer(width, height, **settings)

    return make


@pytest.fixture
def smooth_texture() -> Callable[..., np.ndarray]:
    """Factory for a smooth, seamless uint8 RGB(A) image (low-frequency sinusoids), so that
    texture filtering differences (bilinear weights, no mipmaps) barely matter."""
    def make(height: int = 64, width: int = 64, channels: int = 3,
             phase: float = 0.0) -> np.ndarray:
        y, x = np.mgrid[0:height, 0:width].astype(np.float64)
        a = 2.0 * np.pi * x / width
        b = 2.0 * np.pi * y / height
        chans = [0.55 + 0.35 * np.sin(a + phase) * np.cos(b),
                 0.5 + 0.3 * np.cos(a - b + 0.7 * phase),
                 0.45 + 0.35 * np.sin(b + 1.3 + phase),
                 0.8 + 0.2 * np.cos(a + b)]
        img = np.stack(chans[:max(channels, 1)], axis=-1)
        return np.clip(np.rint(img * 255.0), 0, 255).astype(np.uint8)

    return make


def _free_display(start: int = 90) -> int:
    for n in range(start, start + 200):
        if not os.path.exists(f"/tmp/.X{n}-lock") and not os.path.exists(f"/tmp/.X11-unix/X{n}"):
            return n
    raise RuntimeError("no free X display number")


@pytest.fixture(scope="module")
def xvfb_display() -> Iterator[str]:
    """Starts ``Xvfb :<n> -screen 0 1280x1024x24`` on a free display; yields ``":<n>"``."""
    xvfb = shutil.which("Xvfb")
    if xvfb is None:
        if os.environ.get("CI"):
            pytest.fail("Xvfb is not installed but CI is set: the window test must run")
        pytest.skip("Xvfb is not installed (apt-get install xvfb); window test skipped")
    proc = None
    display = -1
    last_error = ""
    start = 90
    for _attempt in range(5):
        display = _free_display(start)
        proc = subprocess.Popen([xvfb, f":{display}", "-screen", "0", "1280x1024x24",
                                 "-nolisten", "tcp"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        socket = f"/tmp/.X11-unix/X{display}"
        deadline = time.monotonic() + 20.0
        while time.monotonic() < deadline and proc.poll() is None and not os.path.exists(socket):
            time.sleep(0.05)
        if proc.poll() is None and os.path.exists(socket):
            break
        # lost a race for the display number or failed to start: clean up and try the next
        if proc.poll() is None:
            proc.terminate()
        try:
            _, err = proc.communicate(timeout=5)
        except subprocess.TimeoutExpired:
            proc.kill()
            _, err = proc.communicate()
        proc = None
        start = display + 1
        last_error = err.decode(errors="replace") if err else ""
    if proc is None:
        pytest.fail(f"could not start Xvfb: {last_error}")
    try:
        yield f":{display}"
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout=10)
        if proc.stderr is not None:
            proc.stderr.close()
