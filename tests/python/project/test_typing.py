"""Typed Python: the committed stubs of weft._core are what the compiled module generates today,
and a type checker reading them accepts a correct user script and rejects wrong calls."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
STUB = ROOT / "python" / "weft" / "_core.pyi"


def test_package_is_marked_typed():
    assert (ROOT / "python" / "weft" / "py.typed").exists()
    assert STUB.exists()


def test_stubs_regenerate_without_a_difference(tmp_path):
    pytest.importorskip("pybind11_stubgen")
    out = tmp_path / "_core.pyi"
    run = subprocess.run([sys.executable, str(ROOT / "scripts" / "gen_stubs.py"), "--out",
                          str(out)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    fresh = out.read_text(encoding="utf-8").splitlines()
    committed = STUB.read_text(encoding="utf-8").splitlines()
    if fresh != committed:
        import difflib
        diff = "\n".join(list(difflib.unified_diff(committed, fresh, "committed", "generated",
                                                   lineterm=""))[:40])
        pytest.fail("python/weft/_core.pyi is stale; run python scripts/gen_stubs.py\n" + diff)


def test_stubs_name_no_cpp_types_and_cover_the_module():
    import weft._core as core

    text = STUB.read_text(encoding="utf-8")
    assert "::" not in text.replace("# Generated", "")
    for name in dir(core):
        if not name.startswith("_"):
            assert (f"def {name}(" in text or f"class {name}" in text
                    or f"import {name}" in text), name


GOOD = """
    import numpy as np
    import weft

    mesh = weft.Mesh.plane(2.0, 2.0, segments_x=4)
    count: int = mesh.vertex_count
    scene = weft.Scene()
    material = weft.Material(kd=(0.8, 0.2, 0.2), shininess=16.0, texture=None)
    mesh_id: int = scene.add_mesh(mesh, material)
    scene.add_light(weft.DirectionalLight(direction=(0, -1, 0)))
    image: np.ndarray = weft.Renderer(64, 48).render(scene, weft.Camera())
"""

BAD = """
    import weft

    mesh = weft.Mesh.plane(size_x="two")
    count: str = weft.Mesh.box().vertex_count
    weft.Renderer(64, 48).render(weft.Scene(), weft.Camera(), bogus=1)
"""


def _mypy(tmp_path: Path, source: str) -> subprocess.CompletedProcess:
    pytest.importorskip("mypy")
    script = tmp_path / "user.py"
    script.write_text(textwrap.dedent(source), encoding="utf-8")
    # The repository's package and stubs (not whatever weft is installed); errors inside weft's
    # own modules are not the user's and are silenced.
    env = dict(os.environ, MYPYPATH=str(ROOT / "python"))
    return subprocess.run([sys.executable, "-m", "mypy", "--no-incremental",
                           "--follow-imports=silent", "--cache-dir", str(tmp_path / "cache"),
                           str(script)], capture_output=True, text=True, timeout=300,
                          cwd=tmp_path, env=env)


def test_mypy_accepts_a_correct_user_script(tmp_path):
    run = _mypy(tmp_path, GOOD)
    assert run.returncode == 0, run.stdout + run.stderr


def test_mypy_rejects_wrong_calls(tmp_path):
    run = _mypy(tmp_path, BAD)
    assert run.returncode == 1, run.stdout + run.stderr
    out = run.stdout
    assert 'Argument "size_x" to "plane" of "Mesh" has incompatible type "str"' in out
    assert "user.py:5: error: Incompatible types in assignment" in out
    assert 'Unexpected keyword argument "bogus" for "render" of "Renderer"' in out


def _description(doc: str, name: str) -> str:
    """A pybind11 docstring less its signature lines: what a reader learns beyond the types."""
    lines = [line for line in (doc or "").splitlines()
             if not (line.strip().startswith(name + "(") or line.strip() == "Overloaded function."
                     or re.match(r"^\d+\. " + re.escape(name) + r"\(", line.strip()))]
    return "\n".join(lines).strip()


def _public_callables():
    import weft._core as core

    for name in dir(core):
        if name.startswith("_"):
            continue
        obj = getattr(core, name)
        if isinstance(obj, type):
            if issubclass(obj, BaseException):
                continue
            yield f"{name}", obj.__doc__, name
            for attr, value in vars(obj).items():
                if attr.startswith("_") and attr != "__init__":
                    continue
                func = value.__func__ if isinstance(value, staticmethod) else value
                if callable(func) and not isinstance(value, property):
                    yield f"{name}.{attr}", getattr(func, "__doc__", None), attr
        elif callable(obj):
            yield name, obj.__doc__, name


def test_every_public_compiled_callable_has_a_docstring():
    found = list(_public_callables())
    assert len(found) > 150
    missing = [label for label, doc, name in found if not _description(doc, name)]
    assert not missing, f"compiled callables without a docstring: {missing}"
