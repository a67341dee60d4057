"""``python -m weft btf synth/fit`` and ``python -m weft.bench btf --quick``."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import weft
from weft import btf

TIMEOUT_S = 300


def run(*args: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, WEFT_VALIDATION="1")
    return subprocess.run([sys.executable, *args], capture_output=True, text=True,
                          timeout=TIMEOUT_S, env=env)


def test_synth_then_fit_writes_maps_metrics_and_report(tmp_path: Path) -> None:
    data = tmp_path / "cord"
    proc = run("-m", "weft", "btf", "synth", "corduroy", str(data), "--size", "24",
               "--noise", "0.002")
    assert proc.returncode == 0, proc.stderr
    assert (data / "truth" / "material.json").is_file()
    out = tmp_path / "fit"
    proc = run("-m", "weft", "btf", "fit", str(data), "--out", str(out), "--robust",
               "--lafortune", "2")
    assert proc.returncode == 0, proc.stderr
    assert "Blinn-Phong" in proc.stderr  # progress on stderr
    metrics = json.loads((out / "metrics.json").read_text())
    models = metrics["models"]
    assert set(models) == {"linear", "specular_eq4.29", "specular_eq4.30", "blinn_phong",
                           "lafortune_2"}
    assert (out / "maps" / "lafortune_2" / "lobe1_shape.exr").is_file()
    # scored as drawn (8-bit maps): eq. 4.30 reproduces the θ_l = 0 group up to quantisation
    assert models["specular_eq4.30"]["deviation"]["groups"]["0"] < 1e-4
    assert models["blinn_phong"]["deviation"]["total"] < models["linear"]["deviation"]["total"]
    assert len(models["linear"]["sample_deviation"]) == 81
    assert metrics["truth"]["linear"]["mean_deg"] < 5.0
    report = (out / "report.md").read_text()
    assert "tables 4.1-4.3" in report and "figures/histogram.png" in report
    for f in metrics["figures"]["linear"]["polar"] + metrics["figures"]["linear"]["difference"]:
        assert weft.load_png(str(out / "figures" / f)).shape[2] == 3
    back = btf.BtfMaterial.load(str(out / "maps" / "blinn_phong"))
    assert back.shape == (24, 24) and back.exponent_map is not None


def test_synth_zip_and_errors(tmp_path: Path) -> None:
    path = tmp_path / "wool.zip"
    proc = run("-m", "weft", "btf", "synth", "wool", str(path), "--size", "8", "--zip",
               "--format", "png", "--views", "2")
    assert proc.returncode == 0, proc.stderr
    assert btf.load(str(path), views="all").count == 162
    assert (tmp_path / "wool.zip.truth" / "material.json").is_file()
    proc = run("-m", "weft", "btf", "fit", str(tmp_path / "missing"), "--out",
               str(tmp_path / "o"))
    assert proc.returncode == 1 and "neither a folder nor a zip" in proc.stderr
    proc = run("-m", "weft", "btf", "synth", "velvet", str(tmp_path / "v"))
    assert proc.returncode == 2 and "invalid choice" in proc.stderr


def test_bench_btf_quick(tmp_path: Path) -> None:
    out = tmp_path / "bench"
    proc = run("-m", "weft.bench", "btf", "--quick", "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    data = json.loads((out / "bench.json").read_text())
    assert data["benchmark"] == "btf" and "--quick" in data["command"]
    assert data["targets"]["evaluated"] is False
    assert [r["preset"] for r in data["results"]] == ["wool", "corduroy"]
    for r in data["results"]:
        assert r["linear_ms"] > 0 and r["blinn_phong_texels_per_s"] > 0
        assert r["dev_blinn_phong"] < r["dev_spec_eq430"] <= r["dev_linear"]
        assert 0 <= r["normal_mean_linear"] < 5
    assert data["summary"]["max_normal_difference_deg"] < 0.01
    assert "bandwidth bound" in (out / "bench.md").read_text()
