"""Decompressed-size caps (issue 13): small crafted files that claim huge decoded sizes are
refused with weft.IoError from their headers, quickly and without allocating the claim --
zip entries (count, an entry inflating past its declared size), PNG (kMaxPngDecodedBytes,
1 GiB) and EXR (kMaxExrDecodedBytes, 4 GiB, and the codec's best ratio). Declared zip entry
sizes are covered in test_btf_inputs.py."""

from __future__ import annotations

import resource
import struct
import time
import zipfile
import zlib
from pathlib import Path

import numpy as np
import pytest
import weft
from weft import btf


def _quick(fn, *args, match: str, seconds: float = 2.0):
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    t0 = time.perf_counter()
    with pytest.raises(weft.IoError, match=match) as err:
        fn(*args)
    assert time.perf_counter() - t0 < seconds
    # ru_maxrss is the peak (KiB): the refused claim was never allocated
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - rss < 256 * 1024
    return err.value


# zip --------------------------------------------------------------------------------------------


def test_zip_listing_too_many_entries_is_refused(tmp_path: Path) -> None:
    archive = tmp_path / "many.zip"
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_STORED) as z:
        for i in range(100_001):  # kMaxZipEntries + 1
            z.writestr(f"e{i}", b"")
    err = _quick(btf.load, str(archive), match="100001 entries, more than the 100000")
    assert str(archive) in str(err)


def _patch_declared_size(data: bytearray, name: bytes, new_size: int) -> int:
    """Sets the uncompressed size of entry `name` in its local header and central record."""
    patched = 0
    for signature, size_at, name_len_at, name_at in ((b"PK\x03\x04", 22, 26, 30),
                                                     (b"PK\x01\x02", 24, 28, 46)):
        at = data.find(signature)
        while at >= 0:
            name_len = struct.unpack_from("<H", data, at + name_len_at)[0]
            if bytes(data[at + name_at:at + name_at + name_len]) == name:
                struct.pack_into("<I", data, at + size_at, new_size)
                patched += 1
            at = data.find(signature, at + 4)
    return patched


def test_zip_entry_inflating_past_its_declared_size_is_refused(tmp_path: Path) -> None:
    """An entry that declares 1 000 bytes but inflates to 200 000: the reader stops at the
    declared size and refuses the entry instead of trusting either number."""
    samples, _ = btf.synthesize("wool", 4)
    btf.write(str(tmp_path / "w.zip"), samples, fmt="png", zip=True)
    names = btf_names(tmp_path / "w.zip")
    archive = tmp_path / "liar.zip"
    with zipfile.ZipFile(tmp_path / "w.zip") as src, \
            zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as dst:
        for n in names:
            # the first image (read first) gets 200 000 trailing zero bytes after the PNG
            dst.writestr(n, src.read(n) + (bytes(200_000) if n == names[0] else b""))
    with zipfile.ZipFile(tmp_path / "w.zip") as src:
        true_size = len(src.read(names[0]))
    data = bytearray(archive.read_bytes())
    assert _patch_declared_size(data, names[0].encode(), true_size) == 2
    archive.write_bytes(bytes(data))
    err = _quick(btf.load, str(archive), match="inflates to more than|CRC|corrupt")
    assert names[0] in str(err)


def btf_names(path: Path):
    with zipfile.ZipFile(path) as z:
        return sorted(n for n in z.namelist() if not n.endswith("/"))


# PNG --------------------------------------------------------------------------------------------


def _png_chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def _png_claiming(path: Path, width: int, height: int, idat_bytes: int) -> None:
    """A PNG header claiming width x height RGBA 8-bit, followed by `idat_bytes` of deflate data
    (enough that deflate's ratio alone cannot rule the claim out)."""
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    rng = np.random.default_rng(1)
    idat = zlib.compress(rng.integers(0, 256, idat_bytes, dtype=np.uint8).tobytes(), 0)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + _png_chunk(b"IHDR", ihdr) +
                     _png_chunk(b"IDAT", idat) + _png_chunk(b"IEND", b""))


def test_png_over_the_decoded_cap_is_refused_before_allocating(tmp_path: Path) -> None:
    path = tmp_path / "huge.png"
    _png_claiming(path, 20000, 20000, 1_600_000)  # 1.6 GB decoded > 1 GiB, 1.6 MB on disk
    _quick(weft.load_png, str(path), match="1 GiB")


def test_png_claiming_more_than_its_bytes_can_hold_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "bomb.png"
    _png_claiming(path, 60000, 60000, 100)
    _quick(weft.load_png, str(path), match="impossible for the file size")


# EXR --------------------------------------------------------------------------------------------


def _exr_with_window(path: Path, width: int, height: int, piz: bool = False) -> None:
    """A valid small EXR (ZIP compression, 16 lines per chunk) rewritten to claim a width x
    height data window (optionally PIZ, 32 lines per chunk, whose ratio has no small bound),
    with a complete line-offset table whose entries all point at the one real chunk -- so
    OpenEXR opens it, and only the size check stands between the header and the allocation."""
    weft.save_exr(str(path), np.ones((16, 16, 3), np.float32))
    data = bytearray(path.read_bytes())
    key = b"dataWindow\0box2i\0"
    at = data.index(key) + len(key)
    assert struct.unpack_from("<i", data, at)[0] == 16
    struct.pack_into("<4i", data, at + 4, 0, 0, width - 1, height - 1)
    key = b"compression\0compression\0"
    at = data.index(key) + len(key)
    assert struct.unpack_from("<i", data, at)[0] == 1 and data[at + 4] == 3  # ZIP
    if piz:
        data[at + 4] = 4
    end = _header_end(data)
    (old_offset,) = struct.unpack_from("<Q", data, end)
    chunk = bytes(data[old_offset:])
    chunks = -(-height // (32 if piz else 16))
    table_end = end + 8 * chunks
    table = struct.pack("<Q", table_end) * chunks
    path.write_bytes(bytes(data[:end]) + table + chunk)


def _header_end(data: bytearray) -> int:
    """Offset just past the header's terminating empty attribute name."""
    at = 8  # magic + version
    while data[at] != 0:
        name_end = data.index(b"\0", at)
        type_end = data.index(b"\0", name_end + 1)
        (size,) = struct.unpack_from("<i", data, type_end + 1)
        at = type_end + 5 + size
    return at + 1


def test_exr_over_the_decoded_cap_is_refused_before_allocating(tmp_path: Path) -> None:
    path = tmp_path / "huge.exr"
    _exr_with_window(path, 30000, 30000, piz=True)  # 30000^2 RGB floats: 10.8 GB > 4 GiB
    _quick(weft.load_exr, str(path), match="more than the 4294967296 an EXR may have")


def test_exr_claiming_more_than_its_codec_can_hold_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "bomb.exr"
    _exr_with_window(path, 8000, 8000)  # 768 MB of floats from a few hundred ZIP bytes
    _quick(weft.load_exr, str(path), match="impossible for its")


def test_the_caps_still_read_ordinary_files(tmp_path: Path) -> None:
    img = np.random.default_rng(2).uniform(0, 4, (64, 96, 3)).astype(np.float32)
    weft.save_exr(str(tmp_path / "ok.exr"), img)
    np.testing.assert_array_equal(weft.load_exr(str(tmp_path / "ok.exr")), img)
    rgba = np.random.default_rng(3).integers(0, 256, (64, 96, 4), dtype=np.uint8)
    weft.save_png(str(tmp_path / "ok.png"), rgba)
    np.testing.assert_array_equal(weft.load_png(str(tmp_path / "ok.png")), rgba)
