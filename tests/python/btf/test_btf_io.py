"""Bonn-layout reader and writer: round trips (folder, zip, PNG, JPEG, EXR, gamma) and rejection
of missing, duplicate, corrupt, truncated and mis-sized files with errors naming the file."""

from __future__ import annotations

import glob
import os
import shutil
from pathlib import Path

import numpy as np
import pytest
import weft
from weft import btf


@pytest.fixture(scope="module")
def small() -> "weft.BtfSamples":
    samples, _ = btf.synthesize("polyacrylic", 12, noise=0.01)
    return samples


def quantised(values: np.ndarray) -> np.ndarray:
    return np.rint(np.clip(values, 0, 1) * 255) / 255


def write_folder(tmp_path: Path, samples, **kw) -> Path:
    out = tmp_path / "btf"
    btf.write(str(out), samples, **kw)
    return out


def files_of(folder: Path) -> list:
    return sorted(glob.glob(str(folder / "UBO2003" / "MANYFILES" / "*" / "*")))


def test_parse_file_names_by_key() -> None:
    parse = weft._core.btf_parse_file_name
    assert parse("00084 tl015 pl000 tv015 pv120.jpg") == (15, 0, 15, 120)
    assert parse("WoolPKNT256_00084_tl015_pl000_tv015_pv120.jpg") == (15, 0, 15, 120)
    assert parse("x_pv120_tv015_pl060_tl030.png") == (30, 60, 15, 120)  # any order
    assert parse("00084 tl015 pl000 tv015.jpg") is None
    assert parse("00084 tl015 tl030 pl000 tv015 pv000.jpg") is None


def test_png_folder_round_trip_is_exact(tmp_path: Path, small) -> None:
    folder = write_folder(tmp_path, small, fmt="png")
    names = [os.path.basename(f) for f in files_of(folder)]
    assert len(names) == 81 and "00000 tl000 pl000 tv000 pv000.png" in names
    assert "00081 tl015 pl000 tv000 pv000.png" in names
    loaded = btf.load(str(folder))
    np.testing.assert_array_equal(loaded.angles, small.angles)
    np.testing.assert_allclose(loaded.values, quantised(small.values), atol=1e-7)


def test_zip_jpeg_round_trip_with_prefix(tmp_path: Path, small) -> None:
    path = tmp_path / "btf.zip"
    btf.write(str(path), small, fmt="jpg", quality=100, zip=True, prefix="PolyPKNT12")
    loaded = btf.load(str(path))
    assert loaded.count == 81
    err = np.abs(loaded.values - quantised(small.values))
    assert err.mean() < 2.5 / 255 and err.max() < 40 / 255


def test_linear_gamma_round_trip(tmp_path: Path, small) -> None:
    folder = write_folder(tmp_path, small, fmt="png", gamma="linear")
    raw = btf.load(str(folder), gamma="raw")
    lin = btf.load(str(folder), gamma="linear")
    encoded = quantised(np.clip(small.values, 0, 1) ** (1 / 2.2))
    # float32 pow in the writer may round a value at a quantisation boundary the other way
    np.testing.assert_allclose(raw.values, encoded, atol=1 / 255 + 1e-6)
    assert np.mean(np.abs(raw.values - encoded) > 1e-6) < 1e-3
    np.testing.assert_allclose(lin.values, np.clip(small.values, 0, 1), atol=0.01)
    with pytest.raises(ValueError):
        btf.load(str(folder), gamma="srgb")


def test_exr_samples_are_read_as_floats(tmp_path: Path, small) -> None:
    folder = write_folder(tmp_path, small, fmt="png")
    values = small.values
    for f in files_of(folder):
        angles = weft._core.btf_parse_file_name(os.path.basename(f))
        s = [i for i, a in enumerate(small.angles) if tuple(a) == angles][0]
        weft.save_exr(f[:-4] + ".exr", np.ascontiguousarray(values[s].transpose(1, 2, 0)))
        os.remove(f)
    loaded = btf.load(str(folder))
    np.testing.assert_allclose(loaded.values, values, rtol=1e-6)


def test_multiple_views(tmp_path: Path) -> None:
    samples, _ = btf.synthesize("wool", 8, views=3)
    folder = write_folder(tmp_path, samples, fmt="png")
    assert len(os.listdir(folder / "UBO2003" / "MANYFILES")) == 3
    everything = btf.load(str(folder), views="all")
    assert everything.count == 243
    two = btf.load(str(folder), views=[(15, 60), (0, 0)])
    assert two.count == 162 and two.angles[0, 2] == 15 and two.angles[0, 3] == 60
    with pytest.raises(weft.IoError, match="misses"):
        btf.load(str(folder), views=[(30, 0)])


def test_missing_file_is_named(tmp_path: Path, small) -> None:
    folder = write_folder(tmp_path, small, fmt="png")
    os.remove([f for f in files_of(folder) if "tl045 pl020" in f][0])
    with pytest.raises(weft.IoError, match="tl045 pl020"):
        btf.load(str(folder))


def test_duplicate_file_is_named(tmp_path: Path, small) -> None:
    folder = write_folder(tmp_path, small, fmt="png")
    src = [f for f in files_of(folder) if "tl030 pl060" in f][0]
    dup = os.path.join(os.path.dirname(src), "99999 tl030 pl060 tv000 pv000.png")
    shutil.copy(src, dup)
    with pytest.raises(weft.IoError, match="duplicate") as info:
        btf.load(str(folder))
    assert "99999 tl030" in str(info.value) and os.path.basename(src) in str(info.value)


@pytest.mark.parametrize("damage", ["garbage", "truncate", "empty"])
@pytest.mark.parametrize("fmt", ["png", "jpg"])
def test_corrupt_or_truncated_file_is_named(tmp_path: Path, small, damage: str,
                                            fmt: str) -> None:
    folder = write_folder(tmp_path, small, fmt=fmt)
    victim = [f for f in files_of(folder) if "tl060 pl036" in f][0]
    data = Path(victim).read_bytes()
    if damage == "garbage":
        data = data[:16] + bytes(range(256)) * 4
    elif damage == "truncate":
        data = data[: len(data) // 2]
    else:
        data = b""
    Path(victim).write_bytes(data)
    with pytest.raises(weft.IoError, match="tl060 pl036"):
        btf.load(str(folder))


def test_mis_sized_image_is_named(tmp_path: Path, small) -> None:
    folder = write_folder(tmp_path, small, fmt="png")
    victim = [f for f in files_of(folder) if "tl075 pl345" in f][0]
    weft.save_png(victim, np.zeros((6, 6, 3), np.uint8))
    with pytest.raises(weft.IoError, match="tl075 pl345"):
        btf.load(str(folder))


def test_non_standard_light_direction_is_named(tmp_path: Path, small) -> None:
    folder = write_folder(tmp_path, small, fmt="png")
    src = files_of(folder)[0]
    shutil.copy(src, os.path.join(os.path.dirname(src), "00001 tl010 pl000 tv000 pv000.png"))
    with pytest.raises(weft.IoError, match="tl010"):
        btf.load(str(folder))


def test_bad_archives_and_paths(tmp_path: Path, small) -> None:
    path = tmp_path / "btf.zip"
    btf.write(str(path), small, fmt="png", zip=True)
    data = path.read_bytes()
    cut = tmp_path / "cut.zip"
    cut.write_bytes(data[: len(data) // 2])
    with pytest.raises(weft.IoError):
        btf.load(str(cut))
    flipped = bytearray(data)
    flipped[len(data) // 3: len(data) // 3 + 64] = b"\x00" * 64  # inside some entry's data
    bad = tmp_path / "bad.zip"
    bad.write_bytes(bytes(flipped))
    with pytest.raises(weft.IoError):
        btf.load(str(bad))
    with pytest.raises(weft.IoError, match="neither"):
        btf.load(str(tmp_path / "nothing-here"))
    (tmp_path / "empty").mkdir()
    with pytest.raises(weft.IoError, match="no BTF images"):
        btf.load(str(tmp_path / "empty"))
    with pytest.raises(ValueError):
        btf.load(str(path), views=[(95, 0)])
    with pytest.raises(ValueError):
        btf.write(str(tmp_path / "q"), small, quality=0)


def test_material_save_load_round_trip(tmp_path: Path) -> None:
    samples, truth = btf.synthesize("granite", 8)
    m = btf.fit_specular(samples, btf.fit_linear(samples), per_texel=True).material
    m.save(str(tmp_path / "mat"))
    back = btf.BtfMaterial.load(str(tmp_path / "mat"))
    for name in ("normal", "albedo", "ambient", "specular", "exponent_map"):
        np.testing.assert_array_equal(getattr(back, name), getattr(m, name))
    assert back.exponent == m.exponent and back.flat_specular_normal
    assert os.path.isfile(tmp_path / "mat" / "normal.png")
    assert "BtfMaterial 8x8" in repr(back)
    (tmp_path / "mat" / "material.json").write_text("{not json")
    with pytest.raises(weft.IoError):
        btf.BtfMaterial.load(str(tmp_path / "mat"))
    with pytest.raises(weft.IoError):
        btf.BtfMaterial.load(str(tmp_path / "missing"))
