"""Benchmarks: ``python -m weft.bench <subsystem> [options]``.

Every subsystem measures run time *and* error against an independent reference on the same
run, and writes ``bench.json`` + ``bench.md`` into its output folder. A subsystem is a module
with ``DESCRIPTION`` (one line), ``add_arguments(parser)`` and ``run(args) -> int``; register it
in :data:`SUBSYSTEMS` (name -> module) to make it available on the command line.
"""

from __future__ import annotations

import argparse
import importlib
import json
import math
import os
import platform
import sys
import time
from types import ModuleType
from typing import Any, Dict, List, Optional, Sequence

from weft import reporting as _reporting

#: Benchmark subsystems: command name -> module implementing it.
SUBSYSTEMS: Dict[str, str] = {
    "render": "weft.bench.render",
    "scene": "weft.bench.scene",
    "cloth": "weft.bench.cloth",
    "hair": "weft.bench.hair",
    "btf": "weft.bench.btf",
    "ibl": "weft.bench.ibl",
    "picture": "weft.bench.picture",
    "batch": "weft.bench.batch",
    "soak": "weft.bench.soak",
}

__all__ = ["SUBSYSTEMS", "main", "load_subsystem", "machine_info", "Progress", "write_report",
           "markdown_table", "json_safe", "save_figure"]


class UnknownSubsystem(LookupError):
    """Raised for a subsystem name that is not in :data:`SUBSYSTEMS`."""


def load_subsystem(name: str) -> ModuleType:
    """Imports the module of benchmark subsystem ``name``."""
    if name not in SUBSYSTEMS:
        known = ", ".join(sorted(SUBSYSTEMS))
        raise UnknownSubsystem(f"unknown benchmark subsystem {name!r}; known subsystems: {known}")
    return importlib.import_module(SUBSYSTEMS[name])


def machine_info() -> Dict[str, Any]:
    """Where a benchmark ran: platform, CPU, Python/NumPy/weft versions and the Vulkan device."""
    import numpy as np

    info: Dict[str, Any] = {
        "platform": platform.platform(),
        "machine": platform.machine(),
        "processor": platform.processor() or _cpu_model(),
        "cpu_count": os.cpu_count(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "time_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
    }
    try:
        import weft

        info["weft"] = weft.__version__
        selected = [d for d in weft.devices() if d.get("selected")]
        if selected:
            dev = selected[0]
            info["device"] = {k: dev.get(k) for k in ("name", "type", "api_version", "driver")}
        info["validation"] = bool(weft.validation_enabled())
    except Exception as exc:  # the report still says where it ran
        info["device_error"] = str(exc)
    return info


def _cpu_model() -> str:
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.lower().startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return ""


# The shared progress bar and Markdown table (weft.reporting), importable from here as before.
Progress = _reporting.Progress
markdown_table = _reporting.markdown_table
save_figure = _reporting.save_figure


def json_safe(value: Any) -> Any:
    """``value`` with non-finite floats replaced by None (JSON has no NaN/inf) and NumPy
    scalars/arrays turned into Python numbers/lists."""
    if isinstance(value, dict):
        return {str(k): json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(v) for v in value]
    if hasattr(value, "tolist"):
        return json_safe(value.tolist())
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def write_report(out_dir: str, data: Dict[str, Any], markdown: str) -> List[str]:
    """Writes ``bench.json`` and ``bench.md`` into ``out_dir``; returns their paths."""
    data = json_safe(data)
    os.makedirs(out_dir, exist_ok=True)
    json_path = os.path.join(out_dir, "bench.json")
    md_path = os.path.join(out_dir, "bench.md")
    with open(json_path, "w", encoding="utf-8") as f:
        json.dump(data, f, indent=2, allow_nan=False)
        f.write("\n")
    with open(md_path, "w", encoding="utf-8") as f:
        f.write(markdown.rstrip("\n") + "\n")
    return [json_path, md_path]


def _top_parser() -> argparse.ArgumentParser:
    lines = [f"  {name:<10} {getattr(load_subsystem(name), 'DESCRIPTION', '')}"
             for name in sorted(SUBSYSTEMS)]
    return argparse.ArgumentParser(
        prog="python -m weft.bench",
        description="Run a weft benchmark: time and error against a reference, written as "
                    "JSON + Markdown.",
        epilog="subsystems:\n" + "\n".join(lines)
               + "\n\nRun 'python -m weft.bench <subsystem> --help' for its options.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Entry point of ``python -m weft.bench``."""
    args = list(sys.argv[1:] if argv is None else argv)
    if not args or args[0] in ("-h", "--help"):
        parser = _top_parser()
        parser.add_argument("subsystem", choices=sorted(SUBSYSTEMS), help="what to benchmark")
        if not args:
            parser.print_usage(sys.stderr)
            print("python -m weft.bench: error: a subsystem is required; known subsystems: "
                  + ", ".join(sorted(SUBSYSTEMS)), file=sys.stderr)
            return 2
        parser.print_help()
        return 0
    name, rest = args[0], args[1:]
    try:
        module = load_subsystem(name)
    except UnknownSubsystem as exc:
        print(f"python -m weft.bench: error: {exc}", file=sys.stderr)
        return 2
    parser = argparse.ArgumentParser(prog=f"python -m weft.bench {name}",
                                     description=getattr(module, "DESCRIPTION", None))
    module.add_arguments(parser)
    return int(module.run(parser.parse_args(rest)))
