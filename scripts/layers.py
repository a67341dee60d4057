#!/usr/bin/env python3
"""The #include graph of cpp/ by subsystem, checked against the allowed layers.

    python3 scripts/layers.py        # edges between subsystems with their counts; exit 1 on a
                                     # back-edge (an include that the layers do not allow)
    python3 scripts/layers.py -v     # and every #include behind each edge

A subsystem is a folder of cpp/src/ (one OBJECT library each, cpp/CMakeLists.txt). A public
header include/weft/X.h belongs to the subsystem whose weft_subsystem(... HEADERS X) names it.
The allowed graph is ALLOWED below; the build declares the same one (DEPENDS), and
tests/python/project/test_layers.py checks that both agree and that no #include leaves it. See
docs/design/ARCHITECTURE.md, "Layers".
"""
from __future__ import annotations

import collections
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent

# Direct dependencies; a subsystem may include its own headers and those of everything below it.
ALLOWED = {
    "core": set(),
    "vk": {"core"},
    "sim": {"core"},
    "ibl": {"core"},
    "btf": {"core"},
    "hair": {"core"},
    "scene": {"core", "ibl", "btf", "hair"},
    "render": {"vk", "scene"},
    "app": {"render", "sim"},
}
# The GPU structs shared with GLSL (glsl/common/*.h): the renderer's.
GLSL_SHARED = {"render"}
# Private headers the top level may read: peers bound for tests and benchmarks only.
TOP_PRIVATE = {
    "bindings": {"sim/cloth/NaturalGsPeer.h", "btf/BtfImageCodec.h"},
    # the demo's panel (cpp/apps/demo, linked into weft-demo only, so the library links no UI)
    # adds a pass after tone mapping and draws into the swapchain
    "apps": {"render/FrameGraph.h", "render/FramePasses.h", "render/RenderTargets.h",
             "render/FrameOverlay.h", "vk/Context.h", "vk/WindowNative.h", "vk/Vk.h",
             "app/DemoSettings.h", "app/DemoPanel.h"},
}

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)
SUBSYSTEM_CALL = re.compile(r"weft_subsystem\(([^)]*)\)", re.S)


def closure(name: str, graph: dict[str, set[str]] = ALLOWED) -> set[str]:
    """`name` and every subsystem below it."""
    seen, todo = set(), [name]
    while todo:
        n = todo.pop()
        if n not in seen:
            seen.add(n)
            todo.extend(graph[n])
    return seen


def declared_subsystems(cmake: pathlib.Path = ROOT / "cpp" / "CMakeLists.txt"):
    """{name: (DEPENDS, HEADERS)} from the weft_subsystem() calls of the build."""
    out = {}
    for call in SUBSYSTEM_CALL.findall(cmake.read_text()):
        words = call.split()
        name, key, lists = words[0], None, {"DEPENDS": [], "HEADERS": []}
        for w in words[1:]:
            if w.isupper() and w.replace("_", "").isalpha():
                key = w
            elif key in lists:
                lists[key].append(w)
        out[name] = (set(lists["DEPENDS"]), lists["HEADERS"])
    return out


def header_owners(declared) -> dict[str, str]:
    return {f"{h}.h": name for name, (_, headers) in declared.items() for h in headers}


def owner_of(path: pathlib.Path, owners: dict[str, str]) -> str | None:
    rel = path.relative_to(ROOT).parts
    if rel[:2] == ("cpp", "src"):
        return rel[2]
    if rel[:3] == ("cpp", "include", "weft"):
        return owners.get(rel[3], "?")
    if rel[:2] == ("cpp", "bindings"):
        return "bindings"
    if rel[:2] == ("cpp", "apps"):
        return "apps"
    return None


def target_of(kind: str, name: str, includer: pathlib.Path, owners: dict[str, str]):
    """(subsystem, private?) an #include names, or None for a system/third-party header."""
    if name.startswith("weft/"):
        return owners.get(name[5:], "?"), False
    if kind == '"':
        if ".." in pathlib.PurePosixPath(name).parts:
            return "..", True  # a path around the include directories: never allowed
        first = name.split("/")[0]
        if "/" in name and first in ALLOWED:
            return first, True
        if (includer.parent / name).exists():
            return None, False  # beside the includer: its own subsystem
        if (ROOT / "glsl" / "common" / name).exists():
            return "glsl", True
    return None, False


def violations_of(source: str, subsystem: str, includer: pathlib.Path, owners) -> list[str]:
    """The #includes of `source` (a file of `subsystem`) that the layers do not allow."""
    bad = []
    for kind, name in INCLUDE.findall(source):
        target, private = target_of(kind, name, includer, owners)
        if target is None or target == subsystem:
            continue
        if subsystem in TOP_PRIVATE:
            ok = not private or name in TOP_PRIVATE[subsystem]
        elif target == "glsl":
            ok = subsystem in GLSL_SHARED
        else:
            ok = target in closure(subsystem)
        if not ok:
            bad.append(f"{includer.relative_to(ROOT)}: {subsystem} -> {target} ({name})")
    return bad


def sources():
    for folder in ("src", "include", "bindings", "apps"):
        for p in sorted((ROOT / "cpp" / folder).rglob("*")):
            if p.suffix in (".h", ".hpp", ".cpp"):
                yield p


def scan():
    """(edges {(from, to): [include lines]}, violations, unowned public headers)."""
    owners = header_owners(declared_subsystems())
    edges, bad, unowned = collections.defaultdict(list), [], []
    for path in sources():
        sub = owner_of(path, owners)
        if sub == "?":
            unowned.append(str(path.relative_to(ROOT)))
            continue
        text = path.read_text(errors="replace")
        for kind, name in INCLUDE.findall(text):
            target, _ = target_of(kind, name, path, owners)
            if target is not None and target != sub:
                edges[(sub, target)].append(f"{path.relative_to(ROOT)} -> {name}")
        bad += violations_of(text, sub, path, owners)
    return edges, bad, unowned


def main(argv: list[str]) -> int:
    edges, bad, unowned = scan()
    for (a, b), lines in sorted(edges.items()):
        print(f"{a:>8} -> {b:<8} {len(lines):3d}")
        if "-v" in argv:
            for line in lines:
                print(f"           {line}")
    for u in unowned:
        print(f"no subsystem: {u} (name it in a weft_subsystem HEADERS list)")
    for b in bad:
        print(f"back-edge: {b}")
    return 1 if bad or unowned else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
