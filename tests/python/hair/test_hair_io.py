""".hair reading and writing (SPEC §5.1, shared/formats/hair.md) against bytes written with
``struct`` from the format description, plus fuzzing with random and truncated files."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import weft
from weft.reference.hair_geometry import hair_bytes, parse_hair_bytes


def _example(rng: np.random.Generator):
    segments = np.array([3, 1, 5, 0], dtype=np.uint16)
    p = int(np.sum(segments + 1))
    return dict(points=rng.normal(size=(p, 3)).astype(np.float32), segments=segments,
                thickness=rng.uniform(0.5, 2, p).astype(np.float32),
                transparency=rng.uniform(0, 1, p).astype(np.float32),
                colors=rng.uniform(0, 1, (p, 3)).astype(np.float32))


def test_reads_reference_bytes_with_every_array() -> None:
    ex = _example(np.random.default_rng(1))
    h = weft.hair_from_bytes(hair_bytes(**ex, info=b"test model"))
    assert h.strand_count == 4 and h.point_count == 13
    np.testing.assert_array_equal(h.points, ex["points"])
    np.testing.assert_array_equal(h.segments, ex["segments"])
    np.testing.assert_array_equal(h.thickness, ex["thickness"])
    np.testing.assert_array_equal(h.transparency, ex["transparency"])
    np.testing.assert_array_equal(h.colors, ex["colors"])
    np.testing.assert_array_equal(h.offsets, [0, 4, 6, 12, 13])
    assert h.info == "test model" and h.warnings == []
    assert h.arrays == ["segments", "points", "thickness", "transparency", "colors"]


def test_default_segments_and_defaults() -> None:
    pts = np.arange(24, dtype=np.float32).reshape(8, 3)
    h = weft.hair_from_bytes(hair_bytes(pts, default_segments=3))
    assert h.strand_count == 2 and list(h.segments) == [3, 3]
    assert np.all(h.thickness == 1.0) and np.all(h.transparency == 0.0) and np.all(h.colors == 1.0)
    assert h.arrays == ["points"]


def test_z_up_conversion_and_round_trip(tmp_path: Path) -> None:
    ex = _example(np.random.default_rng(2))
    data = hair_bytes(**ex)
    h = weft.load_hair(_write(tmp_path / "a.hair", data), z_up=True)
    p = ex["points"]
    np.testing.assert_array_equal(h.points, np.stack([p[:, 0], p[:, 2], -p[:, 1]], axis=1))
    out = tmp_path / "b.hair"
    weft.save_hair(str(out), h, z_up=True)
    assert out.read_bytes() == data  # every array written back, Z-up restored exactly
    ref = parse_hair_bytes(h.to_bytes())
    np.testing.assert_array_equal(ref["points"], h.points)
    np.testing.assert_array_equal(ref["segments"], ex["segments"])


def test_unknown_flags_and_trailing_bytes_warn() -> None:
    pts = np.zeros((4, 3), np.float32)
    h = weft.hair_from_bytes(hair_bytes(pts, default_segments=1, flags_extra=0x60) + b"xyz")
    assert h.point_count == 4
    assert any("0x60" in w for w in h.warnings) and any("trailing" in w for w in h.warnings)


@pytest.mark.parametrize("mutate, message", [
    (lambda d: b"HAIX" + d[4:], "signature"),
    (lambda d: d[:100], "header"),
    (lambda d: d[:-1], "truncated"),
    (lambda d: d[:4] + (5).to_bytes(4, "little") + d[8:], "segments add up"),  # 5 strands, 4 counts
    (lambda d: d[:8] + (17).to_bytes(4, "little") + d[12:], "segments add up"),
    (lambda d: d[:12] + (1).to_bytes(4, "little") + d[16:], "points array"),
    (lambda d: d[:4] + (0).to_bytes(4, "little") + d[8:], "no strands"),
    (lambda d: d[:8] + (0xFFFFFFFF).to_bytes(4, "little") + d[12:], "segments add up"),
])
def test_corrupt_files_are_rejected(mutate, message) -> None:
    data = hair_bytes(**_example(np.random.default_rng(3)))
    with pytest.raises(weft.IoError, match=message):
        weft.hair_from_bytes(mutate(data))


def test_non_finite_and_out_of_range_values_are_rejected() -> None:
    ex = _example(np.random.default_rng(4))
    ex["points"][2, 1] = np.nan
    with pytest.raises(weft.IoError, match="finite"):
        weft.hair_from_bytes(hair_bytes(**ex))
    ex = _example(np.random.default_rng(4))
    ex["transparency"][0] = 2.0
    with pytest.raises(weft.IoError, match="transparency"):
        weft.hair_from_bytes(hair_bytes(**ex))


def test_huge_counts_do_not_allocate_or_overflow() -> None:
    header = hair_bytes(np.zeros((1, 3), np.float32), default_segments=0)[:128]
    huge = header[:4] + (0xFFFFFFFF).to_bytes(4, "little") * 2 + header[12:16] + \
        (0).to_bytes(4, "little") + header[20:]
    with pytest.raises(weft.IoError, match="truncated"):
        weft.hair_from_bytes(huge)
    # d_segments + 1 overflowing 32 bits must not wrap to a consistent count
    wrap = header[:16] + (0xFFFFFFFF).to_bytes(4, "little") + header[20:]
    with pytest.raises(weft.IoError, match="inconsistent"):
        weft.hair_from_bytes(wrap)


def test_fuzz_random_and_truncated_files() -> None:
    rng = np.random.default_rng(5)
    good = hair_bytes(**_example(rng))
    accepted = 0
    for _ in range(400):
        kind = rng.integers(3)
        if kind == 0:
            data = bytes(rng.integers(0, 256, rng.integers(0, 400), dtype=np.uint8))
        elif kind == 1:
            data = good[: rng.integers(0, len(good))]
        else:
            buf = bytearray(good)
            for i in rng.integers(0, len(buf), rng.integers(1, 8)):
                buf[i] = rng.integers(0, 256)
            if rng.random() < 0.5:
                buf[:4] = b"HAIR"
            data = bytes(buf)
        try:
            h = weft.hair_from_bytes(data)
        except weft.IoError:
            continue
        accepted += 1
        assert np.all(np.isfinite(h.points)) and h.offsets[-1] == h.point_count
    assert accepted < 400


def test_hair_strands_from_arrays_validates() -> None:
    pts = np.zeros((6, 3))
    h = weft.HairStrands(pts, [2, 2])
    assert h.strand_count == 2 and h.points.dtype == np.float32
    assert not h.points.flags.writeable
    assert "2 strands" in repr(h)
    with pytest.raises(weft.InvalidArgument, match="add up"):
        weft.HairStrands(pts, [2, 3])
    with pytest.raises(weft.InvalidArgument, match="finite"):
        weft.HairStrands(np.full((6, 3), np.inf), [2, 2])
    with pytest.raises(weft.InvalidArgument, match="shape"):
        weft.HairStrands(np.zeros((6, 2)), [2, 2])
    with pytest.raises(weft.InvalidArgument, match="entries"):
        weft.HairStrands(pts, [2, 2], thickness=np.ones(5))
    with pytest.raises(weft.InvalidArgument, match="default_segments"):
        weft.HairStrands(pts)
    with pytest.raises(weft.InvalidArgument, match="whole number"):
        weft.HairStrands(pts, default_segments=3)
    with pytest.raises(weft.InvalidArgument, match="65535"):
        weft.HairStrands(pts, [70000])
    with pytest.raises(TypeError):
        weft.HairStrands(pts, ["a", "b"])


def test_missing_file_and_unwritable_path(tmp_path: Path) -> None:
    with pytest.raises(weft.IoError, match="cannot open"):
        weft.load_hair(str(tmp_path / "missing.hair"))
    h = weft.HairStrands(np.zeros((2, 3)), [1])
    with pytest.raises(weft.IoError, match="cannot create"):
        weft.save_hair(str(tmp_path / "no" / "dir.hair"), h)


def _write(path: Path, data: bytes) -> str:
    path.write_bytes(data)
    return str(path)
