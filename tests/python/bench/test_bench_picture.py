"""``python -m weft.bench picture --quick``: weft's frames against Mitsuba, time and error."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.slow  # a benchmark run (pyproject.toml: markers)

pytest.importorskip("mitsuba", reason="mitsuba (PyPI) is not installed: no path-traced reference")
pytest.importorskip("flip_evaluator", reason="flip-evaluator (PyPI) is not installed")


def test_bench_picture_quick(tmp_path: Path) -> None:
    out = tmp_path / "picture"
    proc = subprocess.run([sys.executable, "-m", "weft.bench", "picture", "--quick",
                           "--no-progress", "--out", str(out), "--scenes", "spheres_sun",
                           "cloth"], capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, WEFT_VALIDATION="1"))
    assert proc.returncode == 0, f"--- stdout\n{proc.stdout}\n--- stderr\n{proc.stderr}"
    data = json.loads((out / "bench.json").read_text())
    assert data["benchmark"] == "picture" and "--quick" in data["command"]
    assert [s["scene"] for s in data["scenes"]] == ["spheres_sun", "cloth"]
    for s in data["scenes"]:
        assert (out / f"{s['scene']}.png").stat().st_size > 1000
        assert 0.0 < s["noise_floor"]["covered"] < 0.2
        for r in s["rows"]:
            assert r["frame_ms"] > 0
            for region in ("whole", "covered", "objects", "edges", "unlit"):
                g = r["regions"][region]
                assert 0.0 < g["flip"] < 1.0 and math.isfinite(g["rel"]), (region, g)
    aa = data["aa"]
    assert aa["mesh_edges"] > aa["interior"] and aa["hair_edges"] > 0
    assert (out / "error_vs_time.png").exists()
    md = (out / "bench.md").read_text()
    assert "noise floor" in md and "## Anti-aliasing" in md
