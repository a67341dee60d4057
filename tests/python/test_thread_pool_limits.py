"""The shared thread pool (core/ThreadPool, used by the hair and fur generators, the cloth and
the IBL filters) is bounded (issue 13): found by the method sweep, generate_hair(threads=2**31-1)
tried to start two billion threads and hung; above 256 threads is now weft.InvalidArgument, and
a system that cannot start the threads gives weft.Error (the started ones joined), not a hang or
an abort."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import time

import pytest

import weft


@pytest.mark.parametrize("threads", [257, 2 ** 31 - 1])
def test_too_many_threads_are_refused_at_once(threads):
    t0 = time.perf_counter()
    with pytest.raises(weft.InvalidArgument, match=f"1..256, got {threads}"):
        weft.generate_hair(3, 12, threads=threads)
    assert time.perf_counter() - t0 < 1.0


def test_thread_creation_failure_is_an_error_not_a_hang():
    script = textwrap.dedent("""
        import resource, weft
        reference = weft.generate_hair(50, 400, threads=1).points
        with open("/proc/self/status") as f:
            vm = next(int(l.split()[1]) for l in f if l.startswith("VmSize")) * 1024
        # room for a few 8 MiB thread stacks, not for 256
        resource.setrlimit(resource.RLIMIT_AS, (vm + (48 << 20), resource.RLIM_INFINITY))
        outcomes = set()
        for _ in range(3):
            try:
                weft.generate_hair(50, 400, threads=256)
                outcomes.add("ran")
            except weft.Error as e:
                outcomes.add("error" if "cannot start 255 worker threads" in str(e) else str(e))
        print("outcomes", sorted(outcomes))
        resource.setrlimit(resource.RLIMIT_AS, (resource.RLIM_INFINITY, resource.RLIM_INFINITY))
        print("same", (weft.generate_hair(50, 400, threads=4).points == reference).all())
    """)
    env = dict(os.environ, MALLOC_ARENA_MAX="1", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=120, env=env)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "outcomes ['error']" in proc.stdout and "same True" in proc.stdout, proc.stdout
    assert time.perf_counter() - t0 < 30
