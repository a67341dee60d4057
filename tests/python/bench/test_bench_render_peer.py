"""The Filament peer of ``python -m weft.bench render`` (weft.bench.render_peer, issue 19).

Without open3d the benchmark reports the peer as skipped, with the reason, and succeeds; with
open3d (the optional extra weft[filament]) a tiny peer run times both renderers and Filament
draws the scene. The open3d run is a child process: Open3D keeps one Filament engine per
process, and a driver failure there must not take the test session with it.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import weft
from weft.bench import main as bench_main
from weft.bench import render_peer

pytestmark = pytest.mark.slow  # a benchmark run (pyproject.toml: markers)

TIMEOUT_S = 300


def test_roughness_conversion() -> None:
    # alpha^2 = 2 / (s + 2), roughness = sqrt(alpha): s = 0 is fully rough, sharper lobes
    # are smoother, and the default scene's exponents land in between
    assert render_peer.shininess_to_roughness(0.0) == pytest.approx(1.0)
    assert render_peer.shininess_to_roughness(16.0) == pytest.approx((2.0 / 18.0) ** 0.25)
    values = [render_peer.shininess_to_roughness(s) for s in (1.0, 16.0, 48.0, 1000.0)]
    assert values == sorted(values, reverse=True)
    with pytest.raises(ValueError):
        render_peer.shininess_to_roughness(-1.0)


def test_export_matches_default_scene() -> None:
    scene, camera = weft.default_scene()
    exported = render_peer.export_scene(scene, camera)
    assert len(exported["meshes"]) == scene.instance_count == 3
    ground, sphere, box = exported["meshes"]
    assert ground["texture"] is not None and ground["texture"].shape[2] in (3, 4)
    assert sphere["texture"] is None
    np.testing.assert_allclose(sphere["base_color"], (0.75, 0.18, 0.15), atol=1e-6)
    np.testing.assert_allclose(sphere["transform"][:3, 3], (-0.9, 0.75, 0.0), atol=1e-6)
    for mesh in exported["meshes"]:
        n = len(mesh["positions"])
        assert mesh["normals"].shape == (n, 3) and mesh["uvs"].shape == (n, 2)
        assert mesh["indices"].max() < n
    assert exported["sun"] is not None and exported["sun"]["shadows"]
    np.testing.assert_allclose(exported["camera"]["position"], (0.5, 2.6, 5.2), atol=1e-6)
    assert exported["camera"]["fov_y"] == pytest.approx(float(camera.fov_y))
    assert exported["unmatched"] == []
    # the sun in lux: the Lambertian estimate at Filament's default exposure, calibrated
    lux = render_peer.sun_illuminance(exported["sun"]["intensity"])
    assert lux == pytest.approx(0.9 * math.pi * 1.2 * 256 * 125 * render_peer.SUN_CALIBRATION)


def test_side_by_side_layout() -> None:
    a = np.zeros((10, 20, 4), np.uint8)
    b = np.full((12, 16, 3), 7, np.uint8)
    out = render_peer.side_by_side([(a, b), (a, b)], gap=2)
    assert out.shape == (2 * 12 + 2, 20 + 2 + 16, 3)
    assert (out[:10, :20] == 0).all() and (out[:12, 22:] == 7).all()
    assert (out[12:14] == 255).all()  # the gap between the rows


def test_peer_skipped_without_open3d(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                     capsys: pytest.CaptureFixture) -> None:
    monkeypatch.setitem(sys.modules, "open3d", None)  # `import open3d` raises ImportError
    out = tmp_path / "bench"
    assert bench_main(["render", "--quick", "--peer", "--peer-only", "--out", str(out)]) == 0
    data = json.loads((out / "bench.json").read_text())
    peer = data["peer"]
    assert peer["skipped"] is True
    assert "open3d does not import" in peer["note"] and "weft[filament]" in peer["note"]
    assert data["results"] == []  # --peer-only
    markdown = (out / "bench.md").read_text()
    assert "Filament" in markdown and "Skipped: open3d does not import" in markdown
    assert not (out / "peer.png").exists()
    assert "Skipped" in capsys.readouterr().out


def test_quick_skips_peer_unless_asked(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # --quick (CI) makes no Filament renderer unless --peer, whether open3d imports or not
    from weft.bench import render

    def no_peer(*args: object, **kwargs: object) -> dict:
        raise AssertionError("the peer ran under --quick without --peer")

    stub = {"width": 160, "height": 120, "shadow_map_size": 512, "frames": 1, "passes": [],
            "frame_cpu_ms": 1.0, "frame_gpu_ms": None, "pass_cpu_ms": {}, "pass_gpu_ms": {},
            "render_cpu_ms": 1.0, "render_wall_ms": 1.0, "render_defaults_wall_ms": 1.0,
            "device": "stub", "oracle": None, "oracle_error": "stub"}
    monkeypatch.setattr(render, "measure_peer", no_peer)
    monkeypatch.setattr(render, "measure_setting", lambda *a, **k: dict(stub))
    out = tmp_path / "bench"
    assert bench_main(["render", "--quick", "--out", str(out)]) == 0
    peer = json.loads((out / "bench.json").read_text())["peer"]
    assert peer["skipped"] is True and "--peer" in peer["note"]
    assert "Skipped: not asked for" in (out / "bench.md").read_text()
    # contradictory flags are a usage error
    assert bench_main(["render", "--peer-only", "--no-peer", "--out", str(out)]) == 2


def test_peer_tiny_run(tmp_path: Path) -> None:
    pytest.importorskip("open3d")
    out = tmp_path / "bench"
    env = dict(os.environ, WEFT_VALIDATION="1")
    proc = subprocess.run([sys.executable, "-m", "weft.bench", "render", "--quick", "--peer",
                           "--peer-only", "--out", str(out)], capture_output=True, text=True,
                          timeout=TIMEOUT_S, env=env)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    for marker in ("VUID-", "Validation Error"):
        assert marker not in proc.stdout + proc.stderr
    peer = json.loads((out / "bench.json").read_text())["peer"]
    assert peer["skipped"] is False, peer.get("note")
    assert (peer["width"], peer["height"], peer["frames"]) == (160, 120, 1)
    assert set(peer["modes"]) == {"defaults", "post_off"}
    for mode in peer["modes"].values():
        assert mode["filament_ms"] > 0.0 and mode["weft_ms"] > 0.0
        assert mode["ratio_weft_over_filament"] == pytest.approx(
            mode["weft_ms"] / mode["filament_ms"])
        assert mode["ratio_pairs_median"] > 0.0
        assert mode["filament_image_std"] > 5.0  # the scene, not a uniform clear colour
    assert peer["modes"]["defaults"]["filament_settings"]["msaa"] == 4
    assert peer["modes"]["post_off"]["weft_settings"]["msaa"] == 1
    assert peer["filament"]["backend"]  # Filament named its backend
    assert (out / "peer.png").is_file()
    assert "weft / Filament" in (out / "bench.md").read_text()
