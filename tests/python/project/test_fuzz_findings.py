"""Regression tests for what the loaders' fuzzers found (issue 13, tests/fuzz/): each input is
the minimised kind of file a fuzzer produced, and must now give a clear weft error."""

from __future__ import annotations

import numpy as np
import pytest
import weft
import weft.ibl


def test_npy_with_a_corrupt_header_is_an_io_error(tmp_path):
    # found by the env target: numpy's header parser raised tokenize.TokenError
    path = tmp_path / "cut.npy"
    path.write_bytes(b"\x93NUMPY\x01\x00v\x00{'descr': '<f4', 'fortran_order': False, 'shape': (6,"
                     + b" " * 40 + b"\n")
    with pytest.raises(weft.IoError, match="not a readable .npy"):
        weft.ibl.load_environment_cube(str(path), size=4)


def test_npy_claiming_a_huge_shape_is_refused_before_reading(tmp_path):
    path = tmp_path / "claim.npy"
    np.save(path, np.zeros((6, 2, 2, 3), np.float32))
    data = path.read_bytes().replace(b"(6, 2, 2, 3), ", b"(6,9999,9999,3)")
    path.write_bytes(data)
    with pytest.raises(weft.IoError, match="claims"):
        weft.ibl.load_environment(str(path))


@pytest.mark.parametrize("bad", [-1.0, 3e38])
def test_npy_cube_faces_with_bad_radiance_are_refused(tmp_path, bad):
    # found by the env target: cube faces from .npy skipped the radiance checks (negative and
    # 1e38 values became a cube; resampling 1e38 overflowed to inf)
    faces = np.ones((6, 2, 2, 3), np.float32)
    faces[2, 1, 0, 1] = bad
    np.save(tmp_path / "cube.npy", faces)
    with pytest.raises(weft.InvalidArgument, match="radiance must be in"):
        weft.ibl.load_environment_cube(str(tmp_path / "cube.npy"), size=4)


def test_float64_beyond_float32_is_refused_not_inf(tmp_path):
    image = np.ones((4, 8, 3))
    image[1, 1, 1] = 1e300
    np.save(tmp_path / "eq.npy", image)
    with pytest.raises(weft.InvalidArgument, match="float32"):
        weft.ibl.load_environment_cube(str(tmp_path / "eq.npy"), size=4)


def test_huge_radiance_in_an_hdr_is_refused_not_an_inf_cube(tmp_path):
    image = np.ones((4, 8, 3), np.float32)
    image[2, 3] = 1e32  # representable in RGBE (up to ~1.7e38), above MAX_RADIANCE
    weft.save_hdr(str(tmp_path / "sun.hdr"), image)
    with pytest.raises(weft.InvalidArgument, match="radiance must be in"):
        weft.ibl.load_environment_cube(str(tmp_path / "sun.hdr"), size=4)


def test_demo_script_parses_and_names_bad_lines(tmp_path):
    path = tmp_path / "s.txt"
    path.write_text("# comment\n0 key space\n2 grab 10 20.5\n3 drag 11 21\n4 release\n")
    events = weft.load_demo_script(str(path))
    assert [e[:2] for e in events] == [(0, "key"), (2, "grab"), (3, "drag"), (4, "release")]
    assert events[0][2] == 32 and events[1][3:] == (10.0, 20.5)
    path.write_text("0 grab 1e300 5\n")
    with pytest.raises(weft.IoError, match=r"s.txt:1: grab pixel must be finite"):
        weft.load_demo_script(str(path))
    path.write_text("3 release\n1 release\n")
    with pytest.raises(weft.IoError, match=r"s.txt:2: frames"):
        weft.load_demo_script(str(path))
    with pytest.raises(weft.IoError, match="directory"):
        weft.load_demo_script(str(tmp_path))
