"""``python -m weft.bench btf --quick``: every model on every dataset, the targets table and the
error-against-time plot."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
import weft

pytestmark = pytest.mark.slow  # a benchmark run (pyproject.toml: markers)

MODELS = {"linear", "linear (robust)", "linear + specular eq4.30", "linear + specular eq4.29",
          "Blinn-Phong n_s=n", "Blinn-Phong n_s=(0,0,1)", "Blinn-Phong (chosen)",
          "Lafortune 1 lobe", "Lafortune 2 lobes"}


def test_bench_btf_quick(tmp_path: Path) -> None:
    out = tmp_path / "bench"
    env = dict(os.environ, WEFT_VALIDATION="1")
    proc = subprocess.run([sys.executable, "-m", "weft.bench", "btf", "--quick", "--out",
                           str(out)], capture_output=True, text=True, timeout=120, env=env)
    assert proc.returncode == 0, f"--- stdout\n{proc.stdout}\n--- stderr\n{proc.stderr}"
    data = json.loads((out / "bench.json").read_text())
    assert data["benchmark"] == "btf" and "--quick" in data["command"]
    assert data["seconds"] < 60
    rows = data["results"]
    assert len(data["cases"]) == 3
    for case in data["cases"]:
        models = {r["model"] for r in rows if r["case"] == case}
        assert MODELS <= models, case
        if weft.btf.have_ceres():
            assert any("Ceres" in m for m in models)
    assert any(r["shadows"] for r in rows) and any(r["source"] == "random" for r in rows)
    assert {r["format"] for r in rows} == {"png", "jpg"}
    for r in rows:
        assert r["seconds"] > 0 and r["texels_per_s"] > 0 and r["outside"] >= 0
        assert r["noise_floor"] > 0 and 0 <= r["normal_mean_deg"] < 90
        assert 0 <= r["normal_p95_deg"] <= 180
        assert (r["dev_drawn"] is None) == r["model"].startswith("Lafortune")
        if r["model"] == "Blinn-Phong (chosen)":
            pair = [x["dev_drawn"] for x in rows if x["case"] == r["case"]
                    and x["model"] in ("Blinn-Phong n_s=n", "Blinn-Phong n_s=(0,0,1)")]
            if "cast shadows" not in r["choice_rule"]:
                assert r["dev_drawn"] == min(pair)
    # the noise floor is the truth's own deviation: no fit of the noisy data is far below it
    for r in rows:
        if r["model"] == "linear":
            assert r["dev_fitted"] > 0.5 * r["noise_floor"]
    targets = data["targets"]
    assert targets["evaluated"] is False and len(targets["items"]) == 12
    speed = data["speed"]
    assert speed["read_pass_ms"] > 0 and speed["linear_ms"] > 0
    assert speed["blinn_phong_n_texels_per_s"] > 0
    assert speed["blinn_phong_flat_shadows_texels_per_s"] > 0
    assert speed["blinn_phong_flat_shadows_cpu_texels_per_s"] > 0
    markdown = (out / "bench.md").read_text()
    assert "## Targets (issue 12)" in markdown and "not judged" in markdown
    assert data["plot"] == "error_vs_time.png"
    img = weft.load_png(str(out / "error_vs_time.png"))
    assert img.shape[1] > 600 and img[..., :3].std() > 8
