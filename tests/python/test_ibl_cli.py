"""``python -m weft ibl ...`` on small files written by the test."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import ibl_envs as envs
import weft.ibl as ibl
from weft.__main__ import main


def equirect_of(env, width: int = 128) -> np.ndarray:
    h = width // 2
    theta = np.pi * (np.arange(h) + 0.5) / h
    phi = 2 * np.pi * ((np.arange(width) + 0.5) / width - 0.5)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    d = np.stack([np.sin(t) * np.sin(p), np.cos(t), -np.sin(t) * np.cos(p)], -1).reshape(-1, 3)
    return env(d).reshape(h, width, 3).astype(np.float32)


def test_convert_irradiance_and_lights(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    sun = (0.4, 0.7, -0.6)
    src = tmp_path / "env.npy"
    np.save(src, equirect_of(envs.sun_disc(sun, np.radians(4), 2e3, envs.sky_gradient()), 256))
    faces = tmp_path / "faces.npy"
    assert main(["ibl", "convert", str(src), str(faces), "--as", "faces", "--cube-size", "32"]) == 0
    got = np.load(faces)
    want = np.asarray(ibl.equirect_to_cube(np.load(src), 32).faces)
    np.testing.assert_allclose(got, want, rtol=1e-6)
    cross = tmp_path / "cross.npy"
    assert main(["ibl", "convert", str(faces), str(cross)]) == 0
    assert np.load(cross).shape == (96, 128, 3)
    capsys.readouterr()
    assert main(["ibl", "irradiance", str(cross), "--method", "sh9", "--cube-size", "32"]) == 0
    out = capsys.readouterr().out
    assert "L00" in out and "L22" in out
    assert main(["ibl", "extract-lights", str(src), "--json", "--cube-size", "64"]) == 0
    lights = json.loads(capsys.readouterr().out)
    d = np.asarray(lights[0]["direction"])
    s = np.asarray(sun) / np.linalg.norm(sun)
    assert np.degrees(np.arccos(np.clip(d @ s, -1, 1))) < 2.0


def test_cli_errors_are_reported(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    assert main(["ibl", "convert", str(tmp_path / "missing.npy"), str(tmp_path / "o.npy")]) == 1
    assert "missing.npy" in capsys.readouterr().err
    odd = tmp_path / "odd.npy"
    np.save(odd, np.ones((10, 30, 3), np.float32))
    assert main(["ibl", "irradiance", str(odd)]) == 1
    assert "--source" in capsys.readouterr().err
