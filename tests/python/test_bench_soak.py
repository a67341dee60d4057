"""Soak (issue 13): python -m weft.bench soak renders many frames and measures whether memory
stays flat. Here a short run: device memory exactly flat, the cloth finite, validation silent,
and resident memory flat for the seed's static scene (the control that shows the measurement
can pass), and for the demo scene with the fur drawn opaque. With transparent fur (order-
independent transparency) the demo scene's resident memory grows ~0.3 MiB per frame (found by
this soak; BENCHMARKS.md "reliability"): that check is an expected failure until it is fixed."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from weft.bench import soak


@pytest.fixture(scope="module")
def demo():
    return soak.soak(120, (32, 24), samples=12, warmup=0.25)


def test_demo_soak_keeps_device_memory_flat_and_cloth_finite(demo):
    assert demo["rows"][-1]["frame"] == 120 and len(demo["rows"]) == 12
    assert demo["rows"][0]["device_reserved_mib"] > 0  # the measurement sees the allocator
    assert abs(demo["device_growth_mib"]) < 1e-6  # exactly flat but for float round-off
    assert demo["cloth_finite"]
    assert not demo["validation_messages"]
    assert all(r["frame_ms"] > 0 for r in demo["rows"])


@pytest.mark.xfail(strict=True, reason="host memory grows ~0.3 MiB/frame with transparent "
                                       "fur (renderer OIT path; BENCHMARKS.md reliability)")
def test_demo_soak_keeps_resident_memory_flat(demo):
    assert demo["rss_growth_mib"] < 8.0, soak.verdict(demo, 8.0)


def test_static_scene_soak_is_flat(tmp_path: Path):
    proc = subprocess.run([sys.executable, "-m", "weft.bench", "soak", "--frames", "150",
                           "--samples", "10", "--size", "32", "24", "--scene", "default",
                           "--out", str(tmp_path)], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    report = json.loads((tmp_path / "bench.json").read_text())
    assert report["problems"] == [] and report["rss_growth_mib"] < 8.0
    assert "verdict: flat" in (tmp_path / "bench.md").read_text()


def test_demo_soak_with_opaque_fur_is_flat():
    result = soak.soak(120, (32, 24), samples=12, warmup=0.25, hair_transparency=False)
    assert soak.verdict(result, 8.0) == [] and result["rss_growth_mib"] < 8.0
