"""weft-demo's Dear ImGui panel: drawn over the window (and only there) by a pass after the tone
mapping, leaving the rest of the picture as it was; a --script "set" line changes the same state
the panel's widgets edit, in the window and headless alike."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import List

import numpy as np
import pytest
import weft
from test_demo_window import psnr, run_demo_process, window_env

EXE = os.environ.get("WEFT_DEMO_EXE")
pytestmark = pytest.mark.skipif(not EXE or not Path(EXE).exists(),
                                reason="WEFT_DEMO_EXE (source scripts/env.sh) not built")

W, H = 320, 240
# The panel's first placement: 330 pixels wide from x = 8 (cut by a 320-pixel window), from the
# top to 8 pixels above the bottom.
PANEL = (slice(8, H - 8), slice(8, W))
SCRIPT = "1 set exposure 1.5\n1 set tone-map aces\n2 set bounce off\n"


def window(tmp_path: Path, name: str, env: dict, script: str, extra: List[str]) -> tuple:
    path = tmp_path / f"{name}.txt"
    path.write_text(script)
    shot, stats = tmp_path / f"{name}.png", tmp_path / f"{name}.json"
    proc = run_demo_process(["--width", str(W), "--height", str(H), "--frames", "4", "--msaa", "1",
                             "--no-hot-reload", "--script", str(path), "--screenshot", str(shot),
                             "--stats", str(stats)] + extra, env)
    names = [p["name"] for p in json.loads(stats.read_text())["passes"]]
    return weft.load_png(str(shot))[..., :3], names, proc


def test_panel_draws_over_the_window_only(xvfb_display: str, tmp_path: Path) -> None:
    env = window_env(xvfb_display)
    panel, panel_passes, proc = window(tmp_path, "panel", env, SCRIPT, [])
    plain, plain_passes, _ = window(tmp_path, "plain", env, SCRIPT, ["--no-panel"])
    # the script's settings went through the settings the panel edits
    assert "frame 1: exposure +1.5 EV" in proc.stdout and "frame 2: bounce light off" in proc.stdout
    # its own pass, after the tone mapping, and only with a panel
    assert "panel" in panel_passes and "panel" not in plain_passes, (panel_passes, plain_passes)
    assert panel_passes.index("panel") == panel_passes.index("output") + 1, panel_passes
    # the panel covers its region and nothing else
    differs = np.abs(panel.astype(int) - plain.astype(int)).max(axis=2) > 8
    assert differs[PANEL].mean() > 0.5, (
        f"the panel changed only {differs[PANEL].mean():.0%} of its region")
    outside = np.ones(differs.shape, bool)
    outside[PANEL] = False
    assert differs[outside].mean() < 0.01, "pixels outside the panel changed"
    # a panel switched off by the script leaves the picture a --no-panel run shows
    hidden, hidden_passes, _ = window(tmp_path, "hidden", env, SCRIPT + "2 set panel off\n", [])
    assert "panel" not in hidden_passes
    assert psnr(hidden, plain) >= 40.0, f"{psnr(hidden, plain):.1f} dB"


def test_script_settings_equal_the_options(tmp_path: Path) -> None:
    """Headless, "set" lines at frame 0 give the picture the equivalent options give."""
    env = dict(os.environ, WEFT_VALIDATION="1")
    script = tmp_path / "set.txt"
    script.write_text("0 set exposure -1\n0 set tone-map agx\n0 set ao 0\n0 set bounce off\n")
    size = ["--headless", "--width", "96", "--height", "64", "--frames", "2", "--msaa", "1",
            "--no-hot-reload", "--quiet"]
    scripted, options, plain = tmp_path / "s.png", tmp_path / "o.png", tmp_path / "p.png"
    run_demo_process(size + ["--script", str(script), "--out", str(scripted)], env)
    run_demo_process(size + ["--exposure", "-1", "--tone-map", "agx", "--ao", "0", "--no-bounce",
                             "--out", str(options)], env)
    run_demo_process(size + ["--out", str(plain)], env)
    a, b, c = (weft.load_png(str(p))[..., :3] for p in (scripted, options, plain))
    assert psnr(a, b) >= 40.0, f"script vs options: {psnr(a, b):.1f} dB"
    assert psnr(a, c) < 30.0, "the settings did not change the picture"
