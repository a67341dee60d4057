"""``python -m weft.bench ibl --quick``: the IBL benchmark's report (time against error)."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

pytestmark = pytest.mark.slow  # a benchmark run (pyproject.toml: markers)


def test_bench_ibl_quick(tmp_path: Path) -> None:
    out = tmp_path / "bench"
    env = dict(os.environ, WEFT_VALIDATION="1")
    proc = subprocess.run([sys.executable, "-m", "weft.bench", "ibl", "--quick", "--no-progress",
                           "--out", str(out)], capture_output=True, text=True, timeout=300, env=env)
    assert proc.returncode == 0, f"--- stdout\n{proc.stdout}\n--- stderr\n{proc.stderr}"
    data = json.loads((out / "bench.json").read_text())
    assert data["benchmark"] == "ibl" and "--quick" in data["command"]
    for key in ("conversion", "irradiance", "glossy", "lights", "dome", "machine", "summary"):
        assert key in data, key
    rows = data["irradiance"]["rows"]
    assert {r["method"] for r in rows} >= {"SH9 (project + evaluate)", "seed box blur (sphere map)",
                                           "seed 3-axis rotational blur", "exact (source 32^2)",
                                           "exact (compute, source 32^2)"}
    for cpu, gpu in zip([r for r in rows if r["method"] == "exact (source 32^2)"],
                        [r for r in rows if r["method"] == "exact (compute, source 32^2)"]):
        assert (gpu["env"], gpu["cube"]) == (cpu["env"], cpu["cube"])
        assert abs(gpu["mean_err"] - cpu["mean_err"]) < 1e-4  # the same sum, float rounding apart
    for x in data["irradiance"]["exact_compute"]:
        assert x["cpu_ms"] > 0 and x["compute_ms"] > 0 and x["max_diff"] < 1e-4, x
    assert set(data["summary"]["irradiance_exact_ms"]) == {"sky", "sun + sky"}
    for r in rows + data["glossy"]["phong"] + data["conversion"]:
        assert r["ms"] > 0 and math.isfinite(r["mean_err"])
    sky_sh = next(r for r in rows if r["env"] == "sky" and r["method"].startswith("SH9"))
    assert sky_sh["mean_err"] < 0.03
    for r in data["glossy"]["ggx_chain"]:
        assert r["cpu_s"] > 0 and 0 < r["gpu_dispatch_s"] <= r["gpu_total_s"]
        # the compute chain is the CPU algorithm: the same error against the reference
        np.testing.assert_allclose(r["gpu_level_mean_err_32"], r["level_mean_err_32"], rtol=1e-3,
                                   atol=1e-6)
    threshold = data["lights"][0]
    assert threshold["dir_err_deg"] < 2.0 and threshold["power_err"] < 0.05
    dome = data["dome"]
    assert dome[0]["err"] > dome[-1]["err"]
    frames = data["frames"]
    assert [(x["size"], x["lights"]) for x in frames] == [("64x48", 0), ("64x48", 16)]
    assert all(x["reused_ms"] > 0 and x["rerendered_ms"] > 0 for x in frames)
    assert "64x48, 16 lights" in data["summary"]["shadow_light_frame_times"]
    seed = data["seed_options"]
    assert [x["blur"] for x in seed["dome_blur"]] == [0.0, 2.0, 4.0, 8.0]
    assert all(x["ms"] > 0 and 0.0 <= x["mean_err"] < 0.5 for x in seed["dome_blur"])
    sphere = seed["lookups"][1]
    assert sphere["lookup"] == "sphere_map" and 0.0 < sphere["mean_diff"] < 0.05
    assert seed["phantom_ms"] > 0
    md = (out / "bench.md").read_text()
    assert "## Irradiance" in md and "## Shadow-light dome" in md and "## Frames" in md
    assert "## Seed options" in md
