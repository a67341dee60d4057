"""``python -m weft.bench cloth --quick``: the cloth benchmark's report (time against error)."""

from __future__ import annotations

import importlib.util
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest
from weft.bench import cloth as bench_cloth

pytestmark = pytest.mark.slow  # a benchmark run (pyproject.toml: markers)

TIMEOUT_S = 300


def test_bench_cloth_quick(tmp_path: Path) -> None:
    out = tmp_path / "bench"
    env = dict(os.environ, WEFT_VALIDATION="1")
    proc = subprocess.run([sys.executable, "-m", "weft.bench", "cloth", "--quick", "--no-warp",
                           "--out", str(out)], capture_output=True, text=True,
                          timeout=TIMEOUT_S, env=env)
    assert proc.returncode == 0, f"--- stdout\n{proc.stdout}\n--- stderr\n{proc.stderr}"
    assert "Traceback" not in proc.stderr
    assert "|" in proc.stdout  # the Markdown table
    data = json.loads((out / "bench.json").read_text())
    markdown = (out / "bench.md").read_text()
    for key in ("benchmark", "command", "machine", "scene", "settings", "reference", "results",
                "summary", "warp"):
        assert key in data, key
    assert data["benchmark"] == "cloth" and "--quick" in data["command"]
    assert data["sizes"] == list(bench_cloth.QUICK_SIZES)
    weft_rows = [r for r in data["results"] if r["engine"] == "weft"]
    numpy_rows = [r for r in data["results"] if r["engine"] == "numpy"]
    assert len(weft_rows) == len(numpy_rows) == len(data["sizes"]) * len(data["settings"])
    for r in weft_rows:
        assert r["steps_per_s"] > 0 and r["repeats"] >= 1
        assert 0.0 <= r["mean_strain"] <= r["max_strain"] and math.isfinite(r["max_strain"])
        assert 0.0 <= r["equilibrium_error"] < 1.0
    for r in numpy_rows:
        assert r["steps_per_s"] > 0
        # the same algorithm: the NumPy peer's strain equals weft's to float32 rounding
        mine = next(w for w in weft_rows if (w["n"], w["setting"]) == (r["n"], r["setting"]))
        assert r["strain_source"] == "numpy"
        assert abs(r["mean_strain"] - mine["mean_strain"]) <= 1e-4 + 1e-3 * mine["mean_strain"]
    by = {(r["n"], r["setting"]): r for r in weft_rows}
    for n in data["sizes"]:
        # accurate settings are more accurate than the seed (one iteration, one substep)
        assert by[(n, "tethers-it2-sub2")]["mean_strain"] < by[(n, "seed")]["mean_strain"]
        assert by[(n, "tethers-it2-sub2")]["equilibrium_error"] < \
            by[(n, "seed")]["equilibrium_error"]
        assert data["reference"]["check_error"][str(n)] < 1e-3
    ratios = data["summary"]["weft_vs_numpy_equal_settings"]
    assert set(ratios) == {str(n) for n in data["sizes"]}
    assert data["summary"]["target_128"]["evaluated"] is False
    assert "seed" in markdown and "weft/NumPy" in markdown
    if importlib.util.find_spec("matplotlib") is not None:
        assert data["plot"] and (out / "pareto.png").stat().st_size > 1000
    else:
        assert data["plot"] is None and "matplotlib" in data["plot_note"]


def test_pareto_front() -> None:
    pts = [(0.5, 100.0), (0.1, 50.0), (0.2, 40.0), (0.05, 10.0), (0.5, 200.0)]
    front = bench_cloth.pareto_front(pts)
    assert [pts[i] for i in front] == [(0.05, 10.0), (0.1, 50.0), (0.5, 200.0)]
