"""BTF inputs a user may hand over that the round-trip tests do not write: 16-bit and RGBA PNGs
(written here byte by byte with zlib + struct, independently of weft's writer), macOS zip
metadata, zip bombs, absurd thread counts, a thread limit, and finite samples whose float32 fit
overflows."""

from __future__ import annotations

import os
import struct
import subprocess
import sys
import textwrap
import time
import zipfile
import zlib
from pathlib import Path

import numpy as np
import pytest
import weft
from weft import btf

SIZE = 6  # texels per side of the hand-written images
FOLDER = Path("UBO2003") / "MANYFILES" / "tv000_pv000"


def png_bytes(pixels: np.ndarray, bit_depth: int, gamma: float = None) -> bytes:
    """A PNG of (H, W, C) unsigned integers, C = 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA."""
    height, width, channels = pixels.shape
    colour_type = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    dtype = ">u2" if bit_depth == 16 else "u1"
    rows = b"".join(b"\0" + pixels[y].astype(dtype).tobytes() for y in range(height))

    def chunk(kind: bytes, data: bytes) -> bytes:
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height,
                                                            bit_depth, colour_type, 0, 0, 0))
    if gamma is not None:  # a gAMA chunk: libpng's simplified API would convert by it
        out += chunk(b"gAMA", struct.pack(">I", int(round(gamma * 100000))))
    return out + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


def light_names() -> list:
    """Bonn names of the 81 frontal-view images, in the order of BtfSamples.angles."""
    return [f"{i:05d} tl{int(tl):03d} pl{int(pl):03d} tv000 pv000.png"
            for i, (tl, pl) in enumerate(weft._core.btf_standard_directions())]


def write_pngs(root: Path, images: list, bit_depth: int, **kw) -> Path:
    folder = root / FOLDER
    folder.mkdir(parents=True)
    for name, pixels in zip(light_names(), images):
        (folder / name).write_bytes(png_bytes(pixels, bit_depth, **kw))
    return root


def random_images(rng: np.random.Generator, channels: int, bit_depth: int) -> list:
    top = (1 << bit_depth) - 1
    return [rng.integers(0, top + 1, (SIZE, SIZE, channels)) for _ in range(81)]


def as_samples(images: list, top: int) -> np.ndarray:
    """(81, 3, H, W) values / top, grey repeated into RGB."""
    rgb = [np.repeat(im, 3, axis=2) if im.shape[2] == 1 else im[:, :, :3] for im in images]
    return np.stack([im.transpose(2, 0, 1) for im in rgb]).astype(np.float64) / top


# 16-bit PNG ------------------------------------------------------------------------------------


def test_16bit_png_reads_the_stored_value(tmp_path: Path) -> None:
    quarter = np.full((SIZE, SIZE, 3), 16384)  # 0.25 of 65535 (+ 1/4 step)
    root = write_pngs(tmp_path, [quarter] * 81, 16)
    raw = btf.load(str(root)).values
    np.testing.assert_allclose(raw, 16384 / 65535, rtol=1e-6)  # was 0.533: sRGB-encoded
    linear = btf.load(str(root), gamma="linear").values
    np.testing.assert_allclose(linear, (16384 / 65535) ** 2.2, rtol=1e-5)


@pytest.mark.parametrize("channels", [1, 3, 4])
def test_16bit_png_values_are_exact(tmp_path: Path, channels: int) -> None:
    rng = np.random.default_rng(channels)
    images = random_images(rng, channels, 16)
    if channels == 4:
        for im in images:
            im[:, :, 3] = 65535  # opaque alpha is dropped
    root = write_pngs(tmp_path, images, 16)
    expected = as_samples(images, 65535)
    np.testing.assert_allclose(btf.load(str(root)).values, expected, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(btf.load(str(root), gamma="linear").values, expected ** 2.2,
                               rtol=1e-5, atol=1e-9)


def test_8bit_png_ignores_gamma_chunk_like_16bit(tmp_path: Path) -> None:
    """Values come out as stored whatever the file's gAMA says (as for JPEG); the gamma option
    is the one conversion, the same for 8 and 16 bits."""
    rng = np.random.default_rng(8)
    images = random_images(rng, 3, 8)
    root = write_pngs(tmp_path, images, 8, gamma=1.0)
    np.testing.assert_allclose(btf.load(str(root)).values, as_samples(images, 255), rtol=1e-6)
    np.testing.assert_allclose(btf.load(str(root), gamma="linear").values,
                               as_samples(images, 255) ** 2.2, rtol=1e-5, atol=1e-9)


# RGBA ------------------------------------------------------------------------------------------


@pytest.mark.parametrize("bit_depth", [8, 16])
def test_transparent_png_is_refused_with_its_name(tmp_path: Path, bit_depth: int) -> None:
    top = (1 << bit_depth) - 1
    images = [np.full((SIZE, SIZE, 4), top) for _ in range(81)]
    images[17][2, 3, 3] = top // 2
    root = write_pngs(tmp_path, images, bit_depth)
    with pytest.raises(weft.IoError, match=r"transparent.*alpha .*at pixel \(3, 2\)") as err:
        btf.load(str(root))
    assert light_names()[17] in str(err.value)


def test_opaque_rgba_png_reads_as_rgb(tmp_path: Path) -> None:
    rng = np.random.default_rng(4)
    images = random_images(rng, 4, 8)
    for im in images:
        im[:, :, 3] = 255
    root = write_pngs(tmp_path, images, 8)
    np.testing.assert_allclose(btf.load(str(root)).values, as_samples(images, 255), rtol=1e-6)


# zip archives ----------------------------------------------------------------------------------


def test_macos_zip_metadata_is_skipped(tmp_path: Path) -> None:
    rng = np.random.default_rng(5)
    images = random_images(rng, 3, 8)
    archive = tmp_path / "btf.zip"
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as z:
        for name, im in zip(light_names(), images):
            z.writestr(str(FOLDER / name), png_bytes(im, 8))
            # What macOS's Archive Utility adds: AppleDouble resource forks with the same names.
            z.writestr(str(Path("__MACOSX") / FOLDER / ("._" + name)), b"\0\5\26\7" + b"x" * 80)
        z.writestr(str(FOLDER / ("._" + light_names()[0])), b"\0\5\26\7 not a PNG")
    loaded = btf.load(str(archive))
    np.testing.assert_allclose(loaded.values, as_samples(images, 255), rtol=1e-6)


def test_macos_metadata_files_in_a_folder_are_skipped(tmp_path: Path) -> None:
    rng = np.random.default_rng(6)
    images = random_images(rng, 3, 8)
    root = write_pngs(tmp_path, images, 8)
    (root / FOLDER / ("._" + light_names()[3])).write_bytes(b"\0\5\26\7 resource fork")
    np.testing.assert_allclose(btf.load(str(root)).values, as_samples(images, 255), rtol=1e-6)


def bomb_zip(path: Path, entry_bytes: int) -> None:
    """80 good entries and one deflated run of zeros, streamed (never held in memory here)."""
    names = light_names()
    good = png_bytes(np.full((SIZE, SIZE, 3), 100), 8)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        for name in names[:-1]:
            z.writestr(str(FOLDER / name), good)
        with z.open(str(FOLDER / names[-1]), "w", force_zip64=True) as f:
            block = bytes(1 << 20)
            for _ in range(entry_bytes >> 20):
                f.write(block)


def test_zip_bomb_is_refused_before_inflating(tmp_path: Path) -> None:
    archive = tmp_path / "bomb.zip"
    bomb_zip(archive, 300 << 20)  # 300 MiB of zeros, ~300 KiB on disk
    assert archive.stat().st_size < 2 << 20
    script = textwrap.dedent(f"""
        import resource, time, weft
        from weft import btf
        before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        t0 = time.perf_counter()
        try:
            btf.load({str(archive)!r})
            print("loaded")
        except weft.IoError as e:
            print("IoError", e)
        grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
        print("seconds", time.perf_counter() - t0, "grown_kib", grown)
    """)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         timeout=120).stdout
    assert "IoError" in out and "zip bomb" in out and light_names()[-1] in out, out
    seconds = float(out.split("seconds ")[1].split()[0])
    grown_kib = int(out.split("grown_kib ")[1].split()[0])
    assert seconds < 5.0, out
    assert grown_kib < 64 * 1024, out  # far below the 300 MiB the entry declares


def test_zip_declaring_impossible_sizes_is_refused(tmp_path: Path) -> None:
    """A header forged to claim 3 GiB from a few deflated bytes (more than deflate's ~1032:1)."""
    archive = tmp_path / "forged.zip"
    names = light_names()
    good = png_bytes(np.full((SIZE, SIZE, 3), 7), 8)
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as z:
        for name in names:
            z.writestr(str(FOLDER / name), good)
    data = bytearray(archive.read_bytes())
    target = str(FOLDER / names[40]).encode()
    size = struct.pack("<I", len(good))
    # Local header (size at 22, name length at 26, name at 30) and central directory record
    # (24, 28, 46) must agree, or libzip calls the archive inconsistent.
    patched = 0
    for signature, size_at, name_len_at, name_at in ((b"PK\x03\x04", 22, 26, 30),
                                                     (b"PK\x01\x02", 24, 28, 46)):
        at = data.find(signature)
        while at >= 0:
            name_len = struct.unpack_from("<H", data, at + name_len_at)[0]
            if bytes(data[at + name_at:at + name_at + name_len]) == target:
                assert bytes(data[at + size_at:at + size_at + 4]) == size
                struct.pack_into("<I", data, at + size_at, 3 << 30)
                patched += 1
            at = data.find(signature, at + 4)
    assert patched == 2
    archive.write_bytes(bytes(data))
    with pytest.raises(weft.IoError, match="impossible for deflate|zip bomb") as err:
        btf.load(str(archive))
    assert names[40] in str(err.value)


# threads ---------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def wool() -> "weft.BtfSamples":
    return btf.synthesize("wool", 16, noise=0.004)[0]


@pytest.mark.parametrize("threads", [-1, 257, 100000])
def test_threads_out_of_range_are_refused(tmp_path: Path, wool, threads: int) -> None:
    with pytest.raises(weft.InvalidArgument, match="threads"):
        btf.fit_linear(wool, threads=threads)
    with pytest.raises(weft.InvalidArgument, match="threads"):
        btf.fit_specular(wool, btf.fit_linear(wool), threads=threads)
    btf.write(str(tmp_path / "b"), wool, fmt="png")
    with pytest.raises(weft.InvalidArgument, match="threads"):
        btf.load(str(tmp_path / "b"), threads=threads)


def test_many_threads_give_the_same_fit(wool) -> None:
    one = btf.fit_linear(wool, threads=1)
    many = btf.fit_linear(wool, threads=256)
    np.testing.assert_array_equal(one.normal, many.normal)
    np.testing.assert_array_equal(one.ambient, many.ambient)


def test_thread_creation_failure_does_not_hang(tmp_path: Path) -> None:
    """Under an address-space limit only a few 8 MiB thread stacks can be mapped: work split over
    the 80-81 images or samples (load, the eq. 4.29 exponent search, sample errors) must finish
    on the threads that started, with the same result (the pool deadlocked in its destructor
    before)."""
    script = textwrap.dedent(f"""
        import resource, threading
        import numpy as np
        from weft import btf
        samples = btf.synthesize("wool", 16, noise=0.004)[0]
        btf.write({str(tmp_path / "b")!r}, samples, fmt="png")
        def run(threads):
            loaded = btf.load({str(tmp_path / "b")!r}, threads=threads)
            lin = btf.fit_linear(samples, threads=threads)
            spec = btf.fit_specular(samples, lin, False, threads=threads)
            errors = btf.sample_errors(samples, spec.material, threads=threads)
            return loaded.values, lin.normal, spec.curve, errors
        reference = run(1)
        with open("/proc/self/status") as f:
            vm = next(int(l.split()[1]) for l in f if l.startswith("VmSize")) * 1024
        resource.setrlimit(resource.RLIMIT_AS, (vm + (48 << 20), resource.RLIM_INFINITY))
        hold, started = threading.Event(), []
        try:  # the limit must bite, or this test proves nothing
            for _ in range(64):
                started.append(threading.Thread(target=hold.wait))
                started[-1].start()
            print("limit did not bite")
        except RuntimeError:
            print("limit bites")
        hold.set()
        for t in started:
            if t.is_alive():
                t.join()
        for _ in range(3):
            got = run(256)
        print("same", all(np.array_equal(a, b, equal_nan=True) for a, b in zip(got, reference)))
    """)
    env = dict(os.environ, MALLOC_ARENA_MAX="1", OMP_NUM_THREADS="1",
               OPENBLAS_NUM_THREADS="1")
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=120, env=env)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "limit bites" in proc.stdout and "same True" in proc.stdout, proc.stdout + proc.stderr
    assert time.perf_counter() - t0 < 60


# overflow --------------------------------------------------------------------------------------


def scaled(samples, factor: float) -> "weft.BtfSamples":
    values = samples.values.astype(np.float64) * factor
    assert np.isfinite(values.astype(np.float32)).all()
    return weft.BtfSamples(values.astype(np.float32), samples.angles)


def test_huge_finite_samples_raise_instead_of_nan_maps(wool) -> None:
    lin = btf.fit_linear(wool)
    big = scaled(wool, 1e30)
    # The linear fit is scale-invariant in float32 up to here: it still returns the same normals.
    np.testing.assert_allclose(btf.fit_linear(big).normal, lin.normal, atol=1e-5)
    # So it is at the other end, where Σ t² underflows float (no dark threshold).
    tiny = btf.fit_linear(scaled(wool, 1e-25), dark_threshold=0.0)
    np.testing.assert_allclose(tiny.normal, lin.normal, atol=1e-5)
    for flat in (True, False):  # residual squares overflow: no exponent can be chosen
        with pytest.raises(weft.InvalidArgument, match="non-finite.*scale them"):
            btf.fit_specular(big, btf.fit_linear(big), flat)
    huge = scaled(wool, 1e38)
    for robust in (False, True):
        with pytest.raises(weft.InvalidArgument, match="linear fit produced a non-finite"):
            btf.fit_linear(huge, robust=robust)
    with pytest.raises(weft.InvalidArgument, match="non-finite"):
        btf.fit_specular(huge, lin)


def test_load_none_names_the_type() -> None:
    for bad, kind in ((None, "NoneType"), (3, "int"), (b"btf.zip", "bytes")):
        with pytest.raises(weft.InvalidArgument, match=f"path must be a str or os.PathLike, "
                                                       f"got {kind}"):
            btf.load(bad)
