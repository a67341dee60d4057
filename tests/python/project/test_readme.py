"""The README's Python snippets run, top to bottom in one namespace as a reader would run them,
with the inputs the README leaves to the reader (small synthetic arrays and files in a temporary
folder) supplied by a prelude per block; and a type checker reading weft's stubs accepts them. So
the README cannot drift from the package (issue 14)."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
README = ROOT / "README.md"

#: Inputs a README block uses but does not make, keyed by a line of the block (the first line
#: that matches names the block). Each prelude runs just before its block.
PRELUDES = {
    "scene = weft.Scene()": """
        import os
        os.makedirs("out", exist_ok=True)           # where the README writes its files
    """,
    "hair = weft.load_hair(": """
        weft.save_hair("model.hair", weft.generate_hair(200, 2000, style="wavy"))
        eye = np.array([0.0, 2.0, 4.0], np.float32)
        rng = np.random.default_rng(1)
        t, l, v = (rng.normal(size=(8, 3)).astype(np.float32) for _ in range(3))
        strand_ids = np.arange(8, dtype=np.uint32)
    """,
    "transform=None, cast_shadows=True": """
        mesh = weft.Mesh.uv_sphere(0.5, 32, 16)      # the cloth block's `mesh` holds arrays
        transform = np.eye(4, dtype=np.float32)
        cam = camera
    """,
    "scene.add_light(weft.PointLight(": """
        pattern = np.full((32, 32, 4), 255, np.uint8)
        pattern[8:24, 8:24, :3] = 40
        nmap = np.zeros((32, 32, 4), np.uint8)
        nmap[...] = (128, 128, 255, 255)
        specular = np.full((32, 32, 4), 128, np.uint8)
        os.makedirs("my/glsl", exist_ok=True)
    """,
    "import weft.ibl as ibl": """
        yy, xx = np.mgrid[0:64, 0:64] / 63.0
        sphere_map = np.stack([0.2 + xx, 0.3 + yy, 0.8 + 0 * xx], -1).astype(np.float32)
    """,
}

#: What a block's comments claim, checked after it ran (same keys as PRELUDES).
CHECKS = {
    "scene = weft.Scene()": """
        assert image.shape == (480, 640, 4) and image.dtype == np.uint8
        assert {"position", "normal", "uv", "shadow"} <= set(debug)
        assert "forward" in [p["name"] for p in renderer.stats["passes"]]
    """,
    "cloth = weft.Cloth(": """
        assert steps == 2                                # 60 Hz for 1/30 s
        assert {"positions", "normals", "uvs", "tangents", "indices"} <= set(mesh)
    """,
    "import weft.ibl as ibl": """
        assert np.shape(sh) == (9, 3)
    """,
}

#: Runs the blocks in a fresh process (a snippet sets process-wide state, e.g. the shader
#: directory): each block compiled under its README line, so a traceback names that line.
RUNNER = """
import json, sys, textwrap
blocks = json.load(open(sys.argv[1]))
namespace = {"__name__": "__readme__"}
for block in blocks:
    for name, source in (("prelude", block["prelude"]), ("README.md", block["code"]),
                         ("check", block["check"])):
        if source.strip():
            exec(compile("\\n" * (block["line"] - 1) + source, name, "exec"), namespace)
    print("ran README block at line", block["line"], flush=True)
"""


def python_blocks() -> list[tuple[int, str]]:
    """(line of the first code line, code) of every ```python block."""
    blocks, lines = [], README.read_text(encoding="utf-8").splitlines()
    i = 0
    while i < len(lines):
        if lines[i].strip() == "```python":
            start = i + 1
            end = next(j for j in range(start, len(lines)) if lines[j].strip() == "```")
            blocks.append((start + 1, "\n".join(lines[start:end]) + "\n"))
            i = end
        i += 1
    return blocks


def with_preludes() -> list[dict]:
    blocks = python_blocks()
    used = set()
    out = []
    for line, code in blocks:
        keys = [k for k in set(PRELUDES) | set(CHECKS) if k in code]
        used.update(keys)
        prelude = "".join(textwrap.dedent(PRELUDES.get(k, "")) for k in keys)
        check = "".join(textwrap.dedent(CHECKS.get(k, "")) for k in keys)
        out.append({"line": line, "code": code, "prelude": prelude, "check": check})
    stale = (set(PRELUDES) | set(CHECKS)) - used
    assert not stale, f"preludes or checks for blocks the README no longer has: {stale}"
    return out


def test_the_readme_has_python_blocks() -> None:
    blocks = python_blocks()
    assert len(blocks) >= 8
    assert all("weft" in code for _, code in blocks)


def test_every_python_block_runs(tmp_path: Path) -> None:
    blocks = with_preludes()
    spec = tmp_path / "blocks.json"
    spec.write_text(json.dumps(blocks))
    runner = tmp_path / "run_readme.py"
    runner.write_text(RUNNER)
    work = tmp_path / "work"
    work.mkdir()
    run = subprocess.run([sys.executable, str(runner), str(spec)], cwd=work, capture_output=True,
                         text=True, timeout=1500)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-6000:]
    ran = re.findall(r"ran README block at line (\d+)", run.stdout)
    assert [int(n) for n in ran] == [b["line"] for b in blocks]
    # what the blocks say they write
    assert (work / "out" / "scene.png").stat().st_size > 0
    assert (work / "out" / "fur.hair").stat().st_size > 0
    assert (work / "out" / "cord-material").is_dir()


def test_mypy_accepts_the_readme_blocks(tmp_path: Path) -> None:
    pytest.importorskip("mypy")
    parts = ["import numpy as np\nimport weft\nimport os\n"]
    for block in with_preludes():
        parts.append(f"# ---- README.md line {block['line']}\n{block['prelude']}{block['code']}"
                     f"{block['check']}")
    script = tmp_path / "readme_blocks.py"
    script.write_text("\n".join(parts), encoding="utf-8")
    env = dict(os.environ, MYPYPATH=str(ROOT / "python"))
    run = subprocess.run([sys.executable, "-m", "mypy", "--no-incremental",
                          "--follow-imports=silent", "--allow-redefinition",
                          "--cache-dir", str(tmp_path / "cache"),
                          str(script)], capture_output=True, text=True, timeout=600, cwd=tmp_path,
                         env=env)
    assert run.returncode == 0, run.stdout + run.stderr
