"""The batch's JSON manifest and atomic output files: what makes a batch resumable.

An output counts as finished when its file exists *and* the manifest holds it with the same
key (a hash of everything that decides its bytes: the job's settings, inputs and the weft
version). Files are written to a temporary name and renamed, so a batch killed mid-write
never leaves a half file that a re-run would take as finished.
"""

from __future__ import annotations

import hashlib
import json
import os
import socket
import sys
import time
from typing import Any, Dict, Mapping, Optional

import weft
from weft.bench import json_safe

FORMAT = "weft-batch-manifest"
VERSION = 1


def key_of(*parts: Any) -> str:
    """A stable hash of JSON-able parts (sorted keys) and the weft version."""
    text = json.dumps([weft.__version__, *parts], sort_keys=True, default=str)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:20]


def write_bytes(path: str, data: bytes) -> None:
    """Writes ``data`` to ``path`` through a temporary file and a rename (atomic)."""
    folder = os.path.dirname(path)
    if folder:
        os.makedirs(folder, exist_ok=True)
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)


class Manifest:
    """``out/manifest.json``: per job its settings, status, outputs (with keys, timings, the
    worker and device that made them) and failures; saved atomically, at most every
    ``interval`` seconds while a batch runs and always at :meth:`save` ``(force=True)``."""

    def __init__(self, out: str, kind: str, interval: float = 0.5) -> None:
        self.path = os.path.join(out, "manifest.json")
        self.kind = kind
        self.interval = interval
        self._saved = 0.0
        self.data: Dict[str, Any] = {"format": FORMAT, "version": VERSION, "kind": kind,
                                     "jobs": {}}
        old = self._read()
        if old is not None:
            self.data["jobs"] = old.get("jobs", {})

    def _read(self) -> Optional[Dict[str, Any]]:
        try:
            with open(self.path, encoding="utf-8") as f:
                old = json.load(f)
        except FileNotFoundError:
            return None
        except (OSError, ValueError) as exc:
            raise weft.IoError(f"{self.path}: unreadable manifest ({exc}); remove it to start "
                               "the batch afresh") from None
        if not isinstance(old, dict) or old.get("format") != FORMAT:
            raise weft.IoError(f"{self.path} is not a weft batch manifest")
        if old.get("kind") != self.kind:
            raise weft.InvalidArgument(f"{self.path} belongs to a '{old.get('kind')}' batch, "
                                       f"not '{self.kind}': use another output folder")
        return old

    def job(self, name: str) -> Dict[str, Any]:
        return self.data["jobs"].setdefault(name, {"outputs": {}})

    def finished(self, job: str, output: str, key: str, root: str) -> bool:
        """True when ``output`` (a path relative to ``root``) exists with this key."""
        entry = self.data["jobs"].get(job, {}).get("outputs", {}).get(output)
        return bool(entry and entry.get("key") == key and
                    os.path.exists(os.path.join(root, entry.get("file", output))))

    def record(self, job: str, output: str, entry: Mapping[str, Any]) -> None:
        j = self.job(job)
        j["outputs"][output] = dict(entry)
        j.get("failures", {}).pop(output, None)
        self.save()

    def fail(self, job: str, output: str, error: BaseException) -> None:
        j = self.job(job)
        j.setdefault("failures", {})[output] = f"{type(error).__name__}: {error}"
        j["outputs"].pop(output, None)
        self.save()

    def save(self, force: bool = False, **summary: Any) -> None:
        if summary:
            self.data["summary"] = summary
        now = time.monotonic()
        if not force and now - self._saved < self.interval:
            return
        self._saved = now
        text = json.dumps(json_safe(self.data), indent=2, sort_keys=True) + "\n"
        write_bytes(self.path, text.encode("utf-8"))


def where() -> Dict[str, Any]:
    """The worker that ran a task: host name, process id and, on Ray, the node id (nodes on
    one machine share the host name)."""
    out: Dict[str, Any] = {"host": socket.gethostname(), "pid": os.getpid()}
    ray = sys.modules.get("ray")  # never imports Ray: a serial run has none
    if ray is not None and ray.is_initialized():
        out["node"] = ray.get_runtime_context().get_node_id()
    return out
