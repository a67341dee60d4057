"""The cloth benchmark's equal-accuracy slack: the larger of 1% and weft's measured float32
trajectory spread at the peer's setting (python/weft/bench/cloth.py)."""

from __future__ import annotations

import pytest
from weft.bench import cloth as bench


def rows(spread: float):
    return [
        {"engine": "weft", "n": 64, "setting": "cheap", "mean_strain": 0.0100,
         "strain_spread": spread, "steps_per_s": 1000.0},
        {"engine": "weft", "n": 64, "setting": "dear", "mean_strain": 0.0050,
         "strain_spread": 0.0, "steps_per_s": 400.0},
        {"engine": "warp", "n": 64, "setting": "cheap", "mean_strain": 0.0097,
         "steps_per_s": 250.0},
    ]


def test_slack_is_the_measured_spread_when_larger() -> None:
    res = rows(0.04)  # rounding alone moves "cheap" by 4%: 3% below it is no accuracy gap
    assert bench.slack_for(res, 64, "cheap") == pytest.approx(0.04)
    point = bench.summarize(res, [64])["pareto_vs_peers"]["64"]["points"][0]
    assert point["weft_setting"] == "cheap" and point["ratio"] == pytest.approx(4.0)


def test_slack_floor_keeps_the_dearer_setting_when_spread_is_small() -> None:
    res = rows(1e-4)
    assert bench.slack_for(res, 64, "cheap") == bench.STRAIN_SLACK
    point = bench.summarize(res, [64])["pareto_vs_peers"]["64"]["points"][0]
    assert point["weft_setting"] == "dear" and point["ratio"] == pytest.approx(1.6)


def test_strain_spread_is_small_for_a_settled_setting() -> None:
    setting = bench.Setting("t", 2, 2, tethers=True)
    mean, _ = bench.strain_after(bench.WeftEngine(1), 12, setting)
    spread = bench.strain_spread(12, setting, mean, threads=1, runs=2)
    assert 0.0 <= spread < 0.01
