"""The package's declared dependencies match what the code imports and what
scripts/install-deps.sh installs, and `pip install .` put `weft-demo` on PATH."""

from __future__ import annotations

import os
import re
import subprocess
import sysconfig
from pathlib import Path

import pytest

tomllib = pytest.importorskip("tomllib")  # Python 3.11+

ROOT = Path(__file__).resolve().parents[3]


def _project() -> dict:
    with open(ROOT / "pyproject.toml", "rb") as f:
        return tomllib.load(f)["project"]


def _name(requirement: str) -> str:
    return re.split(r"[<>=!~\[ ;]", requirement, maxsplit=1)[0].lower()


def test_required_dependencies_are_the_core_features_libraries():
    names = {_name(r) for r in _project()["dependencies"]}
    assert names == {"numpy", "matplotlib", "tqdm"}


def test_extras_have_the_names_a_user_guesses():
    extras = _project()["optional-dependencies"]
    assert {"video", "peers", "reference", "batch", "test", "all"} <= set(extras)
    assert {_name(r) for r in extras["video"]} == {"av"}
    assert {_name(r) for r in extras["peers"]} == {"warp-lang"}
    assert {_name(r) for r in extras["reference"]} == {"mitsuba", "flip-evaluator"}
    # [all] names every other extra, so it cannot fall behind one added later
    (all_req,) = extras["all"]
    inner = set(re.search(r"\[(.*)\]", all_req).group(1).split(","))
    assert inner == set(extras) - {"all"}


def test_install_deps_installs_what_pyproject_declares():
    """Every required dependency and every package of the [test] extra (less the extras it
    names) is in install-deps.sh's pip line with the same version bound."""
    script = (ROOT / "scripts" / "install-deps.sh").read_text()
    pip_specs = set(re.findall(r'"([A-Za-z0-9_.\-]+[<>=!~]=?[^"]*)"', script))
    project = _project()
    wanted = [r for r in project["dependencies"] + project["optional-dependencies"]["test"]
              if not r.startswith("weft[")]
    for extra in ("video", "reference", "batch"):
        wanted += project["optional-dependencies"][extra]
    missing = [r for r in wanted if r not in pip_specs]
    assert not missing, f"install-deps.sh does not install {missing}"


def test_weft_demo_is_on_path_next_to_python():
    exe = Path(sysconfig.get_path("scripts")) / "weft-demo"
    if not exe.exists():
        pytest.skip("weft was not installed with pip into this environment")
    out = subprocess.run([str(exe), "--help"], capture_output=True, text=True, timeout=60,
                         env=dict(os.environ, PATH=f"{exe.parent}{os.pathsep}"
                                                   f"{os.environ.get('PATH', '')}"))
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("usage: weft-demo")
    assert "--environment" in out.stdout and "--stats" in out.stdout
