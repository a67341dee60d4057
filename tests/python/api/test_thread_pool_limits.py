"""The engine's thread pool (core/ThreadPool: one pool shared by the hair and fur generators, the
cloth, the BTF fits and the IBL filters) is bounded (issue 13): found by the method sweep,
generate_hair(threads=2**31-1) tried to start two billion threads and hung; above 256 threads is
now weft.InvalidArgument. A call's `threads` no longer starts threads (issue 15): it caps how many
of the pool's threads work on it, and a system that cannot start the pool's threads leaves the
work to the caller's thread, not a hang or an abort."""

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


def test_no_thread_can_start_and_the_work_is_still_done():
    script = textwrap.dedent("""
        import resource, weft
        with open("/proc/self/status") as f:
            vm = next(int(l.split()[1]) for l in f if l.startswith("VmSize")) * 1024
        # no room for one 8 MiB thread stack: the engine pool starts on first use, here
        resource.setrlimit(resource.RLIMIT_AS, (vm + (4 << 20), resource.RLIM_INFINITY))
        outcomes = set()
        for _ in range(3):
            try:
                points = weft.generate_hair(50, 400, threads=256).points
                outcomes.add("ran")
            except weft.Error as e:
                outcomes.add(str(e))
        print("outcomes", sorted(outcomes))
        resource.setrlimit(resource.RLIMIT_AS, (resource.RLIM_INFINITY, resource.RLIM_INFINITY))
        print("same", (weft.generate_hair(50, 400, threads=1).points == points).all())
    """)
    env = dict(os.environ, MALLOC_ARENA_MAX="1", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=120, env=env)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "outcomes ['ran']" in proc.stdout and "same True" in proc.stdout, proc.stdout
    assert time.perf_counter() - t0 < 30
