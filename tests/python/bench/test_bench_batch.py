"""``python -m weft.bench batch --quick``: serial against Ray with 1 and 2 workers."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.slow  # a benchmark run (pyproject.toml: markers)

pytest.importorskip("ray")


def test_bench_batch_quick(tmp_path: Path) -> None:
    out = tmp_path / "bench"
    env = dict(os.environ, WEFT_VALIDATION="1", RAY_USAGE_STATS_ENABLED="0")
    proc = subprocess.run([sys.executable, "-m", "weft.bench", "batch", "--quick", "--datasets",
                           "2", "--size", "12", "--tiles", "2", "--frames", "4", "--frame-size",
                           "32", "24", "--out", str(out)], capture_output=True, text=True,
                          timeout=240, env=env)
    assert proc.returncode == 0, f"--- stdout\n{proc.stdout}\n--- stderr\n{proc.stderr}"
    data = json.loads((out / "bench.json").read_text())
    assert data["benchmark"] == "batch" and "--quick" in data["command"]
    rows = {(r["kind"], r["config"]): r for r in data["results"]}
    assert set(rows) == {(k, c) for k in ("btf", "render") for c in ("serial", "ray 1", "ray 2")}
    for r in rows.values():
        assert r["error"] == 0 and r["failed"] == 0 and r["throughput"] > 0
    assert (rows[("btf", "serial")]["amount"] == 2 * 12 * 12
            and rows[("render", "ray 2")]["amount"] == 4)
    for kind in ("btf", "render"):
        assert rows[(kind, "ray 2")]["scaling_efficiency"] > 0
        assert all("overhead_per_task_s" in rows[(kind, c)] for c in ("serial", "ray 1"))
    assert "scaling 1->2" in (out / "bench.md").read_text()
