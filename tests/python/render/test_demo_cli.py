"""weft-demo's command line (CLI11): the help is complete and what the README promises, bad
values are refused naming the option, the statistics are valid JSON, and the demo says what it
is doing before the seconds it spends building its scene."""

from __future__ import annotations

import json
import os
import re
import subprocess
from pathlib import Path

import pytest

EXE = os.environ.get("WEFT_DEMO_EXE")
README = Path(__file__).resolve().parents[3] / "README.md"
pytestmark = pytest.mark.skipif(not EXE or not Path(EXE).exists(),
                                reason="WEFT_DEMO_EXE (source scripts/env.sh) not built")

OPTIONS = ["--width", "--height", "--frames", "--headless", "--out", "--environment", "--msaa",
           "--ao", "--no-bounce", "--exposure", "--tone-map", "--time", "--script",
           "--screenshot", "--stats", "--no-vsync", "--shader-dir", "--no-hot-reload", "--no-panel",
           "--quiet", "--help"]


def demo(*args: str, timeout: float = 120) -> subprocess.CompletedProcess:
    return subprocess.run([EXE, *args], capture_output=True, text=True, timeout=timeout)


def test_help_lists_every_option_and_what_the_readme_names() -> None:
    proc = demo("--help")
    assert proc.returncode == 0 and proc.stdout.startswith("usage: weft-demo [options]")
    listed = set(re.findall(r"^  (?:-h, )?(--[a-z-]+)", proc.stdout, re.M))
    assert listed == set(OPTIONS)
    assert "controls (window)" in proc.stdout
    # every demo option the README mentions exists
    text = README.read_text()
    start = text.index("- **The demo**")
    mentioned = set(re.findall(r"(--[a-z][a-z-]+)", text[start:text.index("\n- **", start + 1)]))
    mentioned |= set(re.findall(r"weft-demo (--[a-z][a-z-]+)", text))
    assert mentioned and mentioned <= set(OPTIONS), mentioned - set(OPTIONS)


@pytest.mark.parametrize("args,message", [
    (["--width", "x"], "--width"), (["--msaa", "-1"], "--msaa"), (["--frames", "1.5"], "--frames"),
    (["--time", "25"], "--time: needs hours in [0, 24]"), (["--time", "nan"], "--time"),
    (["--tone-map", "sepia"], "--tone-map: must be clamp, aces, agx or neutral"),
    (["--bogus"], "--bogus"), (["--out"], "--out")])
def test_bad_arguments_are_refused_naming_the_option(args, message) -> None:
    proc = demo("--headless", *args, timeout=60)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert proc.stderr.startswith("weft-demo: error:") and message in proc.stderr, proc.stderr


def test_headless_run_prints_progress_and_writes_json(tmp_path: Path) -> None:
    stats = tmp_path / "stats.json"
    proc = demo("--headless", "--width", "64", "--height", "36", "--frames", "2", "--msaa", "1",
                "--ao", "0", "--tone-map", "aces", "--time", "12", "--out", str(tmp_path / "f"),
                "--stats", str(stats), "--no-hot-reload")
    assert proc.returncode == 0, proc.stderr
    # progress on stderr, each line stamped with the seconds since the start; the result on stdout
    progress = proc.stderr.splitlines()
    assert any("building the scene" in line for line in progress), proc.stderr
    assert any("rendering the first frame" in line for line in progress), proc.stderr
    assert any(line.startswith("weft-demo: [") and "frame 2/2" in line
               for line in progress), proc.stderr
    assert "written to" in proc.stdout and "building" not in proc.stdout, proc.stdout
    last = json.loads(stats.read_text())
    assert last["frame_index"] == 1 and last["passes"]
    frames = json.loads((tmp_path / "f" / "stats.json").read_text())
    assert [f["frame_index"] for f in frames] == [0, 1]
    assert all(isinstance(p["name"], str) for f in frames for p in f["passes"])


def test_quiet_run_prints_no_progress(tmp_path: Path) -> None:
    proc = demo("--headless", "--quiet", "--width", "32", "--height", "24", "--msaa", "1",
                "--ao", "0", "--out", str(tmp_path / "q.png"), "--no-hot-reload")
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == "" and "written to" in proc.stdout, proc.stdout + proc.stderr
