"""The loaders' fuzzers (tests/fuzz/fuzz_loaders.py, atheris) run briefly on every test run:
a fixed seed and a few thousand mutations of the checked-in seed corpus per target, in a
subprocess, so a crash (or any exception other than weft.Error) fails the test. The long runs
(1 M executions per target) are recorded in BENCHMARKS.md's reliability section."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

import pytest

pytest.importorskip("atheris", reason="atheris (PyPI) is not installed: no fuzzing")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCRIPT = os.path.join(ROOT, "fuzz", "fuzz_loaders.py")


@pytest.mark.parametrize("target", ["hair", "obj", "png", "hdr", "exr"])
def test_short_fuzz_run_finds_nothing(target, tmp_path):
    corpus = tmp_path / "corpus"
    shutil.copytree(os.path.join(ROOT, "fuzz", "corpus", target), corpus)
    run = subprocess.run([sys.executable, SCRIPT, target, "-runs=3000", "-seed=1",
                          "-max_len=4096", f"-artifact_prefix={tmp_path}/", str(corpus)],
                         capture_output=True, text=True, timeout=300, cwd=tmp_path)
    log = run.stdout + run.stderr
    assert run.returncode == 0, log[-3000:]
    assert "Done 3000 runs" in log, log[-2000:]
