"""weft.batch without Ray: the serial path against ``python -m weft btf fit``, views, resume,
failures reported per job, memory bound, bad input, and the CLI."""

from __future__ import annotations

import json
import os
import re

import numpy as np
import pytest
import weft
import weft.batch as wb
import weft.btf.synth as synth
from batch_data import tree, write_datasets, write_render_jobs
from weft.__main__ import main as weft_main


def _masked_metrics(path: str) -> dict:
    """metrics.json without the measured times."""
    with open(path, encoding="utf-8") as f:
        m = json.load(f)
    m.pop("times_s")
    for r in m["models"].values():
        r.pop("seconds")
    return m


def _masked_report(path: str) -> str:
    """report.md with the 'fit s' column of the models table blanked."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    start = lines.index("## Models")
    end = next(i for i in range(start + 3, len(lines)) if not lines[i].startswith("|"))
    for i in range(start + 4, end):
        lines[i] = re.sub(r"\| [0-9.]+ \|$", "| t |", lines[i])
    return "\n".join(lines)


def _serial(jobs, out):
    with wb.executor("serial") as ex:
        return wb.fit_btf_batch(jobs, str(out), ex, progress=False)


def test_bands_give_the_outputs_of_btf_fit(tmp_path):
    """A fit split into 5 bands of rows writes what btf fit writes for the whole dataset:
    maps and previews byte for byte, metrics and report up to the measured times."""
    path = write_datasets(str(tmp_path), count=1, size=20)[0]
    assert weft_main(["btf", "fit", path, "--out", str(tmp_path / "cli"), "--no-progress",
                      "--no-figures", "--lafortune", "1", "2", "--pooled-exponent"]) == 0
    jobs = wb.make_jobs([path], dict(figures=False, lafortune=[1, 2], pooled_exponent=True),
                        tiles=5)
    summary = _serial(jobs, tmp_path / "batch")
    assert summary["done"] == 1 and summary["texels"] == 400
    cli, batch = tree(str(tmp_path / "cli")), tree(str(tmp_path / "batch" / "m0"))
    assert sorted(cli) == sorted(batch)
    maps = [k for k in cli if k.startswith("maps")]
    assert len(maps) > 30 and any("lafortune_2" in k for k in maps)
    assert any("blinn_phong_pooled" in k for k in maps)
    assert [k for k in maps if cli[k] != batch[k]] == []
    assert _masked_metrics(str(tmp_path / "cli" / "metrics.json")) == \
        _masked_metrics(str(tmp_path / "batch" / "m0" / "metrics.json"))
    assert _masked_report(str(tmp_path / "cli" / "report.md")) == \
        _masked_report(str(tmp_path / "batch" / "m0" / "report.md"))


def test_split_by_views_fits_each_view_as_btf_fit_does(tmp_path):
    samples, _ = synth.synthesize_random(3, 12, views=2, noise=0.002)
    path = str(tmp_path / "two")
    os.makedirs(path)
    synth.write(path, samples, fmt="png")
    views = wb.dataset_views(path)
    assert len(views) == 2
    jobs = wb.make_jobs([path], dict(figures=False, lafortune=[0]), tiles=2, split="views")
    assert [j.name for j in jobs] == [f"two/views/tv{int(t):03d}_pv{int(p):03d}"
                                      for t, p in views]
    assert _serial(jobs, tmp_path / "batch")["done"] == 2
    t, p = views[1]
    assert weft_main(["btf", "fit", path, "--out", str(tmp_path / "cli"), "--no-progress",
                      "--no-figures", "--lafortune", "0", "--views", f"{t:g},{p:g}"]) == 0
    cli = tree(str(tmp_path / "cli"))
    batch = tree(str(tmp_path / "batch" / jobs[1].name))
    assert [k for k in cli if k.startswith("maps") and cli[k] != batch[k]] == []
    with open(tmp_path / "batch" / "two" / "views.json", encoding="utf-8") as f:
        index = json.load(f)["views"]
    assert sorted(index) == sorted(j.name.rsplit("/", 1)[1] for j in jobs)
    assert all(v["deviation"] > 0 for v in index.values())


def test_btf_resume_and_failures_per_job(tmp_path):
    good = write_datasets(str(tmp_path), count=2, size=12)
    broken = tmp_path / "broken"
    broken.mkdir()
    (broken / "UBO_tl000_pl000_tv000_pv000.png").write_bytes(b"not a png")
    opts = dict(figures=False, nonlinear=False, lafortune=[0])
    jobs = wb.make_jobs(good + [str(broken)], opts, tiles=2)
    first = _serial(jobs, tmp_path / "out")
    assert first["done"] == 2 and list(first["failed"]) == ["broken"]
    assert "broken" in first["failed"] and first["failed"]["broken"]
    with open(tmp_path / "out" / "manifest.json", encoding="utf-8") as f:
        manifest = json.load(f)
    assert manifest["jobs"]["broken"]["failures"]["fit"]
    before = os.stat(tmp_path / "out" / "m0" / "metrics.json").st_mtime_ns
    os.remove(tmp_path / "out" / "m1" / "metrics.json")
    again = _serial(jobs, tmp_path / "out")
    assert again["skipped"] == 1 and again["done"] == 1 and list(again["failed"]) == ["broken"]
    assert os.stat(tmp_path / "out" / "m0" / "metrics.json").st_mtime_ns == before
    assert os.path.exists(tmp_path / "out" / "m1" / "metrics.json")
    # other options: not the same outputs, so nothing is skipped
    changed = wb.make_jobs(good, dict(opts, robust=True), tiles=2)
    assert _serial(changed, tmp_path / "out")["skipped"] == 0


def test_memory_per_task_is_enforced_with_a_message(tmp_path):
    path = write_datasets(str(tmp_path), count=1, size=12)[0]
    jobs = wb.make_jobs([path], dict(figures=False), tiles=2, memory=10_000)
    failed = _serial(jobs, tmp_path / "out")["failed"]
    assert "GiB" in failed["m0"] and "memory" in failed["m0"]


def test_frames_resume_and_a_failing_job_does_not_stop_the_others(tmp_path):
    jobs_file = write_render_jobs(str(tmp_path), frames=3)
    with open(tmp_path / "bad.py", "w", encoding="utf-8") as f:
        f.write("def build(frame, params):\n    raise ValueError('no scene here')\n")
    jobs = wb.load_render_jobs(jobs_file) + [wb.make_render_job(
        {"name": "bad", "scene": "bad.py", "frames": 2, "settings": {"width": 16, "height": 16}},
        str(tmp_path))]
    with wb.executor("serial") as ex:
        first = wb.render_batch(jobs, str(tmp_path / "out"), ex, progress=False)
    assert first["done"] == 5 and sorted(first["failed"]) == ["bad/0000", "bad/0001"]
    assert "no scene here" in first["failed"]["bad/0000"]
    frame = weft.load_png(str(tmp_path / "out" / "orbit" / "frame_0002.png"))
    assert frame.shape == (36, 48, 4) and frame[..., :3].std() > 5  # a picture, not a fill
    os.remove(tmp_path / "out" / "orbit" / "frame_0001.png")
    with wb.executor("serial") as ex:
        again = wb.render_batch(jobs[:2], str(tmp_path / "out"), ex, progress=False)
    assert again["done"] == 1 and again["skipped"] == 4


def test_render_frames_do_not_depend_on_order(tmp_path):
    """What makes frames tasks: a worker that rendered other frames first gives the same
    bytes as a fresh one (frames 3, 0 on one worker against 0 and 3 each fresh)."""
    job = wb.load_render_jobs(write_render_jobs(str(tmp_path), frames=4))[0]
    from weft.batch.render_worker import FrameRenderer

    shared = FrameRenderer()
    late, early = shared.render((job, 3))["png"], shared.render((job, 0))["png"]
    assert FrameRenderer().render((job, 0))["png"] == early
    assert FrameRenderer().render((job, 3))["png"] == late and late != early


@pytest.mark.parametrize("spec, message", [
    ({"name": "a", "frames": 0}, "frames"),
    ({"name": "../a"}, "relative folder"),
    ({"name": "a", "settings": {"widht": 3}}, "unknown settings"),
    ({"name": "a", "scene": "castle"}, "scene script"),
    ({"name": "a", "camera": {"spline": []}}, "orbit"),
    ({"name": "a", "camera": {"orbit": {"radius": "far"}}}, "finite number"),
    ({"name": "a", "colour": 1}, "unknown render job keys"),
])
def test_bad_render_jobs_are_refused(spec, message):
    with pytest.raises(weft.InvalidArgument, match=message):
        wb.make_render_job(spec)


def test_bad_btf_jobs_are_refused(tmp_path):
    path = write_datasets(str(tmp_path), count=1, size=8)[0]
    with pytest.raises(weft.InvalidArgument, match="tiles"):
        wb.make_jobs([path], tiles=0)
    with pytest.raises(weft.InvalidArgument, match="unknown BTF fit options"):
        wb.make_jobs([path], dict(colour=1))
    with pytest.raises(weft.InvalidArgument, match="two datasets named"):
        wb.make_jobs([path, path])
    with pytest.raises(weft.IoError, match="no such"):
        wb.make_jobs([str(tmp_path / "missing")])
    with pytest.raises(weft.InvalidArgument, match="mode"):
        with wb.executor("threads"):
            pass
    with pytest.raises(weft.IoError, match="not JSON"):
        (tmp_path / "j.json").write_text("{")
        wb.load_render_jobs(str(tmp_path / "j.json"))


def test_cli_serial(tmp_path, capsys):
    paths = write_datasets(str(tmp_path), count=1, size=8)
    assert weft_main(["batch", "btf", *paths, "--out", str(tmp_path / "btf"), "--serial",
                      "--no-figures", "--no-nonlinear", "--lafortune", "0", "--tiles", "2",
                      "--no-progress"]) == 0
    assert "1 done, 0 skipped" in capsys.readouterr().out
    assert os.path.exists(tmp_path / "btf" / "m0" / "maps" / "linear" / "normal.exr")
    jobs = write_render_jobs(str(tmp_path), frames=1)
    assert weft_main(["batch", "render", jobs, "--out", str(tmp_path / "frames"), "--serial",
                      "--no-progress", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["done"] == 3 and summary["executor"] == "serial"
    assert np.asarray(weft.load_png(str(tmp_path / "frames" / "script" / "frame_0001.png"))).any()
    with pytest.raises(SystemExit):
        weft_main(["batch", "btf", *paths, "--out", str(tmp_path / "x"), "--serial",
                   "--address", "auto"])


def test_the_serial_path_needs_no_ray(tmp_path):
    """A serial batch never imports Ray (it runs where Ray is not installed)."""
    import subprocess
    import sys

    path = write_datasets(str(tmp_path), count=1, size=8)[0]
    code = ("import sys, weft.batch as wb\n"
            f"jobs = wb.make_jobs([{path!r}], dict(figures=False, nonlinear=False), tiles=2)\n"
            "with wb.executor('serial') as ex:\n"
            f"    s = wb.fit_btf_batch(jobs, {str(tmp_path / 'out')!r}, ex, progress=False)\n"
            "assert s['done'] == 1, s\n"
            "assert 'ray' not in sys.modules\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr
