"""``python -m weft.bench scene --quick``: the demo scene's per-pass frame times and error."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.slow  # a benchmark run (pyproject.toml: markers)


def test_bench_scene_quick(tmp_path: Path) -> None:
    out = tmp_path / "scene"
    proc = subprocess.run([sys.executable, "-m", "weft.bench", "scene", "--quick", "--msaa", "1",
                           "--out", str(out), "--no-progress"], capture_output=True, text=True,
                          timeout=300, env=dict(os.environ, WEFT_VALIDATION="1"))
    assert proc.returncode == 0, proc.stderr
    data = json.loads((out / "bench.json").read_text())
    assert data["benchmark"] == "scene" and len(data["results"]) == 2
    few, many = data["results"]
    assert many["lights"] == few["lights"] + 4
    assert data["command"].endswith("--msaa 1")
    for r in data["results"]:
        assert r["msaa"] == 1 and r["sim_ms"] > 0 and r["render_ms"] > 0
        # the cloth moves every frame, so its shadow is drawn every frame; hair is in the scene
        assert {"shadow", "forward", "hair DOM", "hair OIT", "output"} <= set(r["pass_ms"]), \
            r["pass_ms"]
        assert r["shadow_mismatch"] is not None and r["shadow_mismatch"] < 0.01
    assert "shadow error" in (out / "bench.md").read_text()


def test_bench_scene_refuses_an_msaa_count_the_renderer_has_not(tmp_path: Path) -> None:
    proc = subprocess.run([sys.executable, "-m", "weft.bench", "scene", "--quick", "--msaa", "3",
                           "--out", str(tmp_path), "--no-progress"], capture_output=True,
                          text=True, timeout=60)
    assert proc.returncode == 2 and "--msaa must be 1, 2, 4 or 8" in proc.stderr
