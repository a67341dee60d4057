"""Float images: OpenEXR and Radiance .hdr IO against independent NumPy encoders/decoders."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import weft


def rgbe_encode(rgb: np.ndarray) -> np.ndarray:
    """Radiance RGBE encoding (Ward): shared exponent of the largest component."""
    m = rgb.max(axis=-1)
    mant, expo = np.frexp(m)
    scale = np.where(m > 1e-32, mant * 256.0 / np.where(m > 0, m, 1), 0.0)
    out = np.zeros(rgb.shape[:-1] + (4,), np.uint8)
    out[..., :3] = np.minimum(255, np.floor(rgb * scale[..., None])).astype(np.uint8)
    out[..., 3] = np.where(m > 1e-32, expo + 128, 0).astype(np.uint8)
    return out


def rgbe_decode(e: np.ndarray) -> np.ndarray:
    """mantissa * 2^(exponent - 136): stb_image's decoding (and Bruce Walter's rgbe.c);
    Radiance's own adds 0.5 to the mantissa."""
    scale = np.where(e[..., 3] > 0, np.ldexp(1.0, e[..., 3].astype(np.int32) - 136), 0.0)
    return e[..., :3].astype(np.float64) * scale[..., None]


def parse_hdr_bytes(data: bytes) -> np.ndarray:
    """An independent reader: header, then flat or new-style run-length scanlines."""
    header_end = data.index(b"\n\n") + 2
    res_end = data.index(b"\n", header_end)
    parts = data[header_end:res_end].split()
    h, w = int(parts[1]), int(parts[3])
    pos = res_end + 1
    out = np.zeros((h, w, 4), np.uint8)
    for y in range(h):
        if 8 <= w <= 32767 and data[pos] == 2 and data[pos + 1] == 2:
            pos += 4
            for c in range(4):
                x = 0
                while x < w:
                    n = data[pos]
                    pos += 1
                    if n > 128:
                        out[y, x:x + n - 128, c] = data[pos]
                        pos += 1
                        x += n - 128
                    else:
                        out[y, x:x + n, c] = np.frombuffer(data[pos:pos + n], np.uint8)
                        pos += n
                        x += n
        else:
            out[y] = np.frombuffer(data[pos:pos + 4 * w], np.uint8).reshape(w, 4)
            pos += 4 * w
    assert pos == len(data)
    return out


def hdr_test_image(h: int = 13, w: int = 37, seed: int = 1) -> np.ndarray:
    rng = np.random.default_rng(seed)
    img = np.exp(rng.normal(0.0, 3.0, (h, w, 3))).astype(np.float32)
    img[2, :20] = [4.0, 2.0, 1.0]  # a run
    img[5, 3] = 0.0
    img[6, :] = 1e-3
    return img


def test_hdr_writer_matches_an_independent_rgbe_encoder(tmp_path: Path) -> None:
    img = hdr_test_image()
    path = tmp_path / "a.hdr"
    weft.save_hdr(str(path), img)
    data = path.read_bytes()
    assert data.startswith(b"#?RADIANCE\n") and b"FORMAT=32-bit_rle_rgbe" in data
    np.testing.assert_array_equal(parse_hdr_bytes(data), rgbe_encode(img.astype(np.float64)))
    assert len(data) < 13 * 37 * 4  # the runs were encoded


def test_hdr_reader_decodes_flat_and_rle_files(tmp_path: Path) -> None:
    img = hdr_test_image(h=9, w=40, seed=2)
    e = rgbe_encode(img.astype(np.float64))
    # flat file written by hand
    flat = tmp_path / "flat.hdr"
    flat.write_bytes(b"#?RGBE\nEXPOSURE=1.0\nFORMAT=32-bit_rle_rgbe\n\n-Y 9 +X 40\n" + e.tobytes())
    np.testing.assert_allclose(weft.load_hdr(str(flat)), rgbe_decode(e), rtol=1e-6)
    # run-length file written by weft, read back: within RGBE precision of the input
    rle = tmp_path / "rle.hdr"
    weft.save_hdr(str(rle), img)
    back = weft.load_hdr(str(rle))
    assert back.shape == (9, 40, 3) and back.dtype == np.float32
    np.testing.assert_allclose(back, rgbe_decode(e), rtol=1e-6)
    rel = np.abs(back - img) / np.maximum(img.max(axis=-1, keepdims=True), 1e-30)
    assert rel.max() < 2.0 / 256


def test_exr_round_trip_is_exact(tmp_path: Path) -> None:
    rng = np.random.default_rng(3)
    for channels in (1, 2, 3, 4):
        img = rng.normal(0, 100, (7, 11, channels)).astype(np.float32)
        path = tmp_path / f"c{channels}.exr"
        weft.save_exr(str(path), img)
        back = weft.load_exr(str(path))
        assert back.shape == img.shape
        np.testing.assert_array_equal(back, img)
    grey = rng.random((5, 6)).astype(np.float32)
    weft.save_exr(str(tmp_path / "g.exr"), grey)
    np.testing.assert_array_equal(weft.load_image_float(str(tmp_path / "g.exr"))[..., 0], grey)


def test_load_image_float_png_and_unknown(tmp_path: Path) -> None:
    u8 = np.arange(48, dtype=np.uint8).reshape(4, 4, 3)
    weft.save_png(str(tmp_path / "a.png"), u8)
    np.testing.assert_allclose(weft.load_image_float(str(tmp_path / "a.png")), u8 / 255.0,
                               rtol=1e-6)
    with pytest.raises(weft.InvalidArgument, match="unknown image type"):
        weft.load_image_float(str(tmp_path / "a.tga"))


@pytest.mark.parametrize("kind", ["exr", "hdr"])
def test_truncated_and_corrupt_files_raise_io_error(tmp_path: Path, kind: str) -> None:
    img = hdr_test_image(h=16, w=16)
    good = tmp_path / f"good.{kind}"
    (weft.save_exr if kind == "exr" else weft.save_hdr)(str(good), img)
    data = good.read_bytes()
    load = weft.load_exr if kind == "exr" else weft.load_hdr
    rng = np.random.default_rng(4)
    cuts = sorted(set([0, 1, 4, 10, len(data) // 2, len(data) - 1] +
                      list(rng.integers(0, len(data), 10))))
    for cut in cuts:
        bad = tmp_path / f"cut{cut}.{kind}"
        bad.write_bytes(data[:cut])
        with pytest.raises(weft.IoError, match=f"cut{cut}"):
            load(str(bad))
    for trial in range(20):  # random garbage after a valid signature
        bad = tmp_path / f"junk{trial}.{kind}"
        bad.write_bytes(data[:8] + rng.integers(0, 256, 200, dtype=np.uint8).tobytes())
        with pytest.raises(weft.IoError):
            load(str(bad))
    with pytest.raises(weft.IoError, match="cannot open"):
        load(str(tmp_path / f"missing.{kind}"))


def test_hdr_header_lies_about_size(tmp_path: Path) -> None:
    bad = tmp_path / "huge.hdr"
    bad.write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 60000 +X 60000\n" + b"\0" * 64)
    with pytest.raises(weft.IoError, match="too short"):
        weft.load_hdr(str(bad))
    bad.write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 4 +X 4\n" + b"\0" * 64)
    with pytest.raises(weft.IoError, match="resolution"):
        weft.load_hdr(str(bad))
    bad.write_bytes(b"#?RADIANCE\n\n-Y 4 +X 4\n" + b"\0" * 64)  # stb_image needs FORMAT=
    with pytest.raises(weft.IoError, match="FORMAT=32-bit_rle_rgbe"):
        weft.load_hdr(str(bad))


def test_hdr_run_length_zero_counts_and_cuts_end_quickly(tmp_path: Path) -> None:
    """A zero count in a run-length scanline made this stb_image loop forever (it does not
    advance); weft hands it padding past the end and refuses the file as cut short."""
    import time

    header = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 16\n"
    for body in (bytes([2, 2, 0, 16]) + bytes(40),  # zero counts up to the end
                 bytes([2, 2, 0, 16, 0x90, 7]),      # one run of 16, then the file ends
                 bytes([2, 2, 0, 16]) + bytes([0x90, 7]) * 4 + bytes([2, 2])):
        bad = tmp_path / "zero.hdr"
        bad.write_bytes(header + body)
        start = time.perf_counter()
        with pytest.raises(weft.IoError, match="zero.hdr.*ends early"):
            weft.load_hdr(str(bad))
        assert time.perf_counter() - start < 1.0
    # the same scanlines complete: read, every pixel 7 * 2^(7 - 136)
    good = tmp_path / "runs.hdr"
    good.write_bytes(header + (bytes([2, 2, 0, 16]) + bytes([0x90, 7]) * 4) * 2)
    np.testing.assert_array_equal(weft.load_hdr(str(good)), np.full((2, 16, 3), 7 * 2.0 ** -129,
                                                                    np.float32))


def test_bad_float_images_are_rejected(tmp_path: Path) -> None:
    path = str(tmp_path / "x.exr")
    with pytest.raises(weft.InvalidArgument, match="non-finite"):
        weft.save_exr(path, np.array([[1.0, np.nan]], np.float32))
    with pytest.raises(weft.InvalidArgument):
        weft.save_exr(path, np.zeros((0, 4, 3), np.float32))
    with pytest.raises(weft.InvalidArgument):
        weft.save_exr(path, np.zeros((4, 4, 5), np.float32))
    with pytest.raises(weft.InvalidArgument, match=">= 0"):
        weft.save_hdr(str(tmp_path / "n.hdr"), -np.ones((4, 4, 3), np.float32))
    # RGBE's exponent byte holds values below 2^127; 2^127 would wrap to black
    with pytest.raises(weft.InvalidArgument, match="2\\^127"):
        weft.save_hdr(str(tmp_path / "big.hdr"), np.full((4, 4, 3), 2.0 ** 127, np.float32))
    weft.save_hdr(str(tmp_path / "big.hdr"), np.full((4, 4, 3), 1e38, np.float32))
    np.testing.assert_allclose(weft.load_hdr(str(tmp_path / "big.hdr")), 1e38, rtol=1 / 128)
    with pytest.raises(TypeError):
        weft.save_exr(path, "not an image")
