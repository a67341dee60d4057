"""Connecting to Ray: a local cluster started for the batch (default) or an existing one.

``executor(mode, address, workers)`` is what the batch functions take:

- ``mode="serial"``: no Ray at all (:class:`~weft.batch.executor.SerialExecutor`);
- ``mode="ray"`` without ``address``: ``ray.init()`` starts a private local cluster with
  ``workers`` CPUs and stops it at the end;
- ``address="HOST:PORT"`` (or ``"auto"``): joins a cluster started with ``ray start --head``
  (docs/batch.md); weft must be installed on every node.
"""

from __future__ import annotations

import contextlib
import os
from typing import Any, Iterator, Optional

import weft
from weft.batch.executor import RayExecutor, SerialExecutor

#: The Ray this package is tested with (pyproject extra ``weft[batch]``).
RAY_REQUIREMENT = "ray==2.60.0"


def import_ray() -> Any:
    try:
        import ray
    except ImportError:
        raise weft.InvalidArgument(
            "Ray is not installed: pip install 'weft[batch]' (or pip install ray), or run the "
            "batch with mode='serial' / --serial") from None
    return ray


@contextlib.contextmanager
def executor(mode: str = "ray", address: Optional[str] = None, workers: Optional[int] = None,
             retries: int = 3, cpus_per_task: float = 1.0,
             object_store_bytes: Optional[int] = None) -> Iterator[Any]:
    """Yields an executor; a local Ray cluster started here is shut down on exit.

    ``workers``: CPUs of the local cluster (default: all cores); ignored with ``address``.
    ``object_store_bytes``: the local cluster's shared-memory object store (default Ray's)."""
    if mode not in ("ray", "serial"):
        raise weft.InvalidArgument(f"mode must be 'ray' or 'serial', got {mode!r}")
    if mode == "serial":
        if address:
            raise weft.InvalidArgument("address needs mode='ray'")
        ex = SerialExecutor()
        try:
            yield ex
        finally:
            ex.close()
        return
    if workers is not None and (isinstance(workers, bool) or int(workers) < 1):
        raise weft.InvalidArgument(f"workers must be >= 1, got {workers}")
    ray = import_ray()
    started = False
    if not ray.is_initialized():
        kwargs: dict = dict(include_dashboard=False, log_to_driver=False,
                            configure_logging=False)
        if address:
            ray.init(address=address, **kwargs)
        else:
            ray.init(num_cpus=int(workers or os.cpu_count() or 1),
                     object_store_memory=object_store_bytes, **kwargs)
        started = True
    ex = RayExecutor(retries=retries, cpus=cpus_per_task)
    try:
        yield ex
    finally:
        ex.close()
        if started:
            ray.shutdown()
