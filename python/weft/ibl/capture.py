"""Capture conveniences: LDR decoding, environment files, cube crosses and the one-camera
mirror-ball setup (SPEC §4.1).

Cube crosses use the cube-map face orientation unchanged (weft/CubeMap.h):
horizontal (4 x 3 faces): row 0 ``. +Y . .``, row 1 ``-X +Z +X -Z``, row 2 ``. -Y . .``;
vertical (3 x 4 faces): row 0 ``. +Y .``, row 1 ``-X +Z +X``, row 2 ``. -Y .``, row 3 ``. -Z .``
with -Z turned by 180 degrees. Neighbouring cells then share their edges.
"""

from __future__ import annotations

import os
from typing import Iterable, Iterator, Optional, Sequence, Tuple

import numpy as np

from weft._core import (
    CubeMap,
    InvalidArgument,
    IoError,
    equirect_to_cube,
    fill_unseen,
    fisheye_to_cube,
    sphere_to_cube,
)

#: (row, column) of each face (+X, -X, +Y, -Y, +Z, -Z) in the crosses, in face units.
_HORIZONTAL = ((1, 2), (1, 0), (0, 1), (2, 1), (1, 1), (1, 3))
_VERTICAL = ((1, 2), (1, 0), (0, 1), (2, 1), (1, 1), (3, 1))


def _positive_int(value: object) -> bool:
    """True for an int (Python or NumPy, not bool) >= 1."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, bool) and value >= 1


def srgb_to_linear(image: np.ndarray) -> np.ndarray:
    """Decodes sRGB: uint8 (0..255) or float (0..1) -> linear float32 (alpha dropped)."""
    a = np.asarray(image)
    if a.dtype == np.uint8:
        x = a.astype(np.float64) / 255.0
    elif np.issubdtype(a.dtype, np.floating):
        x = a.astype(np.float64)
    else:
        raise InvalidArgument(f"sRGB image must be uint8 or float, got {a.dtype}")
    if x.ndim == 3 and x.shape[2] in (2, 4):
        x = x[..., :-1]
    lin = np.where(x <= 0.04045, x / 12.92, ((x + 0.055) / 1.055) ** 2.4)
    return lin.astype(np.float32)


#: Largest radiance an environment file may hold: far above any capture (the sun's disc is
#: about 1e9 W/(sr m^2)), low enough that resampling sums stay finite in float32 (an RGBE or
#: float file can hold up to ~3e38, whose averages overflow to inf).
MAX_RADIANCE = 1e30


def _checked_radiance(a: np.ndarray, name: str) -> np.ndarray:
    """``a`` as contiguous float32, refused unless finite, >= 0 and <= MAX_RADIANCE (after the
    cast: float64 values beyond float32's range would become inf)."""
    if not (np.issubdtype(a.dtype, np.floating) or np.issubdtype(a.dtype, np.integer)):
        raise InvalidArgument(f"{name} must be float (linear), got {a.dtype}")
    with np.errstate(over="ignore", invalid="ignore"):
        out = np.ascontiguousarray(a, dtype=np.float32)
    if not np.all(np.isfinite(out)):
        raise InvalidArgument(f"{name} must be finite (found NaN/inf, or values beyond float32)")
    if out.size and (out.min() < 0.0 or out.max() > MAX_RADIANCE):
        raise InvalidArgument(f"{name}: radiance must be in [0, {MAX_RADIANCE:g}], got "
                              f"[{out.min():g}, {out.max():g}]")
    return out


def _float_image(image: np.ndarray, name: str) -> np.ndarray:
    a = np.asarray(image)
    if a.dtype == np.uint8:
        return srgb_to_linear(a)
    if not np.issubdtype(a.dtype, np.floating):
        raise InvalidArgument(f"{name} must be float (linear) or uint8 (sRGB), got {a.dtype}")
    if a.ndim == 2:
        a = a[..., None]
    if a.ndim != 3 or a.shape[2] not in (1, 3, 4):
        raise InvalidArgument(f"{name} must have shape (H, W), (H, W, 1), (H, W, 3) or (H, W, 4)")
    if a.shape[2] == 1:
        a = np.repeat(a, 3, axis=2)
    if not np.all(np.isfinite(a)):
        raise InvalidArgument(f"{name} must be finite (found NaN/inf)")
    with np.errstate(over="ignore", invalid="ignore"):
        out = np.ascontiguousarray(a[..., :3], dtype=np.float32)
    if not np.all(np.isfinite(out)):
        raise InvalidArgument(f"{name} has values beyond float32's range")
    return out


#: Largest .npy array load_environment reads (bytes of data): a 16384 x 8192 RGB float32
#: equirect is 1.5 GiB.
MAX_NPY_BYTES = 4 << 30


def _load_npy(path: str) -> np.ndarray:
    """A .npy file's array, its header checked before the data is read: the shape must fit the
    file and MAX_NPY_BYTES (a forged header must not make numpy allocate the claim), no pickled
    objects. Any failure to parse is weft.IoError."""
    fmt = np.lib.format
    try:
        size = os.path.getsize(path)
        with open(path, "rb") as f:
            version = fmt.read_magic(f)
            if version == (1, 0):
                shape, _, dtype = fmt.read_array_header_1_0(f)
            elif version == (2, 0):
                shape, _, dtype = fmt.read_array_header_2_0(f)
            else:
                raise ValueError(f"unsupported .npy version {version}")
            data_bytes = size - f.tell()
        need = int(np.prod(shape, dtype=np.float64)) * dtype.itemsize
        if dtype.hasobject:
            raise ValueError("it holds Python objects")
        if need > MAX_NPY_BYTES:
            raise ValueError(f"its header claims {need} bytes, more than {MAX_NPY_BYTES}")
        if need > data_bytes:
            raise ValueError(f"its header claims {need} bytes, the file holds {data_bytes}")
        return np.load(path, allow_pickle=False)
    except Exception as exc:  # numpy's parser raises ValueError, EOFError, TokenError, ...
        raise IoError(f"{path}: not a readable .npy file ({type(exc).__name__}: {exc})") from None


def load_environment(path: str) -> np.ndarray:
    """Reads an environment image as linear float32 (H, W, 3): ``.hdr`` / ``.exr``, ``.npy``
    (float, or cube faces (6, S, S, 3)) or ``.png`` (sRGB decoded). Missing, truncated or corrupt
    files raise weft.IoError; radiance that is not finite, negative or above MAX_RADIANCE raises
    weft.InvalidArgument."""
    import weft

    ext = os.path.splitext(path)[1].lower()
    if not os.path.exists(path):
        raise IoError(f"{path}: no such file")
    if ext == ".png":
        return srgb_to_linear(weft.load_png(path))
    if ext == ".npy":
        a = _load_npy(path)
        if a.ndim == 4:
            if a.shape[0] != 6 or a.shape[1] != a.shape[2] or a.shape[3] != 3:
                raise InvalidArgument(f"{path}: cube faces must have shape (6, S, S, 3), got "
                                      f"{a.shape}")
            return _checked_radiance(a, path)
        return _checked_radiance(_float_image(a, path), path)
    if ext == ".hdr":
        return _checked_radiance(_float_image(weft.load_hdr(path), path), path)
    if ext == ".exr":
        return _checked_radiance(_float_image(weft.load_exr(path), path), path)
    raise InvalidArgument(f"{path}: unsupported environment format {ext!r} "
                          "(use .hdr, .exr, .npy or .png)")


#: What ``source="auto"`` guesses from an image's shape (width x height).
SOURCE_BY_SHAPE = "2:1 equirect, 4:3 or 3:4 cross, 1:1 sphere map"


def guess_source(width: int, height: int) -> str:
    """The kind of capture an image of this shape is: 'equirect' (2:1), 'cross' (4:3 or 3:4) or
    'sphere' (square mirror-ball sphere map); InvalidArgument for any other shape."""
    if width == 2 * height:
        return "equirect"
    if width * 3 == height * 4 or width * 4 == height * 3:
        return "cross"
    if width == height:
        return "sphere"
    raise InvalidArgument(f"cannot tell the kind of a {width} x {height} environment image "
                          f"({SOURCE_BY_SHAPE}); give the source (equirect, cross, sphere or "
                          "fisheye)")


def load_environment_cube(path: str, size: int = 64, source: str = "auto", wrap: float = 1.0,
                          fov: float = np.pi, matrix: Optional[np.ndarray] = None) -> CubeMap:
    """An environment file as a world-space radiance CubeMap of face ``size``: any image
    :func:`load_environment` reads, converted by :func:`to_cube` as ``source`` says ('auto':
    :func:`guess_source`), or ``.npy`` cube faces (6, S, S, 3) resampled to ``size``. ``wrap``
    and ``matrix`` (world -> sphere / camera) apply to sphere maps and fisheyes, ``fov``
    (radians) to fisheyes. Unseen regions are filled. Errors: weft.IoError for unreadable files,
    weft.InvalidArgument for bad parameters, shapes or non-finite or negative radiance."""
    if not _positive_int(size):
        raise InvalidArgument(f"cube size must be a positive integer, got {size!r}")
    if source not in ("auto", "equirect", "cross", "sphere", "fisheye"):
        raise InvalidArgument(f"unknown source {source!r}: use auto, equirect, cross, sphere or "
                              "fisheye")
    if not (isinstance(wrap, (int, float, np.integer, np.floating)) and np.isfinite(wrap)
            and 0.0 < wrap <= 1.0):
        raise InvalidArgument(f"wrap must be a number in (0, 1], got {wrap!r}")
    image = load_environment(path)
    if image.ndim == 4:
        if image.shape[0] != 6 or image.shape[1] != image.shape[2] or image.shape[3] != 3:
            raise InvalidArgument(f"{path}: cube faces must have shape (6, S, S, 3), got "
                                  f"{image.shape}")
        cube = CubeMap(np.ascontiguousarray(image, np.float32))
        return cube if cube.size == size else resize_cube(cube, int(size))
    if source == "auto":
        source = guess_source(image.shape[1], image.shape[0])
    if np.any(image < 0.0):
        raise InvalidArgument(f"{path}: radiance must be >= 0")
    return to_cube(image, source, int(size), wrap=wrap, fov=fov, matrix=matrix)


def save_environment(path: str, image: np.ndarray) -> None:
    """Writes a float image (H, W, 3): ``.npy``, ``.hdr`` / ``.exr`` or ``.png`` (sRGB encoded,
    clipped)."""
    import weft

    ext = os.path.splitext(path)[1].lower()
    a = np.ascontiguousarray(image, dtype=np.float32)
    if ext == ".npy":
        np.save(path, a)
    elif ext == ".png":
        x = np.clip(a, 0.0, 1.0)
        srgb = np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)
        weft.save_png(path, np.rint(srgb * 255.0).astype(np.uint8))
    elif ext == ".hdr":
        weft.save_hdr(path, a)
    elif ext == ".exr":
        weft.save_exr(path, a)
    else:
        raise InvalidArgument(f"{path}: cannot write {ext!r} (use .npy, .hdr, .exr or .png)")


def cross_to_cube(image: np.ndarray, layout: str = "auto") -> CubeMap:
    """Cube cross (horizontal 4x3 or vertical 3x4, see the module doc) -> CubeMap."""
    a = _float_image(image, "cube cross")
    h, w = a.shape[:2]
    if layout == "auto":
        layout = "horizontal" if w * 3 == h * 4 else "vertical" if w * 4 == h * 3 else ""
        if not layout:
            raise InvalidArgument(f"a cube cross must be 4:3 or 3:4, got {w} x {h}")
    if layout not in ("horizontal", "vertical"):
        raise InvalidArgument("cross layout must be 'horizontal', 'vertical' or 'auto'")
    s = w // 4 if layout == "horizontal" else w // 3
    expected = (3 * s, 4 * s) if layout == "horizontal" else (4 * s, 3 * s)
    if s < 1 or (h, w) != expected:
        raise InvalidArgument(f"{layout} cross must be {expected[1]} x {expected[0]}, "
                              f"got {w} x {h}")
    cells = _HORIZONTAL if layout == "horizontal" else _VERTICAL
    faces = np.empty((6, s, s, 3), np.float32)
    for f, (r, c) in enumerate(cells):
        cell = a[r * s:(r + 1) * s, c * s:(c + 1) * s]
        faces[f] = cell[::-1, ::-1] if (layout == "vertical" and f == 5) else cell
    return CubeMap(faces)


def cube_to_cross(cube, layout: str = "horizontal") -> np.ndarray:
    """CubeMap or (6, S, S, 3) -> cross image (black outside the faces)."""
    faces = np.asarray(cube.faces if isinstance(cube, CubeMap) else cube, dtype=np.float32)
    if faces.ndim != 4 or faces.shape[0] != 6 or faces.shape[1] != faces.shape[2]:
        raise InvalidArgument("cube must have shape (6, S, S, 3)")
    s = faces.shape[1]
    if layout not in ("horizontal", "vertical"):
        raise InvalidArgument("cross layout must be 'horizontal' or 'vertical'")
    out = np.zeros((3 * s, 4 * s, 3) if layout == "horizontal" else (4 * s, 3 * s, 3), np.float32)
    cells = _HORIZONTAL if layout == "horizontal" else _VERTICAL
    for f, (r, c) in enumerate(cells):
        face = faces[f][::-1, ::-1] if (layout == "vertical" and f == 5) else faces[f]
        out[r * s:(r + 1) * s, c * s:(c + 1) * s] = face
    return out


def to_cube(image: np.ndarray, source: str, size: int, wrap: float = 1.0,
            fov: float = np.pi, matrix: Optional[np.ndarray] = None,
            fill: bool = True) -> CubeMap:
    """Any supported capture -> CubeMap. ``source``: 'equirect', 'cross', 'sphere' (mirror ball,
    with ``wrap`` and the world->sphere ``matrix``) or 'fisheye' (``fov`` radians, world->camera
    ``matrix``). Unseen regions are filled (push-pull) when ``fill``."""
    if source == "cross":
        cube = cross_to_cube(image)
        return cube if cube.size == size else resize_cube(cube, size)
    img = _float_image(image, "environment image")
    if source == "equirect":
        return equirect_to_cube(img, size)
    if source == "sphere":
        cube, valid = sphere_to_cube(img, size, matrix, wrap)
    elif source == "fisheye":
        cube, valid = fisheye_to_cube(img, size, fov, matrix)
    else:
        raise InvalidArgument(f"unknown source {source!r}: use equirect, cross, sphere or fisheye")
    return fill_unseen(cube, valid) if fill and not valid.all() else cube


def resize_cube(cube: CubeMap, size: int) -> CubeMap:
    """Resamples a cube map to ``size`` (trilinear from its mip chain, seamless)."""
    from weft._core import cube_texel_directions

    src = cube.copy()
    src.build_mips()
    lod = max(0.0, float(np.log2(src.size / size)))
    dirs = cube_texel_directions(size).reshape(-1, 3)
    return CubeMap(np.asarray(src.sample(dirs, lod), np.float32).reshape(6, size, size, 3))


def sphere_rect(marker_to_camera: np.ndarray, centre: Sequence[float], radius: float,
                projection: np.ndarray, width: int,
                height: int) -> Tuple[float, float, float, float]:
    """The one-camera setup (seed §3.3.1): bounding rectangle of the mirror ball in pixels,
    ``(x0, y0, x1, y1)`` with y down. ``c_eye = M c``; corners ``c_eye -+ (r, r, 0)`` are
    projected by ``P`` to OpenGL-style NDC (y up) and mapped to the image."""
    m = np.asarray(marker_to_camera, np.float64)
    p = np.asarray(projection, np.float64)
    c = np.asarray(centre, np.float64)
    if m.shape != (4, 4) or p.shape != (4, 4) or c.shape != (3,):
        raise InvalidArgument("marker_to_camera and projection must be 4x4, centre a 3-vector")
    if not (np.all(np.isfinite(m)) and np.all(np.isfinite(p)) and np.all(np.isfinite(c))):
        raise InvalidArgument("camera matrices and centre must be finite")
    if not (np.isfinite(radius) and radius > 0) or width < 1 or height < 1:
        raise InvalidArgument("radius must be > 0 and the image size positive")
    eye = m @ np.append(c, 1.0)
    corners = []
    for sign in (-1.0, 1.0):
        q = p @ (eye + np.array([sign * radius, sign * radius, 0.0, 0.0]))
        if not abs(q[3]) > 1e-12:
            raise InvalidArgument("the ball projects to infinity (w = 0)")
        corners.append(q[:2] / q[3])
    (lx, ly), (ux, uy) = corners
    x0, x1 = sorted(((lx * 0.5 + 0.5) * width, (ux * 0.5 + 0.5) * width))
    y0, y1 = sorted(((0.5 - ly * 0.5) * height, (0.5 - uy * 0.5) * height))
    return float(x0), float(y0), float(x1), float(y1)


def cut_out_sphere(frame: np.ndarray, rect: Tuple[float, float, float, float],
                   size: int) -> np.ndarray:
    """Resamples the rectangle ``(x0, y0, x1, y1)`` (pixels, y down) of a frame into a square
    ``size`` x ``size`` sphere map (bilinear, edges clamped)."""
    img = _float_image(frame, "frame")
    x0, y0, x1, y1 = (float(v) for v in rect)
    if size < 1 or not (np.isfinite([x0, y0, x1, y1]).all() and x1 > x0 and y1 > y0):
        raise InvalidArgument("rectangle must be finite with x1 > x0, y1 > y0, and size >= 1")
    h, w = img.shape[:2]
    t = (np.arange(size) + 0.5) / size
    px = np.clip(x0 + t * (x1 - x0) - 0.5, 0.0, w - 1.0)
    py = np.clip(y0 + t * (y1 - y0) - 0.5, 0.0, h - 1.0)
    ix = np.minimum(np.floor(px).astype(int), w - 2) if w > 1 else np.zeros(size, int)
    iy = np.minimum(np.floor(py).astype(int), h - 2) if h > 1 else np.zeros(size, int)
    fx = (px - ix)[None, :, None] if w > 1 else np.zeros((1, size, 1))
    fy = (py - iy)[:, None, None] if h > 1 else np.zeros((size, 1, 1))
    ix1 = np.minimum(ix + 1, w - 1)
    iy1 = np.minimum(iy + 1, h - 1)
    top = img[iy][:, ix] * (1 - fx) + img[iy][:, ix1] * fx
    bottom = img[iy1][:, ix] * (1 - fx) + img[iy1][:, ix1] * fx
    return (top * (1 - fy) + bottom * fy).astype(np.float32)


def environments_from_frames(frames: Iterable[np.ndarray], size: int, sphere_size: int = 256,
                             rect: Optional[Tuple[float, float, float, float]] = None,
                             marker_to_camera: Optional[Iterable[np.ndarray]] = None,
                             centre: Sequence[float] = (0.0, 0.0, 0.0), radius: float = 0.05,
                             projection: Optional[np.ndarray] = None, wrap: float = 0.9,
                             world_to_sphere: Optional[np.ndarray] = None,
                             source: Optional[str] = None, fov: float = np.pi,
                             fill: bool = True) -> Iterator[CubeMap]:
    """Frame by frame (an image sequence, or a video through
    :func:`weft.ibl.environments_from_video`), one CubeMap of face ``size`` per frame.

    Mirror ball in a larger frame: cut the ball out (fixed ``rect`` = two-camera setup, or
    per-frame ``marker_to_camera`` matrices with ``centre``/``radius``/``projection`` = one-camera
    setup) into a ``sphere_size`` sphere map, convert it with ``wrap`` and ``world_to_sphere``
    and (``fill``) fill what the ball cannot show. Whole-frame captures: ``source`` ('sphere',
    'equirect', 'cross' or 'fisheye') converts each frame with :func:`to_cube` (``wrap``,
    ``fov``, ``world_to_sphere``, ``fill``). Exactly one of ``rect``, ``marker_to_camera`` and
    ``source`` must be given; the choice is checked when called, each frame when it is reached."""
    given = sum(x is not None for x in (rect, marker_to_camera, source))
    if given != 1:
        raise InvalidArgument("give exactly one of a fixed rect, per-frame marker_to_camera "
                              "matrices or a whole-frame source")
    if marker_to_camera is not None and projection is None:
        raise InvalidArgument("the one-camera setup needs the projection matrix")
    if source is not None and source not in ("sphere", "equirect", "cross", "fisheye"):
        raise InvalidArgument(f"unknown source {source!r}: use equirect, cross, sphere or fisheye")
    if not _positive_int(size):
        raise InvalidArgument(f"cube size must be a positive integer, got {size!r}")
    return _environments(frames, int(size), sphere_size, rect, marker_to_camera, centre, radius,
                         projection, wrap, world_to_sphere, source, fov, fill)


def _environments(frames, size, sphere_size, rect, marker_to_camera, centre, radius, projection,
                  wrap, world_to_sphere, source, fov, fill) -> Iterator[CubeMap]:
    matrices = iter(marker_to_camera) if marker_to_camera is not None else None
    for frame in frames:
        if source is not None:
            yield to_cube(frame, source, size, wrap=wrap, fov=fov, matrix=world_to_sphere,
                          fill=fill)
            continue
        img = _float_image(frame, "frame")
        r = rect
        if matrices is not None:
            try:
                m = next(matrices)
            except StopIteration:
                raise InvalidArgument("fewer marker matrices than frames") from None
            r = sphere_rect(m, centre, radius, projection, img.shape[1], img.shape[0])
        sphere = cut_out_sphere(img, r, sphere_size)
        cube, valid = sphere_to_cube(sphere, size, world_to_sphere, wrap)
        yield fill_unseen(cube, valid) if fill and not valid.all() else cube
