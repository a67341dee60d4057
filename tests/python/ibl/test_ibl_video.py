"""Video files drive the environment frame by frame (SPEC §4.1, issue 6): a mirror-ball video
written here with PyAV (lossless FFV1, 8 and 16 bits) is read back through weft.ibl, frame count
and content checked against what was written, the planted sun found in the right direction, and
every bad input answered with a weft error."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import List

import numpy as np
import pytest
import weft
import weft.ibl as ibl
from ibl_envs import mirror_ball_directions
from weft.reference import ibl as ref_ibl

av = pytest.importorskip("av")

SIZE = 64          # sphere-map frame size (pixels)
FRAMES = 6
# per frame: the sun's direction (world; the ball's identity frame: +Y up, +Z towards the camera)
SUNS = [np.array([np.cos(a) * 0.6, 0.55, np.sin(a) * 0.6]) for a in
        np.linspace(0.0, 2.0 * np.pi, FRAMES, endpoint=False)]
SUNS = [s / np.linalg.norm(s) for s in SUNS]
TINTS = [np.array([0.15 + 0.1 * k, 0.2, 0.45 - 0.05 * k]) for k in range(FRAMES)]


def ball_frame(k: int, size: int = SIZE) -> np.ndarray:
    """Frame k as linear radiance (H, W, 3) in [0, 1]: a sky tinted TINTS[k] plus a bright
    (clipped to 1) sun of ~12 degrees around SUNS[k]."""
    d = mirror_ball_directions(size)
    sun = np.exp((d @ SUNS[k] - 1.0) / 0.01)[..., None]  # cos 12 deg ~ 0.978: exp(-2.2)
    sky = TINTS[k] * (0.6 + 0.4 * np.clip(d[..., 1:2], 0.0, 1.0))
    return np.clip(sky + sun, 0.0, 1.0)


def encode_srgb(linear: np.ndarray, bits: int) -> np.ndarray:
    x = np.clip(linear, 0.0, 1.0)
    s = np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)
    top = (1 << bits) - 1
    return np.rint(s * top).astype(np.uint8 if bits == 8 else np.uint16)


def write_video(path: Path, frames: List[np.ndarray], bits: int = 8, container: str = "") -> None:
    """Writes frames (uint8 or uint16 RGB) losslessly: FFV1 stores RGB exactly (bgr0 for 8 bits,
    gbrp16le for 16); the RGB -> stored -> RGB round trip is a permutation of the components,
    so the decoded frames equal the written ones bit for bit."""
    out = av.open(str(path), mode="w", format=container or None)
    stream = out.add_stream("ffv1", rate=10)
    stream.width, stream.height = SIZE, SIZE
    stream.pix_fmt = "bgr0" if bits == 8 else "gbrp16le"
    for f in frames:
        frame = av.VideoFrame.from_ndarray(f, format="rgb24" if bits == 8 else "rgb48le")
        for packet in stream.encode(frame):
            out.mux(packet)
    for packet in stream.encode():
        out.mux(packet)
    out.close()


@pytest.fixture(scope="module", params=[8, 16], ids=["8bit", "16bit"])
def ball_video(request, tmp_path_factory) -> tuple:
    bits = request.param
    path = tmp_path_factory.mktemp("video") / f"ball{bits}.mkv"
    stored = [encode_srgb(ball_frame(k), bits) for k in range(FRAMES)]
    write_video(path, stored, bits)
    return path, stored, bits


def angle_deg(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.degrees(np.arccos(np.clip(a @ b / np.linalg.norm(a) / np.linalg.norm(b),
                                              -1.0, 1.0))))


def test_frames_are_read_back_exactly_as_linear_float(ball_video) -> None:
    path, stored, bits = ball_video
    frames = list(ibl.read_video_frames(path))
    assert len(frames) == FRAMES
    top = float((1 << bits) - 1)
    for k, (got, want) in enumerate(zip(frames, stored)):
        assert got.dtype == np.float32 and got.shape == (SIZE, SIZE, 3)
        # lossless codec: exactly the sRGB decoding of what was written
        np.testing.assert_allclose(got, ibl.srgb_to_linear(want.astype(np.float64) / top),
                                   atol=1e-6)
        # and the linear radiance it encodes, to the quantisation step (8 bits: 1/255 in sRGB
        # is at most ~0.0052 linear at the bright end)
        assert np.abs(got - ball_frame(k)).max() < (6e-3 if bits == 8 else 5e-5)
        # the per-frame tint and sun are what change: the mean colour follows them (measured
        # 1.4e-3 / 1.6e-5 off at 8 / 16 bits: rounding to the nearest sRGB code is not
        # unbiased in linear terms)
        np.testing.assert_allclose(got.mean(axis=(0, 1)), ball_frame(k).mean(axis=(0, 1)),
                                   atol=3e-3 if bits == 8 else 1e-4)
    # frames differ from each other (the sequence really changes per frame)
    assert np.abs(frames[0] - frames[1]).max() > 0.5


def test_frame_selection_and_transfer(ball_video) -> None:
    path, stored, bits = ball_video
    picked = list(ibl.read_video_frames(path, every=2, max_frames=2))
    full = list(ibl.read_video_frames(path))
    assert len(picked) == 2
    np.testing.assert_array_equal(picked[0], full[0])
    np.testing.assert_array_equal(picked[1], full[2])
    assert len(list(ibl.read_video_frames(path, every=4))) == 2  # frames 0 and 4
    raw = next(ibl.read_video_frames(path, transfer="linear"))
    np.testing.assert_allclose(raw, stored[0] / float((1 << bits) - 1), atol=1e-6)


def test_video_drives_the_environment_like_an_image_sequence(ball_video) -> None:
    path, _, _ = ball_video
    cubes = list(ibl.environments_from_video(path, 32, source="sphere", wrap=1.0))
    assert len(cubes) == FRAMES and all(c.size == 32 for c in cubes)
    # the same conversion as the sequence path fed with the decoded frames, bit for bit
    seq = list(ibl.environments_from_frames(ibl.read_video_frames(path), 32, source="sphere",
                                            wrap=1.0))
    for a, b in zip(cubes, seq):
        np.testing.assert_array_equal(np.asarray(a.faces), np.asarray(b.faces))
    dirs = ibl.cube_texel_directions(32).reshape(-1, 3)
    env = ibl.Environment(cubes[0])
    versions = [env.version]
    for k, cube in enumerate(cubes):
        faces = np.asarray(cube.faces).reshape(-1, 3)
        lum = faces @ np.array([0.2126, 0.7152, 0.0722])
        # the planted sun: the brightest texels point at it
        bright = dirs[lum >= 0.95 * lum.max()].mean(axis=0)
        assert angle_deg(bright, SUNS[k]) < 2.0, (k, angle_deg(bright, SUNS[k]))  # 0.5 meas.
        # away from the sun the sky has this frame's tint (colour ratios to green)
        sky = faces[(dirs @ SUNS[k] < 0.5) & (dirs[:, 1] > 0.3)].mean(axis=0)
        np.testing.assert_allclose(sky / sky[1], TINTS[k] / TINTS[k][1], rtol=0.02)
        # frame by frame into one Environment: a new version and the new radiance each time
        env.set_radiance(cube)
        versions.append(env.version)
        # the environment now holds this frame: its SH9 projection is the NumPy reference's of
        # the frame's cube, and the horizontal part of band 1 (Y11 ~ x, Y10 ~ z: the sky's
        # gradient and tint are symmetric about the y axis, so only the sun contributes) points
        # at the sun's azimuth
        sh = np.asarray(env.irradiance_sh(), np.float64)
        np.testing.assert_allclose(sh, ref_ibl.project_sh9(np.asarray(cube.faces, np.float64)),
                                   rtol=1e-4, atol=1e-6)
        azimuth = np.array([sh[3].sum(), 0.0, sh[2].sum()])
        assert angle_deg(azimuth, SUNS[k] * [1.0, 0.0, 1.0]) < 3.0  # measured <= 1.1 degrees
    assert versions == sorted(set(versions))  # strictly increasing


def test_mirror_ball_cut_out_of_a_larger_video_frame(tmp_path: Path) -> None:
    # the two-camera setup: the ball fills a fixed rectangle of a bigger frame
    ball = encode_srgb(ball_frame(2), 8)
    frame = np.full((SIZE, SIZE, 3), 40, np.uint8)
    frame[16:48, 8:40] = ball[::2, ::2]
    path = tmp_path / "room.avi"
    write_video(path, [frame, frame], container="avi")
    cubes = list(ibl.environments_from_video(path, 16, rect=(8, 16, 40, 48), sphere_size=32,
                                             wrap=1.0))
    assert len(cubes) == 2
    dirs = ibl.cube_texel_directions(16).reshape(-1, 3)
    lum = np.asarray(cubes[0].faces).reshape(-1, 3).sum(axis=1)
    assert angle_deg(dirs[np.argmax(lum)], SUNS[2]) < 12.0  # 16^2 faces: ~5.6 deg texels


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(weft.IoError, match="no such file"):
        next(ibl.read_video_frames(tmp_path / "nope.mkv"))
    with pytest.raises(weft.IoError, match="directory"):
        next(ibl.read_video_frames(tmp_path))


def test_not_a_video(tmp_path: Path) -> None:
    text = tmp_path / "notes.mkv"
    text.write_text("these are not video frames\n" * 20)
    with pytest.raises(weft.IoError, match="not a readable video"):
        next(ibl.read_video_frames(text))
    empty = tmp_path / "empty.mp4"
    empty.write_bytes(b"")
    with pytest.raises(weft.IoError, match="not a readable video"):
        list(ibl.environments_from_video(empty, 8, source="sphere"))
    # a sound file: readable by FFmpeg, but no pictures
    wav = tmp_path / "tone.wav"
    out = av.open(str(wav), mode="w")
    stream = out.add_stream("pcm_s16le", rate=8000)
    samples = (1000 * np.sin(np.arange(800) * 0.1)).astype(np.int16)[None]
    frame = av.AudioFrame.from_ndarray(samples, format="s16", layout="mono")
    frame.sample_rate = 8000
    for packet in list(stream.encode(frame)) + list(stream.encode()):
        out.mux(packet)
    out.close()
    with pytest.raises(weft.IoError, match="no video stream"):
        next(ibl.read_video_frames(wav))


def test_zero_frames(tmp_path: Path) -> None:
    # AVI writes its header with a video stream and no frames at all
    path = tmp_path / "empty.avi"
    out = av.open(str(path), mode="w")
    stream = out.add_stream("ffv1", rate=10)
    stream.width, stream.height, stream.pix_fmt = SIZE, SIZE, "bgr0"
    out.start_encoding()
    out.close()
    with pytest.raises(weft.IoError, match="no frames"):
        next(ibl.read_video_frames(path))
    with pytest.raises(weft.IoError, match="no frames"):
        list(ibl.environments_from_video(path, 8, source="equirect"))


def test_truncated_video_keeps_the_frames_before_the_damage(tmp_path: Path) -> None:
    path = tmp_path / "ball.mkv"
    write_video(path, [encode_srgb(ball_frame(k), 8) for k in range(FRAMES)])
    cut = tmp_path / "cut.mkv"
    data = path.read_bytes()
    cut.write_bytes(data[:len(data) // 2])
    try:
        frames = list(ibl.read_video_frames(cut))
    except weft.IoError as exc:  # FFmpeg may also report the damage: a weft error either way
        assert "cut.mkv" in str(exc)
    else:
        assert 0 < len(frames) < FRAMES
        assert all(np.isfinite(f).all() for f in frames)


@pytest.mark.parametrize("kwargs, message", [
    (dict(max_frames=0), "max_frames"), (dict(max_frames=1.5), "max_frames"),
    (dict(every=0), "every"), (dict(transfer="gamma22"), "transfer"),
])
def test_bad_arguments_are_rejected_at_the_call(tmp_path: Path, kwargs, message) -> None:
    with pytest.raises(weft.InvalidArgument, match=message):
        ibl.read_video_frames(tmp_path / "any.mkv", **kwargs)


def test_bad_capture_arguments_are_rejected_at_the_call(ball_video) -> None:
    path = ball_video[0]
    with pytest.raises(weft.InvalidArgument, match="exactly one"):
        ibl.environments_from_video(path, 16)
    with pytest.raises(weft.InvalidArgument, match="exactly one"):
        ibl.environments_from_video(path, 16, source="sphere", rect=(0, 0, 8, 8))
    with pytest.raises(weft.InvalidArgument, match="unknown source"):
        ibl.environments_from_video(path, 16, source="cubemap")
    with pytest.raises(weft.InvalidArgument, match="cube size"):
        ibl.environments_from_video(path, 0, source="sphere")


def test_missing_pyav_names_the_install_command(ball_video, monkeypatch) -> None:
    monkeypatch.setitem(sys.modules, "av", None)  # import av -> ImportError
    with pytest.raises(weft.IoError, match="pip install av"):
        next(ibl.read_video_frames(ball_video[0]))
