"""weft.batch on a real Ray cluster on this machine: a head and a second worker node started
with ``ray start`` (one CPU each), BTF datasets and frames compared byte for byte with the serial
run (no Ray), and a render worker killed in the middle of the batch."""

from __future__ import annotations

import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

import pytest

# The cluster and this process (the driver) share a token made for this run; Ray reads the
# authentication mode when it is imported, so it is set first.
_TOKEN = os.environ.setdefault("RAY_AUTH_TOKEN", secrets.token_hex(32))
os.environ.setdefault("RAY_AUTH_MODE", "token")

ray = pytest.importorskip("ray")

import weft.batch as wb  # noqa: E402
from batch_data import tree, write_datasets, write_render_jobs  # noqa: E402


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _stop(procs) -> None:
    for p in procs:  # every node runs in its own process group: stop the group, by its id
        try:
            os.killpg(p.pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
    deadline = time.monotonic() + 3  # a clean stop is quick; what is left then gets SIGKILL
    for p in procs:
        try:
            p.wait(max(0.1, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            pass
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    for p in procs:  # the nodes' daemons (GCS, raylet) leave after their parent: wait for them
        while time.monotonic() < deadline + 10 and _running_in_group(p.pid):
            time.sleep(0.2)


def _running_in_group(pgid: int) -> bool:
    """Whether a process of group ``pgid`` still runs (zombies, which a container's init may
    never reap, do not count)."""
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", encoding="utf-8", errors="replace") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == pgid and fields[0] != "Z":
            return True
    return False


@pytest.fixture(scope="module")
def cluster():
    """HOST:PORT of a two-node cluster (head + worker, --num-cpus 1 each), stopped after."""
    port = _free_port()
    # Ray's sockets live under its temp dir, and an AF_UNIX path may not exceed 107 bytes: under
    # pytest-xdist, tmp_path_factory's /tmp/pytest-of-root/pytest-N/popen-gwK/ left too few
    temp = tempfile.mkdtemp(prefix="weft-ray-")
    env = dict(os.environ, RAY_USAGE_STATS_ENABLED="0")
    ray_cli = os.path.join(os.path.dirname(sys.executable), "ray")
    common = ["--num-cpus", "1", "--object-store-memory", str(100 << 20), "--block",
              "--disable-usage-stats"]
    procs = []
    try:
        procs.append(subprocess.Popen(
            [ray_cli, "start", "--head", "--port", str(port), "--include-dashboard=false",
             "--temp-dir", temp, *common], env=env, start_new_session=True,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        address = f"127.0.0.1:{port}"
        procs.append(subprocess.Popen(
            [ray_cli, "start", "--address", address, *common], env=env, start_new_session=True,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        _wait_for_nodes(address, 2)
        yield address
    finally:
        if ray.is_initialized():
            ray.shutdown()
        _stop(procs)
        shutil.rmtree(temp, ignore_errors=True)


def _wait_for_nodes(address: str, count: int, timeout: float = 60.0) -> None:
    deadline = time.monotonic() + timeout
    while True:
        try:
            ray.init(address=address, include_dashboard=False, log_to_driver=False,
                     configure_logging=False)
            try:
                while time.monotonic() < deadline:
                    if len([n for n in ray.nodes() if n["Alive"]]) >= count:
                        return
                    time.sleep(0.5)
            finally:
                ray.shutdown()
            raise TimeoutError(f"the Ray cluster did not reach {count} nodes")
        except ConnectionError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.5)


def test_btf_datasets_on_the_cluster_equal_the_serial_run(cluster, tmp_path):
    paths = write_datasets(str(tmp_path), count=4, size=16)
    jobs = wb.make_jobs(paths, dict(figures=False, threads=1), tiles=3, times=False)
    with wb.executor("serial") as ex:
        serial = wb.fit_btf_batch(jobs, str(tmp_path / "serial"), ex, progress=False)
    workers = set()
    with wb.executor("ray", address=cluster) as ex:
        assert len([n for n in ray.nodes() if n["Alive"]]) == 2
        distributed = wb.fit_btf_batch(
            jobs, str(tmp_path / "ray"), ex, progress=False,
            on_event=lambda e: workers.add(json.dumps(e.get("worker"), sort_keys=True)))
    assert serial["done"] == distributed["done"] == 4 and not distributed["failed"]
    a, b = tree(str(tmp_path / "serial")), tree(str(tmp_path / "ray"))
    assert sorted(a) == sorted(b) and len(a) > 4 * 20
    assert [k for k in a if a[k] != b[k]] == []
    # the tasks ran in Ray's worker processes (not here); which node takes them is Ray's
    # choice (tasks this short often all go to one leased worker): the render test below
    # checks that both nodes work
    assert workers and all(json.loads(w)["node"] and json.loads(w)["pid"] != os.getpid()
                           for w in workers)


def test_frames_survive_a_killed_worker_and_equal_the_serial_run(cluster, tmp_path):
    jobs = wb.load_render_jobs(write_render_jobs(str(tmp_path), frames=8))
    with wb.executor("serial") as ex:
        serial = wb.render_batch(jobs, str(tmp_path / "serial"), ex, progress=False)
    killed = []

    def kill_first_worker(event):
        # the worker that delivered the first frame still has a frame queued: kill its
        # process; Ray restarts the actor and re-runs what it had not finished
        if event["stage"] == "frame" and not killed:
            os.kill(event["worker"]["pid"], signal.SIGKILL)
            killed.append(event["worker"]["pid"])

    with wb.executor("ray", address=cluster) as ex:
        distributed = wb.render_batch(jobs, str(tmp_path / "ray"), ex, workers=2,
                                      progress=False, on_event=kill_first_worker)
    assert killed
    assert serial["done"] == distributed["done"] == 10 and not distributed["failed"]
    a, b = tree(str(tmp_path / "serial")), tree(str(tmp_path / "ray"))
    assert len(a) == 10 and sorted(a) == sorted(b)
    assert [k for k in a if a[k] != b[k]] == []
    with open(tmp_path / "ray" / "manifest.json", encoding="utf-8") as f:
        manifest = json.load(f)
    frames = [o for j in manifest["jobs"].values() for o in j["outputs"].values()]
    assert len(frames) == 10 and all(not o["validation_messages"] for o in frames)
    pids = {o["worker"]["pid"] for o in frames}
    assert len(pids) >= 2 and any(p != killed[0] for p in pids)
    # two workers of one CPU each on two nodes of one CPU each: both nodes rendered
    assert len({o["worker"]["node"] for o in frames}) == 2
