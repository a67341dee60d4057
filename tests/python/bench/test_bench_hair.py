"""``python -m weft.bench hair --quick``: the hair benchmark's report (time and error)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.slow  # a benchmark run (pyproject.toml: markers)


def test_bench_hair_quick(tmp_path: Path) -> None:
    out = tmp_path / "bench"
    env = dict(os.environ, WEFT_VALIDATION="1")
    proc = subprocess.run([sys.executable, "-m", "weft.bench", "hair", "--quick", "--out",
                           str(out)], capture_output=True, text=True, timeout=120, env=env)
    assert proc.returncode == 0, f"--- stdout\n{proc.stdout}\n--- stderr\n{proc.stderr}"
    data = json.loads((out / "bench.json").read_text())
    assert data["benchmark"] == "hair" and "--quick" in data["command"]
    parts = {r["part"] for r in data["results"]}
    for part in ("hair generator", ".hair save", ".hair load", "fur (CPU)",
                 "shading sadeghi (compute)", "DOM 3 layers (linear)", "WBOIT weight eq10"):
        assert part in parts, part
    for r in data["results"]:
        assert r["seconds"] > 0 and r["error"] is not None
        if r["part"].startswith((".hair", "hair generator")):
            assert r["error"] == 0
        if r["part"].startswith("shading"):
            assert r["error_p999"] < 1e-4
        if r["part"].startswith("DOM"):
            assert r["error"] < 0.05
    frames = [r for r in data["results"] if r["part"].startswith("frame")]
    assert {r["part"] for r in frames} == {"frame B", "frame B+S", "frame B+S+T"}
    for r in frames:
        assert r["error"] < 1e-2, r
    assert "Frame times" in (out / "bench.md").read_text()
