"""JPEG cells kept with the samples (BtfSamples.jpeg_cells, read with libjpeg's
jpeg_read_coefficients): checked against an independent decode of the same files by Pillow, whose
JFIF YCbCr and 8 x 8 DCT must fall inside the stored cells [(c - 1/2) q, (c + 1/2) q]."""

from __future__ import annotations

import glob
import os

import numpy as np
import pytest
import weft
from weft import btf
from weft.btf import synth

Image = pytest.importorskip("PIL.Image")  # Pillow comes with matplotlib, a declared dependency

SIZE = 32


def _dct8() -> np.ndarray:
    # T.81 A.3.3, written out here rather than taken from weft.btf.jpeg_cells
    x = np.arange(8)
    c = np.array([[np.cos((2 * i + 1) * u * np.pi / 16) for i in x] for u in x]) * 0.5
    c[0] *= 1 / np.sqrt(2)
    return c


def _block_dct(plane: np.ndarray) -> np.ndarray:
    h, w = plane.shape
    b = plane.reshape(h // 8, 8, w // 8, 8).transpose(0, 2, 1, 3)
    c = _dct8()
    return np.einsum("uk,abkl,vl->abuv", c, b, c)


@pytest.fixture(scope="module")
def jpeg_data(tmp_path_factory):
    samples, _ = synth.synthesize_random(11, SIZE, noise=0.004)
    folder = str(tmp_path_factory.mktemp("cells") / "jpg")
    btf.write(folder, samples, fmt="jpg", quality=90)
    return folder, btf.load(folder, jpeg_cells=True)


def test_cells_layout(jpeg_data):
    _, s = jpeg_data
    cells = s.jpeg_cells
    assert cells is not None and cells["ycbcr"]
    y, cb, cr = cells["components"]
    assert y["coefficients"].shape == (s.count, SIZE // 8, SIZE // 8, 8, 8)
    assert cb["coefficients"].shape == cr["coefficients"].shape == \
        (s.count, SIZE // 16, SIZE // 16, 8, 8)
    assert y["sampling"] == (2, 2) and cb["sampling"] == (1, 1)
    assert y["quant"].shape == (s.count, 8, 8) and y["quant"].min() >= 1
    assert y["coefficients"].dtype == np.int16


def test_cells_contain_pillows_decode(jpeg_data):
    """Pillow's decoded luma (JFIF Y of its RGB) has its block DCT inside the cells weft read,
    and its half-resolution chroma nearly so (the decoders upsample chroma differently)."""
    folder, s = jpeg_data
    cells = s.jpeg_cells
    angles = np.asarray(s.angles)
    files = sorted(glob.glob(os.path.join(folder, "**", "*.jpg"), recursive=True))
    assert len(files) == s.count
    ycc = np.array([[0.299, 0.587, 0.114], [-0.168736, -0.331264, 0.5],
                    [0.5, -0.418688, -0.081312]])
    inside, chroma_err = [], []
    for f in files[::8]:
        tl, pl, tv, pv = weft._core.btf_parse_file_name(os.path.basename(f))
        k = int(np.flatnonzero((angles[:, 0] == tl) & (angles[:, 1] == pl))[0])
        rgb = np.asarray(Image.open(f).convert("RGB"), np.float64)
        planes = rgb @ ycc.T
        y = _block_dct(planes[..., 0] - 128)
        c = cells["components"][0]["coefficients"][k].astype(np.float64)
        q = cells["components"][0]["quant"][k].astype(np.float64)
        dist = np.abs(y - c * q) - q / 2
        inside.append(dist <= 0.75)  # Pillow's 8-bit RGB rounding moves F by < 1 level
        for ch in (1, 2):
            half = planes[..., ch].reshape(SIZE // 2, 2, SIZE // 2, 2).mean((1, 3))
            f_c = _block_dct(half)
            cc = cells["components"][ch]["coefficients"][k].astype(np.float64)
            qc = cells["components"][ch]["quant"][k].astype(np.float64)
            chroma_err.append(np.abs(f_c - cc * qc) / qc)
    inside = np.concatenate([a.ravel() for a in inside])
    assert inside.mean() >= 0.999, inside.mean()
    chroma_err = np.concatenate([a.ravel() for a in chroma_err])
    assert np.mean(chroma_err <= 0.5) >= 0.9, np.mean(chroma_err <= 0.5)
    # a shifted table (the wrong component or order) would put most coefficients outside
    assert np.median(chroma_err) < 0.1


def test_no_cells_without_jpeg(tmp_path, jpeg_data):
    folder, s = jpeg_data
    assert btf.load(folder).jpeg_cells is None  # only when asked for
    # cells hold 8-bit raw values
    assert btf.load(folder, gamma="linear", jpeg_cells=True).jpeg_cells is None
    samples, _ = synth.synthesize_random(11, 16, noise=0.004)
    png = str(tmp_path / "png")
    btf.write(png, samples, fmt="png")
    assert btf.load(png, jpeg_cells=True).jpeg_cells is None
    # samples built from arrays have no file behind them
    assert weft.BtfSamples(np.ascontiguousarray(s.values), s.angles).jpeg_cells is None


def _fit(samples, truth, jpeg_cells):
    from weft.btf import scoring
    flat = truth.flat_specular_normal
    seed = btf.fit_specular(samples, btf.fit_linear(samples), flat).material
    fit = btf.fit_blinn_phong(samples, seed, flat_specular_normal=flat, luminance_normals=True,
                              jpeg_cells=jpeg_cells)
    return fit.material, scoring.truth_errors(fit.material, truth), \
        scoring.physical_violations(fit.material)["texels"]


def test_cell_refinement_lowers_the_normal_error(tmp_path):
    """Seed 31 (not one of the tuning seeds 0, 1, 3, 21), unshadowed, JPEG q90, 32²: the block
    solve against the luma cells brings normals nearer the truth (0.72° -> 0.49° when
    measured) and keeps every texel physical. The issue's 0.5° is not asserted on JPEG: no fit
    reaches it yet on every material (BENCHMARKS.md, btf)."""
    samples, truth = synth.synthesize_random(31, SIZE, noise=0.004)
    folder = str(tmp_path / "jpg")
    btf.write(folder, samples, fmt="jpg", quality=90)
    data = btf.load(folder, jpeg_cells=True)
    _, before, _ = _fit(data, truth.material, False)
    refined, after, outside = _fit(data, truth.material, True)
    assert outside == 0
    assert after["mean_deg"] < 0.85 * before["mean_deg"], (before, after)
    assert after["k_s_median_rel_error"] <= before["k_s_median_rel_error"] + 0.01
    # without cells the option changes nothing
    plain = weft.BtfSamples(np.ascontiguousarray(data.values), data.angles)
    m0, _, _ = _fit(plain, truth.material, False)
    m1, _, _ = _fit(plain, truth.material, True)
    np.testing.assert_array_equal(m0.normal, m1.normal)
