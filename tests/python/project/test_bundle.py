"""The portable builds of issue 19, made from the existing build (no second C++ build):

- scripts/bundle.sh --wheel: the self-contained wheel installs into a fresh virtual environment,
  loads its own copies of the Debian libraries (weft.libs/) and the system's Vulkan loader, and
  renders the same pixels as the weft this suite tests;
- the native bundle (tarball) is relocatable: unpacked elsewhere, every library its programs
  load is its own except glibc's, the C++ runtime and the Vulkan loader; its gpu-check.sh runs
  the C++ tests and weft-bench (--quick, validation on) with LD_LIBRARY_PATH cleared, and says
  plainly when there is no GPU.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import tarfile
from pathlib import Path

import numpy as np
import pytest
import weft

ROOT = Path(__file__).resolve().parents[3]
BUILD = ROOT / "build" / "py"
# What the bundle leaves to the system (scripts/bundle.sh): glibc, the C++ runtime, the loader.
SYSTEM_LIB = re.compile(r"^(linux-vdso|ld-linux|libc|libm|libdl|libpthread|librt|libutil|"
                        r"libresolv|libnsl|libstdc\+\+|libgcc_s|libvulkan)\.so")

pytestmark = [
    pytest.mark.slow,  # builds the bundle and a wheel, installs it into a fresh venv
    pytest.mark.skipif(
        not (BUILD / "cpp" / "weft-bench").exists()
        or not (BUILD / "tests" / "weft_tests").exists(),
        reason="needs scripts/build.sh's build/py (weft-bench and the C++ tests)"),
]


def _env(**extra: str) -> dict:
    env = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}
    env.update(extra)
    return env


@pytest.fixture(scope="module")
def dist(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("dist")
    run = subprocess.run(["bash", str(ROOT / "scripts" / "bundle.sh"), "--out", str(out),
                          "--wheel"], cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert run.returncode == 0, run.stdout + run.stderr
    return out


@pytest.fixture(scope="module")
def bundle(dist: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The tarball unpacked somewhere else than where it was staged."""
    (tarball,) = dist.glob("weft-*-linux-*.tar.gz")
    where = tmp_path_factory.mktemp("unpacked")
    with tarfile.open(tarball) as t:
        t.extractall(where)
    (top,) = where.iterdir()
    return top


def test_wheel_renders_in_a_fresh_venv(dist: Path, tmp_path: Path) -> None:
    (wheel,) = dist.glob("weft-*manylinux*.whl")
    venv = tmp_path / "venv"
    # numpy and matplotlib come from the surrounding site-packages; weft must be the wheel's.
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    py = venv / "bin" / "python"
    subprocess.run([str(py), "-m", "pip", "install", "-q", "--no-deps", "--ignore-installed",
                    "--no-index", str(wheel)], check=True, capture_output=True)
    script = (
        "import json, numpy as np, weft\n"
        "scene, camera = weft.default_scene()\n"
        "img = weft.Renderer(96, 72, shadow_map_size=512).render(scene, camera)\n"
        "np.save('frame.npy', img)\n"
        "maps = sorted({l.split()[-1] for l in open('/proc/self/maps') if '.so' in l})\n"
        "print(json.dumps({'file': weft.__file__, 'maps': maps,\n"
        "                  'validation': list(weft.validation_messages())}))\n")
    run = subprocess.run([str(py), "-c", script], cwd=tmp_path, capture_output=True, text=True,
                         env=_env(WEFT_VALIDATION="1"), timeout=300)
    assert run.returncode == 0, run.stderr
    info = json.loads(run.stdout.strip().splitlines()[-1])
    assert info["file"].startswith(str(venv)), info["file"]
    assert info["validation"] == []
    libs = str(venv / "lib")
    for name in ("libpng16", "libOpenEXR", "libglfw"):
        hits = [m for m in info["maps"] if os.path.basename(m).startswith(name)]
        assert hits and all(h.startswith(libs) and "weft.libs" in h for h in hits), (name, hits)
    loader = [m for m in info["maps"] if os.path.basename(m).startswith("libvulkan.so")]
    assert loader and not any(m.startswith(libs) for m in loader), loader
    # Same code, same device: the wheel's frame equals the one the tested weft renders.
    scene, camera = weft.default_scene()
    want = weft.Renderer(96, 72, shadow_map_size=512).render(scene, camera)
    got = np.load(tmp_path / "frame.npy")
    assert got.shape == want.shape and np.array_equal(got, want)


def test_bundle_is_relocatable(bundle: Path) -> None:
    programs = sorted((bundle / "bin").iterdir())
    assert {p.name for p in programs} == {"weft-bench", "weft-demo", "weft_tests"}
    ldd = subprocess.run(["ldd", *map(str, programs)], capture_output=True, text=True,
                         env=_env(), check=True).stdout
    resolved = re.findall(r"^\s*(\S+) => (\S+)", ldd, re.M)
    assert len(resolved) > 30  # Debian's libraries (OpenEXR, GLFW, Ceres ...) and the system's
    for soname, path in resolved:
        assert path != "not", f"{soname} is not found"
        path = os.path.realpath(path)
        if SYSTEM_LIB.match(soname):
            assert not path.startswith(os.path.realpath(bundle)), (soname, path)
        else:
            assert path.startswith(os.path.realpath(bundle / "lib")), (soname, path)
    assert (bundle / "lib" / "fallback" / "libvulkan.so.1").exists()
    run = subprocess.run([str(bundle / "bin" / "weft-demo"), "--width", "nope"],
                         capture_output=True, text=True, env=_env())
    # the relocated binary runs far enough to parse its options (CLI11: exit 2, the option named)
    assert run.returncode == 2 and "--width" in run.stderr, (run.returncode, run.stderr)


def _has_gpu() -> bool:
    return any(d["type"] in ("discrete", "integrated", "virtual") for d in weft.devices())


def test_gpu_check_from_the_bundle(bundle: Path, tmp_path: Path) -> None:
    out = tmp_path / "check"
    run = subprocess.run(["bash", str(bundle / "gpu-check.sh"), "--allow-cpu", "--quick",
                          "--out", str(out)], cwd=tmp_path, capture_output=True, text=True,
                         env=_env(), timeout=900)
    assert run.returncode == 0, run.stdout + run.stderr
    report = json.loads((out / "gpu-check.json").read_text())
    assert report["status"] == "passed"
    assert report["gpu"] == _has_gpu()
    assert report["validation"].startswith("on")
    assert report["tests"]["passed"] >= 50 and report["tests"]["failed"] == 0
    bench = json.loads((out / "bench" / "bench.json").read_text())
    assert bench["validation"]["enabled"] and bench["validation"]["messages"] == []
    sets = [r["set"] for r in bench["rows"]]
    assert sets.count("demo") == 1 and sets.count("hair") == 6 and sets.count("dome") == 4
    assert all(r["wall_ms"] > 0 for r in bench["rows"])
    assert all(r["passes_gpu_ms"] for r in bench["rows"])
    md = (out / "gpu-check.md").read_text()
    assert bench["device"]["name"] in md
    if not report["gpu"]:
        assert "No GPU on this machine" in md


@pytest.mark.skipif(_has_gpu(), reason="this machine has a GPU")
def test_gpu_check_says_no_gpu(bundle: Path, tmp_path: Path) -> None:
    run = subprocess.run(["bash", str(bundle / "gpu-check.sh"), "--quick", "--out",
                          str(tmp_path / "none")], capture_output=True, text=True, env=_env(),
                         timeout=120)
    assert run.returncode == 2
    assert "NO GPU" in run.stderr and "--allow-cpu" in run.stderr
    assert not (tmp_path / "none" / "bench").exists()


def test_gpu_pytest_runs_the_tests_on_the_wheel(dist: Path, bundle: Path, tmp_path: Path) -> None:
    """scripts/gpu-pytest.sh (the Python tests on a GPU machine) here on lavapipe: the wheel is
    the weft the tests import, the selected test passes, the report is written."""
    (wheel,) = dist.glob("weft-*.whl")
    script = str(ROOT / "scripts" / "gpu-pytest.sh")
    out = tmp_path / "out"
    run = subprocess.run(["bash", script, "--bundle", str(bundle), "--wheel", str(wheel),
                          "--out", str(out), "--workers", "1",
                          "--tests", "tests/python/render/test_bounce_light.py",
                          "--", "-k", "unoccluded"],
                         cwd=ROOT, capture_output=True, text=True, env=_env(), timeout=600)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "weft-gpu-pytest" in run.stdout  # imported from the wheel's scratch folder
    assert "1 passed" in run.stdout, run.stdout
    assert 'tests="1"' in (out / "pytest.xml").read_text()
    bad = subprocess.run(["bash", script, "--bundle", str(bundle), "--wheel",
                          str(tmp_path / "none.whl")], cwd=ROOT, capture_output=True, text=True,
                         env=_env(), timeout=60)
    assert bad.returncode == 2 and "no wheel" in bad.stderr
