"""Where batch tasks run: :class:`SerialExecutor` (this process, no Ray) or :class:`RayExecutor`.

Both run the same task functions on the same inputs, so a batch gives the same bytes either
way. A batch is a graph: :meth:`submit` takes a function and its arguments, where an argument
may be the :class:`Handle` of an earlier task (its result is passed in; a failed dependency fails
the task without running it). :meth:`finished` yields ``(handle, value, error)`` as tasks end.
Rendering uses :meth:`pool`: long-lived workers (Ray actors) that keep their Vulkan renderer.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence, Tuple

Finished = Tuple["Handle", Any, Optional[BaseException]]
Mapped = Tuple[Any, Any, Optional[BaseException]]  # (item, result, error)


@dataclass(eq=False)
class Handle:
    """One task's result (``index`` picks one of several returns)."""

    id: int
    ref: Any = None          # Ray: the ObjectRef; serial: unused
    parent: Optional["Handle"] = None
    index: int = 0
    label: str = ""


class TaskFailed(RuntimeError):
    """A task raised (or a task it depends on did); ``str`` names the first cause."""


class SerialExecutor:
    """Runs every task in this process, in submission order, when :meth:`finished` is
    iterated. ``workers`` is 1: the serial reference of a batch."""

    workers = 1
    kind = "serial"

    def __init__(self) -> None:
        self._ids = itertools.count()
        self._queue: List[Tuple[Handle, Callable[..., Any], Tuple[Any, ...], List[Handle]]] = []
        self._values: Dict[int, Any] = {}
        self._errors: Dict[int, BaseException] = {}
        self._uses: Dict[int, int] = {}  # queued tasks that still need a result (then freed)

    def submit(self, fn: Callable[..., Any], *args: Any, num_returns: int = 1,
               memory: int = 0, label: str = "", track: Optional[Sequence[int]] = None,
               spread: bool = False) -> Any:
        """Queues ``fn(*args)``; with ``num_returns`` > 1 returns one handle per result, and
        :meth:`finished` reports those in ``track`` (default all)."""
        h = Handle(next(self._ids), label=label)
        for a in args:
            if isinstance(a, Handle):
                root = (a.parent or a).id
                self._uses[root] = self._uses.get(root, 0) + 1
        if num_returns == 1:
            self._queue.append((h, fn, args, [h]))
            return h
        parts = [Handle(next(self._ids), parent=h, index=i, label=label)
                 for i in range(num_returns)]
        keep = range(num_returns) if track is None else track
        self._queue.append((h, fn, args, [parts[i] for i in keep]))
        return parts

    def _resolve(self, arg: Any) -> Any:
        if not isinstance(arg, Handle):
            return arg
        if arg.parent is not None:
            if arg.parent.id in self._errors:
                raise TaskFailed(str(self._errors[arg.parent.id]))
            return self._values[arg.parent.id][arg.index]
        if arg.id in self._errors:
            raise TaskFailed(str(self._errors[arg.id]))
        return self._values[arg.id]

    def _release(self, args: Sequence[Any]) -> None:
        for a in args:
            if isinstance(a, Handle):
                root = (a.parent or a).id
                self._uses[root] -= 1
                if not self._uses[root]:
                    self._values.pop(root, None)

    def finished(self) -> Iterator[Finished]:
        while self._queue:
            h, fn, args, report = self._queue.pop(0)
            try:
                value = fn(*[self._resolve(a) for a in args])
            except Exception as exc:  # a failed job is reported, the batch goes on
                self._errors[h.id] = exc
                self._release(args)
                for r in report:
                    yield r, None, exc
                continue
            self._release(args)
            if self._uses.get(h.id):
                self._values[h.id] = value
            for r in report:
                yield r, (value if r is h else value[r.index]), None

    def pool(self, factory: Callable[[], Any], size: int, memory: int = 0,
             gpus: float = 0.0) -> "SerialPool":
        return SerialPool(factory())

    def close(self) -> None:
        self._values.clear()


class SerialPool:
    """One worker object called in this process (the serial twin of :class:`RayPool`)."""

    def __init__(self, worker: Any) -> None:
        self.worker = worker
        self.size = 1

    def map_unordered(self, method: str, items: Sequence[Any]) -> Iterator[Mapped]:
        for item in items:
            try:
                yield item, getattr(self.worker, method)(item), None
            except Exception as exc:
                yield item, None, exc

    def close(self) -> None:
        self.worker = None


def _failure(exc: BaseException) -> BaseException:
    """The user's error inside a Ray error (the first line names it), else ``exc``."""
    cause = getattr(exc, "cause", None)
    if isinstance(cause, BaseException):
        return cause
    return exc


class RayExecutor:
    """Runs tasks as Ray tasks on the connected cluster (:func:`weft.batch.cluster.connect`).

    ``retries``: how often a task is re-run when its worker process or node is lost (Ray's
    ``max_retries``; exceptions the task raises are not retried: they are the job's failure).
    ``memory``: bytes a task reserves (Ray schedules no more tasks on a node than its memory
    holds); ``cpus``: CPUs a task reserves (its native fits use that many threads)."""

    kind = "ray"

    def __init__(self, retries: int = 3, cpus: float = 1.0) -> None:
        import ray

        self.ray = ray
        self.retries = int(retries)
        self.cpus = float(cpus)
        self._ids = itertools.count()
        self._pending: Dict[Any, Handle] = {}
        self._remote: Dict[Callable[..., Any], Any] = {}
        self.workers = max(1, int(ray.cluster_resources().get("CPU", 1) // max(cpus, 1e-9)))

    def _fn(self, fn: Callable[..., Any]) -> Any:
        if fn not in self._remote:
            self._remote[fn] = self.ray.remote(fn)
        return self._remote[fn]

    def submit(self, fn: Callable[..., Any], *args: Any, num_returns: int = 1,
               memory: int = 0, label: str = "", track: Optional[Sequence[int]] = None,
               spread: bool = False) -> Any:
        """``spread``: place the task on the least loaded node (Ray's SPREAD; for tasks that
        start a job's work, e.g. one per dataset), else where its inputs are (DEFAULT)."""
        opts: Dict[str, Any] = dict(num_returns=num_returns, max_retries=self.retries,
                                    retry_exceptions=False, num_cpus=self.cpus)
        if spread:
            opts["scheduling_strategy"] = "SPREAD"
        if memory > 0:
            opts["memory"] = int(memory)
        refs = self._fn(fn).options(**opts).remote(
            *[a.ref if isinstance(a, Handle) else a for a in args])
        if num_returns == 1:
            h = Handle(next(self._ids), ref=refs, label=label)
            self._pending[refs] = h
            return h
        parent = Handle(next(self._ids), label=label)
        out = [Handle(next(self._ids), ref=r, parent=parent, index=i, label=label)
               for i, r in enumerate(refs)]
        for i in (range(num_returns) if track is None else track):
            self._pending[out[i].ref] = out[i]
        return out

    def finished(self) -> Iterator[Finished]:
        while self._pending:
            done, _ = self.ray.wait(list(self._pending), num_returns=1)
            for ref in done:
                h = self._pending.pop(ref)
                try:
                    # task results are small (maps of a tile, file bytes); big inputs stay in
                    # the object store and go from task to task without passing through here
                    value = self.ray.get(ref)
                except Exception as exc:
                    yield h, None, _failure(exc)
                    continue
                yield h, value, None

    def pool(self, factory: Callable[[], Any], size: int, memory: int = 0,
             gpus: float = 0.0) -> "RayPool":
        return RayPool(self.ray, factory, size, memory, self.retries, self.cpus, gpus)

    def close(self) -> None:
        self._pending.clear()


class RayPool:
    """``size`` actors made by ``factory`` (each keeps its state, e.g. one Vulkan renderer).
    An actor whose process dies is restarted (``max_restarts``) and its unfinished calls are
    re-run (``max_task_retries``); each actor has at most two calls queued so work goes to the
    actor that is free."""

    def __init__(self, ray: Any, factory: Callable[[], Any], size: int, memory: int,
                 retries: int, cpus: float, gpus: float = 0.0) -> None:
        self.ray = ray
        opts: Dict[str, Any] = dict(max_restarts=retries, max_task_retries=retries,
                                    num_cpus=cpus)
        if gpus > 0:  # Ray then sets CUDA_VISIBLE_DEVICES; Vulkan picks by WEFT_DEVICE
            opts["num_gpus"] = gpus
        if memory > 0:
            opts["memory"] = int(memory)
        cls = ray.remote(_ActorShell).options(**opts)
        self.actors = [cls.remote(factory) for _ in range(max(1, int(size)))]
        self.size = len(self.actors)

    def map_unordered(self, method: str, items: Sequence[Any]) -> Iterator[Mapped]:
        queue = list(items)
        inflight: Dict[Any, Tuple[Any, Any]] = {}
        load = {id(a): 0 for a in self.actors}

        def feed() -> None:
            for actor in self.actors:
                while queue and load[id(actor)] < 2:
                    item = queue.pop(0)
                    inflight[actor.call.remote(method, item)] = (actor, item)
                    load[id(actor)] += 1

        feed()
        while inflight:
            done, _ = self.ray.wait(list(inflight), num_returns=1)
            for ref in done:
                actor, item = inflight.pop(ref)
                load[id(actor)] -= 1
                try:
                    yield item, self.ray.get(ref), None
                except Exception as exc:
                    yield item, None, _failure(exc)
            feed()

    def close(self) -> None:
        for a in self.actors:
            self.ray.kill(a)


class _ActorShell:
    """The Ray actor around a worker object: ``call(method, item)``, ``pid()``."""

    def __init__(self, factory: Callable[[], Any]) -> None:
        self.worker = factory()

    def call(self, method: str, item: Any) -> Any:
        return getattr(self.worker, method)(item)

    def pid(self) -> int:
        import os

        return os.getpid()
