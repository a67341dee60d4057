"""Video files as environment captures (SPEC §4.1: "an image sequence or video file can drive the
environment frame by frame").

:func:`read_video_frames` decodes a video file into the same thing an image sequence is: an
iterator of linear float32 (H, W, 3) frames. :func:`environments_from_video` feeds them to
:func:`weft.ibl.environments_from_frames`, so a video gets exactly the conversion an image
sequence gets (mirror-ball cut-out with a fixed rectangle or per-frame marker matrices, or the
whole frame as a sphere map / equirectangular panorama / cross / fisheye), one
:class:`weft.ibl.CubeMap` per frame. Driving a scene's lighting is then::

    env = weft.ibl.Environment(first_cube)
    scene.set_environment(env, dome_lights=16)
    for cube in weft.ibl.environments_from_video("ball.mkv", 64, source="sphere"):
        env.set_radiance(cube)          # new version: re-filtered at the next render
        image = renderer.render(scene, camera)

Decoding uses PyAV (``pip install av``; its wheels bundle FFmpeg), imported only when a video is
read, so weft works without it. 8-bit videos are decoded to RGB and the sRGB curve is removed
(``transfer="srgb"``, the default: what cameras and encoders write) or kept as stored
(``transfer="linear"``); videos with more than 8 bits per component are decoded at 16 bits, so
their precision survives. Missing files, files FFmpeg cannot read, files without a video stream
and videos without a frame raise :class:`weft.IoError`; a missing PyAV raises
:class:`weft.IoError` naming ``pip install av``.
"""

from __future__ import annotations

import os
from typing import Any, Iterator, Optional

import numpy as np

from weft._core import CubeMap, InvalidArgument, IoError
from weft.ibl.capture import _positive_int, environments_from_frames, srgb_to_linear

TRANSFERS = ("srgb", "linear")


def _import_av(path: str) -> Any:
    """PyAV, or a weft.IoError saying how to install it."""
    try:
        import av  # noqa: PLC0415 - optional dependency, imported only when a video is read
    except ImportError:
        raise IoError(f"{path}: reading video files needs PyAV, which is not installed "
                      "(pip install av)") from None
    return av


def _check_args(path: Any, max_frames: Optional[int], every: int, transfer: str) -> str:
    try:
        path = os.fspath(path)
    except TypeError:
        raise InvalidArgument(f"video path must be a str or os.PathLike, got "
                              f"{type(path).__name__}") from None
    if max_frames is not None and not _positive_int(max_frames):
        raise InvalidArgument(f"max_frames must be a positive integer or None, got {max_frames!r}")
    if not _positive_int(every):
        raise InvalidArgument(f"every must be a positive integer, got {every!r}")
    if transfer not in TRANSFERS:
        raise InvalidArgument(f"transfer must be one of {TRANSFERS}, got {transfer!r}")
    return path


def _to_linear(frame: Any, transfer: str) -> np.ndarray:
    """One decoded av.VideoFrame -> linear float32 (H, W, 3)."""
    deep = max((c.bits for c in frame.format.components), default=8) > 8
    if deep:
        x = frame.to_ndarray(format="rgb48le").astype(np.float32) / np.float32(65535.0)
    else:
        x = frame.to_ndarray(format="rgb24")
    if transfer == "srgb":
        return srgb_to_linear(x)
    x = x.astype(np.float32) / np.float32(255.0) if x.dtype == np.uint8 else x
    return np.ascontiguousarray(x, dtype=np.float32)


def read_video_frames(path: "str | os.PathLike[str]", max_frames: Optional[int] = None,
                      every: int = 1, transfer: str = "srgb") -> Iterator[np.ndarray]:
    """Decodes a video file (anything FFmpeg reads: .mkv, .mp4, .avi, .mov, ...) frame by frame.

    Yields linear float32 (H, W, 3) arrays, the first video stream's frames in presentation
    order: every ``every``-th frame starting with the first, at most ``max_frames`` of them.
    ``transfer``: ``"srgb"`` decodes the sRGB curve (the usual camera/encoder output),
    ``"linear"`` takes the stored values as linear (0..1). The file is opened when the iteration
    starts and closed when it ends or the iterator is dropped.

    Arguments are checked at the call; file problems surface at the first ``next``:
    :class:`weft.IoError` for a missing file, a file that is not a readable video, a file with
    no video stream, a stream that fails to decode, zero frames, or a missing PyAV.
    """
    path = _check_args(path, max_frames, every, transfer)
    return _frames(path, max_frames, every, transfer)


def _frames(path: str, max_frames: Optional[int], every: int,
            transfer: str) -> Iterator[np.ndarray]:
    if not os.path.exists(path):
        raise IoError(f"{path}: no such file")
    if os.path.isdir(path):
        raise IoError(f"{path}: is a directory, not a video file")
    av = _import_av(path)
    try:
        container = av.open(path, mode="r")
    except (av.error.FFmpegError, OSError, ValueError) as exc:
        raise IoError(f"{path}: not a readable video file ({exc})") from None
    try:
        if not container.streams.video:
            raise IoError(f"{path}: contains no video stream")
        stream = container.streams.video[0]
        decoded = yielded = 0
        try:
            for frame in container.decode(stream):
                if decoded % every == 0:
                    image = _to_linear(frame, transfer)
                    yielded += 1
                    yield image
                    if max_frames is not None and yielded >= max_frames:
                        return
                decoded += 1
        except (av.error.FFmpegError, OSError, ValueError) as exc:
            if isinstance(exc, IoError):
                raise
            raise IoError(f"{path}: decoding failed after {decoded} frame(s) ({exc})") from None
        if decoded == 0:
            raise IoError(f"{path}: the video stream contains no frames")
    finally:
        container.close()


def environments_from_video(path: "str | os.PathLike[str]", size: int,
                            max_frames: Optional[int] = None, every: int = 1,
                            transfer: str = "srgb", **capture: Any) -> Iterator[CubeMap]:
    """A video file's frames as cube maps of face ``size``: :func:`read_video_frames` (``path``,
    ``max_frames``, ``every``, ``transfer``) followed by the image-sequence conversion
    :func:`weft.ibl.environments_from_frames` with the keyword arguments in ``capture``:

    - ``rect=(x0, y0, x1, y1)``: the mirror ball at a fixed place (two-camera setup), or
      ``marker_to_camera=[M0, M1, ...]`` with ``centre``, ``radius`` and ``projection``
      (one-camera setup), plus ``sphere_size``, ``wrap``, ``world_to_sphere``;
    - ``source="sphere" | "equirect" | "cross" | "fisheye"``: the whole frame is that kind of
      capture (with ``wrap``, ``fov``, ``world_to_sphere``).

    Feed the cubes to :meth:`weft.ibl.Environment.set_radiance` to light a scene frame by frame
    (see the module doc). Errors as in :func:`read_video_frames`; bad capture arguments raise
    :class:`weft.InvalidArgument`.
    """
    frames = read_video_frames(path, max_frames=max_frames, every=every, transfer=transfer)
    return environments_from_frames(frames, size, **capture)
