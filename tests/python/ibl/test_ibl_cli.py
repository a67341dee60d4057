"""``python -m weft ibl ...`` on small files written by the test."""

from __future__ import annotations

import json
from pathlib import Path

import ibl_envs as envs
import numpy as np
import pytest
import weft
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


def test_hdr_and_exr_environments(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    eq = equirect_of(envs.sun_disc((0.2, 0.9, 0.3), np.radians(5), 50.0, envs.sky_gradient()), 128)
    hdr = tmp_path / "env.hdr"
    weft.save_hdr(str(hdr), eq)
    source = ibl.load_environment(str(hdr))  # RGBE-quantised
    assert source.shape == (64, 128, 3) and source.dtype == np.float32
    # RGBE keeps 8 bits per channel under the pixel's largest one's exponent: stb_image_write
    # truncates, stb_image decodes without a half step, so each channel is within one step
    step = np.ldexp(1.0, np.frexp(eq.max(axis=-1, keepdims=True))[1] - 8)
    assert np.all(source <= eq) and np.all(eq - source < step)
    out = tmp_path / "cube.exr"
    assert main(["ibl", "convert", str(hdr), str(out), "--cube-size", "16"]) == 0
    cross = ibl.load_environment(str(out))
    np.testing.assert_allclose(np.asarray(ibl.cross_to_cube(cross).faces),
                               np.asarray(ibl.equirect_to_cube(source, 16).faces), rtol=1e-6)
    capsys.readouterr()


def test_truncated_and_corrupt_files_raise_io_errors(tmp_path: Path,
                                                     capsys: pytest.CaptureFixture) -> None:
    eq = np.ones((16, 32, 3), np.float32)
    good = tmp_path / "good.hdr"
    weft.save_hdr(str(good), eq)
    data = good.read_bytes()
    truncated = tmp_path / "truncated.hdr"
    truncated.write_bytes(data[: len(data) // 2])
    corrupt = tmp_path / "corrupt.exr"
    corrupt.write_bytes(b"v/1\x01" + b"\x00garbage" * 10)
    for path in (truncated, corrupt):
        with pytest.raises(weft.IoError, match=path.name):
            ibl.load_environment(str(path))
        assert main(["ibl", "irradiance", str(path)]) == 1
        assert path.name in capsys.readouterr().err
    with pytest.raises(weft.InvalidArgument, match="cannot write"):
        ibl.save_environment(str(tmp_path / "x.tiff"), eq)
    (tmp_path / "x.tiff").write_bytes(b"II*\x00")
    with pytest.raises(weft.InvalidArgument, match="unsupported"):
        ibl.load_environment(str(tmp_path / "x.tiff"))


def test_exact_irradiance_on_the_gpu_from_the_cli(tmp_path: Path) -> None:
    faces = envs.to_faces(envs.random_smooth(2), 16)
    src = tmp_path / "faces.npy"
    np.save(src, faces)
    cpu, gpu = tmp_path / "cpu.npy", tmp_path / "gpu.npy"
    for method, out in (("exact", cpu), ("exact-gpu", gpu)):
        assert main(["ibl", "irradiance", str(src), str(out), "--method", method, "--size", "8",
                     "--as", "faces"]) == 0
    np.testing.assert_allclose(np.load(gpu), np.load(cpu), rtol=1e-4)
    assert np.load(cpu).shape == (6, 8, 8, 3)
