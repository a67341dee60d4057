"""``python -m weft btf synth/fit``: every model in the report, the best one chosen by deviation
as drawn, figures that show something."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import weft
from weft import btf

pytestmark = pytest.mark.slow  # the BTF CLI over every model (~35 s)

TIMEOUT_S = 300
MODELS = {"linear", "linear_robust", "specular_eq4.29", "specular_eq4.30", "blinn_phong_n",
          "blinn_phong_flat", "lafortune_1", "lafortune_2"}


def run(*args: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, WEFT_VALIDATION="1")
    return subprocess.run([sys.executable, *args], capture_output=True, text=True,
                          timeout=TIMEOUT_S, env=env)


@pytest.fixture(scope="module")
def fitted(tmp_path_factory: pytest.TempPathFactory):
    tmp = tmp_path_factory.mktemp("btf_cli")
    data = tmp / "cord"
    proc = run("-m", "weft", "btf", "synth", "corduroy", str(data), "--size", "24",
               "--noise", "0.002")
    assert proc.returncode == 0, proc.stderr
    assert (data / "truth" / "material.json").is_file()
    out = tmp / "fit"
    proc = run("-m", "weft", "btf", "fit", str(data), "--out", str(out), "--robust",
               "--lafortune", "1", "2", "--progress")
    assert proc.returncode == 0, proc.stderr
    assert "Blinn-Phong" in proc.stderr  # progress on stderr, asked for (stderr is a pipe)
    return data, out, json.loads((out / "metrics.json").read_text())


def test_every_model_is_reported_and_scored_as_drawn(fitted) -> None:
    data, out, metrics = fitted
    models = metrics["models"]
    assert set(models) == MODELS
    for name, m in models.items():
        assert len(m["sample_deviation"]) == 81
        assert m["drawn"] == (not name.startswith("lafortune"))
    assert models["specular_eq4.30"]["fitted_deviation"]["groups"]["0"] < 1e-10
    # the robust linear fit is scored as the renderer draws it (clamped n.l, 8-bit maps), the
    # number a user gets from the saved maps, not the unclamped model's
    samples = btf.load(str(data))
    robust = btf.BtfMaterial.load(str(out / "maps" / "linear_robust"))
    drawn = btf.deviation(samples, btf.sample_errors(samples, robust, drawn=True))["total"]
    assert models["linear_robust"]["deviation"]["total"] == pytest.approx(drawn, rel=1e-6)
    back = btf.BtfMaterial.load(str(out / "maps" / "blinn_phong_flat"))
    assert back.shape == (24, 24) and back.flat_specular_normal
    assert (out / "maps" / "lafortune_2" / "lobe1_shape.exr").is_file()


def test_best_model_and_highlight_choice(fitted) -> None:
    _, out, metrics = fitted
    models = metrics["models"]
    drawable = {n: m["deviation"]["total"] for n, m in models.items() if m["drawn"]}
    assert metrics["best"] == min(drawable, key=drawable.get)
    assert next(iter(models)) == metrics["best"]  # the best model leads every table
    everything = {n: m["deviation"]["total"] for n, m in models.items()}
    assert metrics["most_accurate"] == min(everything, key=everything.get)
    choice = metrics["blinn_phong_choice"]
    pair = {k: models[k]["deviation"]["total"] for k in ("blinn_phong_n", "blinn_phong_flat")}
    assert choice["chosen"] == min(pair, key=pair.get)
    assert choice["deviation_n"] == pytest.approx(pair["blinn_phong_n"])
    report = (out / "report.md").read_text()
    assert f"**Best model: {metrics['best']}**" in report
    assert f"**{choice['chosen']}** is chosen" in report
    assert "tables 4.1-4.3" in report and "lafortune_2 (not drawn)" in report


def test_truth_table_covers_every_model(fitted) -> None:
    _, out, metrics = fitted
    truth = metrics["truth"]
    assert set(truth) - {"folder"} == MODELS
    for name, t in truth.items():
        if name == "folder":
            continue
        assert 0 <= t["mean_deg"] <= t["p95_deg"] < 30, (name, t)
        assert t["albedo_abs_error"] >= 0 and t["ambient_abs_error"] >= 0
    assert truth["linear"]["mean_deg"] < 5.0
    assert truth["blinn_phong_flat"]["exponent_median_rel_error"] is not None
    assert truth["lafortune_1"]["exponent_median_rel_error"] is None
    report = (out / "report.md").read_text()
    assert "## Against the ground truth" in report and "exponent rel. err" in report


def _busy(path: Path) -> np.ndarray:
    """The PNG's pixels, asserting it is not blank: several grey levels and some spread."""
    img = weft.load_png(str(path))[..., :3].astype(np.float64)
    assert img.std() > 8, path
    assert len(np.unique(img.reshape(-1, 3), axis=0)) > 50, path
    return img


def test_figures_are_drawn_with_content(fitted) -> None:
    _, out, metrics = fitted
    figures = metrics["figures"]
    assert set(figures["difference"]) == MODELS and set(figures["maps"]) == MODELS
    assert len(figures["polar"]) == 3
    for name in [*figures["difference"].values(), *figures["maps"].values(),
                 *figures["polar"], "histogram.png"]:
        img = _busy(out / "figures" / name)
        assert img.shape[0] > 150 and img.shape[1] > 300  # a figure with axes, not a thumbnail
    report = (out / "report.md").read_text()
    for name in figures["polar"]:
        assert f"figures/{name}" in report
    assert sum(c for _, _, c in metrics["histogram"]) == 81


def test_map_previews_are_not_black(fitted) -> None:
    _, out, metrics = fitted
    for model in ("blinn_phong_flat", "linear", "lafortune_1"):
        for name, how in metrics["previews"][model].items():
            img = weft.load_png(str(out / "maps" / model / f"{name}_preview.png"))
            # tone-mapped by a high percentile: most texels visible, not a few bright dots
            bright = img[..., :3].max(axis=-1)
            assert np.percentile(bright, 75) > 20 and np.mean(bright == 0) < 0.5, (model, name)
            assert how in (out / "report.md").read_text()


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


def test_synth_random_writes_its_truth(tmp_path: Path) -> None:
    out = tmp_path / "r"
    proc = run("-m", "weft", "btf", "synth", "random", str(out), "--size", "16", "--seed", "5",
               "--highlight", "flat", "--format", "png")
    assert proc.returncode == 0, proc.stderr
    truth = btf.BtfMaterial.load(str(out / "truth"))
    _, expected = btf.synth.synthesize_random(5, 16, flat_specular_normal=True)
    assert truth.flat_specular_normal and truth.exponent == pytest.approx(
        expected.material.exponent)
    np.testing.assert_allclose(truth.normal, expected.material.normal, atol=1e-6)
    assert btf.load(str(out)).count == 81


def test_pooled_exponent_model(tmp_path) -> None:
    """--pooled-exponent adds the chosen highlight with pooled exponents: nearer the truth's one
    exponent than the per-texel fit (random material, noise 0.004, 32 x 32)."""
    data = tmp_path / "rand"
    proc = run("-m", "weft", "btf", "synth", "random", str(data), "--seed", "31", "--size", "32",
               "--format", "png")
    assert proc.returncode == 0, proc.stderr
    out = tmp_path / "fit"
    proc = run("-m", "weft", "btf", "fit", str(data), "--out", str(out), "--lafortune", "0",
               "--no-figures", "--pooled-exponent")
    assert proc.returncode == 0, proc.stderr
    metrics = json.loads((out / "metrics.json").read_text())
    pooled = metrics["models"]["blinn_phong_pooled"]
    assert pooled["highlight"] == metrics["blinn_phong_choice"]["chosen"]
    assert pooled["outside_physical_space"]["texels"] == 0
    truth = metrics["truth"]
    chosen = metrics["blinn_phong_choice"]["chosen"]
    assert truth["blinn_phong_pooled"]["exponent_median_rel_error"] < \
        0.5 * truth[chosen]["exponent_median_rel_error"]
    back = btf.BtfMaterial.load(str(out / "maps" / "blinn_phong_pooled"))
    assert back.exponent_map is not None
