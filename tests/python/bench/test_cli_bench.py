"""Command lines: ``python -m weft`` and ``python -m weft.bench``."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path
from typing import List

import pytest

pytestmark = pytest.mark.slow  # a benchmark run (pyproject.toml: markers)

TIMEOUT_S = 300


def run(args: List[str], check: bool = True) -> subprocess.CompletedProcess:
    env = dict(os.environ, WEFT_VALIDATION="1")
    proc = subprocess.run([sys.executable, *args], capture_output=True, text=True,
                          timeout=TIMEOUT_S, env=env)
    if check:
        assert proc.returncode == 0, \
            f"{args} exited {proc.returncode}\n--- stdout\n{proc.stdout}\n--- stderr\n{proc.stderr}"
    for marker in ("VUID-", "Validation Error"):
        assert marker not in proc.stdout + proc.stderr, f"validation message:\n{proc.stderr}"
    return proc


def test_weft_help() -> None:
    proc = run(["-m", "weft", "--help"])
    for word in ("demo", "devices", "render"):
        assert word in proc.stdout
    for sub in ("demo", "devices", "render"):
        assert "usage" in run(["-m", "weft", sub, "--help"]).stdout


def test_weft_without_command_fails() -> None:
    proc = run(["-m", "weft"], check=False)
    assert proc.returncode != 0
    assert "usage" in proc.stderr


def test_devices_json() -> None:
    proc = run(["-m", "weft", "devices", "--json"])
    devices = json.loads(proc.stdout)
    assert isinstance(devices, list) and devices
    assert sum(1 for d in devices if d["selected"]) == 1
    table = run(["-m", "weft", "devices"]).stdout
    selected = next(d for d in devices if d["selected"])
    assert selected["name"] in table


def test_render_command(tmp_path: Path) -> None:
    out = tmp_path / "render.png"
    proc = run(["-m", "weft", "render", "--width", "64", "--height", "48", "--out", str(out)])
    assert out.is_file()
    assert str(out.name) in proc.stdout
    assert "forward" in proc.stdout  # the frame statistics list the passes


def test_bench_render_quick(tmp_path: Path) -> None:
    out = tmp_path / "bench"
    proc = run(["-m", "weft.bench", "render", "--quick", "--out", str(out)])
    assert "|" in proc.stdout  # the Markdown table
    data = json.loads((out / "bench.json").read_text())
    markdown = (out / "bench.md").read_text()
    for key in ("benchmark", "command", "device", "machine", "results", "frames"):
        assert key in data, key
    assert data["benchmark"] == "render"
    assert data["machine"]["cpu_count"] >= 1 and data["machine"]["platform"]
    assert data["device"] and data["device"] in markdown
    assert len(data["results"]) == 1
    r = data["results"][0]
    assert (r["width"], r["height"], r["shadow_map_size"], r["frames"]) == (160, 120, 512, 1)
    assert r["frame_cpu_ms"] > 0.0 and r["render_cpu_ms"] > 0.0
    for group in ("shadow", "forward", "output"):
        assert group in r["pass_gpu_ms"], r["pass_gpu_ms"]
        gpu = r["pass_gpu_ms"][group]
        assert gpu is None or gpu >= 0.0
    oracle = r["oracle"]
    assert oracle is not None, r.get("oracle_error")
    for key in ("max_abs", "mean_abs", "p99_abs", "max_u8", "u8_over_1", "shading_max_abs",
                "shadow_mismatch", "background_max_abs"):
        assert math.isfinite(oracle[key]), (key, oracle[key])
    # with T from the frame the oracle checks the shading equation alone: strict tolerances
    assert oracle["covered_pixels"] > 100
    assert oracle["shading_max_abs"] <= 1e-3, oracle
    assert oracle["shading_max_u8"] <= 1, oracle
    # textured pixels include the sampler's precision and the estimated mip LOD (approximate
    # along silhouettes at 160x120): sane bounds only
    assert oracle["mean_abs"] < 0.005, oracle
    assert oracle["p99_abs"] < 0.05, oracle
    assert oracle["max_abs"] < 0.25, oracle
    assert oracle["u8_over_1"] < 0.1, oracle
    assert oracle["shadow_mismatch"] < 0.01, oracle
    assert oracle["background_max_abs"] < 1e-5, oracle


def test_bench_help_lists_subsystems() -> None:
    proc = run(["-m", "weft.bench", "--help"])
    assert "render" in proc.stdout


@pytest.mark.parametrize("args", [["no-such-thing"], ["no-such-thing", "--quick"], []])
def test_bench_unknown_subsystem(args: List[str]) -> None:
    proc = run(["-m", "weft.bench", *args], check=False)
    assert proc.returncode != 0
    assert "render" in proc.stderr  # the message lists the known subsystems
    assert "Traceback" not in proc.stderr
