"""weft-bench's command line (CLI11, laid out as weft-demo's): the help lists every option with
what gpu-check.sh and the README rely on, bad values are refused naming the option (exit 2), and
the options reach the run (--sets replaces the default list, --quick means one timed frame)."""

from __future__ import annotations

import json
import re
import subprocess
from pathlib import Path

import pytest

EXE = Path(__file__).resolve().parents[3] / "build" / "py" / "cpp" / "weft-bench"
pytestmark = [pytest.mark.slow,  # a benchmark run (pyproject.toml: markers)
              pytest.mark.skipif(not EXE.exists(), reason="needs scripts/build.sh's weft-bench")]

OPTIONS = ["--quick", "--frames", "--sets", "--out", "--images", "--device", "--list-devices",
           "--require-gpu", "--fur-23m", "--no-fur-23m", "--help"]


def bench(*args: str, timeout: float = 300) -> subprocess.CompletedProcess:
    return subprocess.run([str(EXE), *args], capture_output=True, text=True, timeout=timeout)


def test_help_lists_every_option_once() -> None:
    run = bench("--help")
    assert run.returncode == 0 and run.stderr == ""
    text = run.stdout
    assert text.startswith("usage: weft-bench [options]\n\nRenders the benchmark set")
    listed = re.findall(r"^  (-h, )?(--[a-z0-9-]+)", text, re.M)
    assert [name for _, name in listed] == OPTIONS
    for meta in ("--frames N", "--sets LIST", "--out DIR", "--device X"):
        assert f"  {meta} " in text, meta
    assert text.rstrip().endswith("any message fails the run (exit 3).")


@pytest.mark.parametrize("args, named", [
    (["--sets", "demo,nope"], "--sets"), (["--frames", "0"], "--frames"),
    (["--frames", "1001"], "--frames"), (["--frames", "two"], "--frames"),
    (["--device", ""], "--device"), (["--fur-23m", "--no-fur-23m"], "--fur-23m"),
    (["--out"], "--out"), (["--bogus"], "--bogus")])
def test_bad_arguments_exit_2_naming_the_option(args: list[str], named: str) -> None:
    run = bench(*args)
    assert run.returncode == 2, run.stderr
    assert run.stderr.startswith("weft-bench: error: ") and named in run.stderr
    assert run.stdout == ""


def test_sets_and_quick_reach_the_run(tmp_path: Path) -> None:
    run = bench("--quick", "--sets", "demo", "--out", str(tmp_path))
    assert run.returncode == 0, run.stderr
    report = json.loads((tmp_path / "bench.json").read_text())
    rows = report["rows"]
    assert rows and {r["set"] for r in rows} == {"demo"}  # not the default demo,hair,dome
    assert all(r["frames"] == 1 for r in rows)  # --quick: one timed frame
