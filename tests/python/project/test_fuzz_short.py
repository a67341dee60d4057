"""The loaders' fuzzers (tests/fuzz/fuzz_loaders.py, atheris) run briefly on every test run:
a fixed seed and a few thousand mutations of the checked-in seed corpus per target, in a
subprocess, so a crash (or any exception other than weft.Error) fails the test. The long runs
(1 M executions per target) are recorded in BENCHMARKS.md's reliability section."""

from __future__ import annotations

import os
import re
import resource
import shutil
import subprocess
import sys

import pytest

pytest.importorskip("atheris", reason="atheris (PyPI) is not installed: no fuzzing")

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # tests/
SCRIPT = os.path.join(ROOT, "fuzz", "fuzz_loaders.py")


#: runs per target: a few seconds each (the BTF targets load up to 81 images per run)
RUNS = {"hair": 3000, "obj": 3000, "png": 3000, "hdr": 3000, "exr": 3000, "jpeg": 3000,
        "btfzip": 300, "btftree": 100, "scene": 600, "renderer": 600, "lights": 600,
        "script": 600, "env": 600}


@pytest.mark.parametrize("target", sorted(RUNS))
def test_short_fuzz_run_finds_nothing(target, tmp_path):
    runs = RUNS[target]
    corpus = tmp_path / "corpus"
    shutil.copytree(os.path.join(ROOT, "fuzz", "corpus", target), corpus)
    # libFuzzer's -rss_limit_mb (default 2048) checks the peak resident set, and a child
    # starts with its parent's peak (Linux keeps the high-water mark across fork and exec), so
    # once pytest itself had grown past 2 GiB every run here stopped as "out-of-memory" at its
    # first input. The limit is 2 GiB above what this process has reached.
    inherited_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024
    run = subprocess.run([sys.executable, SCRIPT, target, f"-runs={runs}", "-seed=1",
                          "-max_len=70000", f"-rss_limit_mb={inherited_mb + 2048}",
                          f"-artifact_prefix={tmp_path}/", str(corpus)],
                         capture_output=True, text=True, timeout=300, cwd=tmp_path)
    log = run.stdout + run.stderr
    assert run.returncode == 0, log[-3000:]
    # libFuzzer counts the seed inputs it replays at start as runs too, so it may end a few
    # past -runs (a seed corpus it reduced on the way ended at "Done 103 runs" for 100)
    done = re.search(r"Done (\d+) runs", log)
    assert done and int(done.group(1)) >= runs, log[-2000:]
