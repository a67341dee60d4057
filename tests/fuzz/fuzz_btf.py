"""Fuzz targets for the BTF reader (issue 13): what weft.btf.load reads from a folder or a zip,
and the JPEG / PNG decoding of its images.

- ``btfzip``: the bytes of a zip file (seeds: small valid 81-image BTF zips, stored and deflated).
- ``btftree``: a folder or zip built from the input by FuzzedDataProvider: entry count, names
  (valid Bonn names, ``__MACOSX/`` and ``._*`` entries, nested folders, odd bytes, duplicates)
  and contents (valid tiny JPEG / PNG / EXR, or bytes from the input).
- ``jpeg``: bytes decoded as the BTF reader decodes an image (``_core.btf_decode_image``, JPEG or
  PNG by signature).
"""

from __future__ import annotations

import io
import os
import shutil
import tempfile
import zipfile

from outcome_feedback import outcome  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")

_PREFIXES = ["", "", "", "__MACOSX/", "sub/", "a/b/c/", "._", "__MACOSX/._", "sub/._"]
_EXTENSIONS = [".jpg", ".jpg", ".png", ".exr", ".JPEG", ".txt", ""]


def _standard_names():
    import weft

    return [f"00000 tl{int(t):03d} pl{int(p):03d} tv000 pv000"
            for t, p in weft._core.btf_standard_directions()]


def _tiny_images():
    """Valid 4x4 images of every kind the reader decodes (bytes), read from the seed corpus."""
    out = []
    for path in ("jpeg/rgb.jpg", "jpeg/grey.png", "jpeg/rgb16.png", "exr/ramp.exr"):
        with open(os.path.join(CORPUS, path), "rb") as f:
            out.append(f.read())
    return out


def _safe_parts(name: str):
    """A fuzzed entry name as folder parts that stay inside the temporary folder."""
    parts = [p.replace("\0", "_") for p in name.split("/")]
    parts = [p[:100] for p in parts if p not in ("", ".", "..")]
    return parts


def _tree_entries(data: bytes, names, images):
    import atheris

    fdp = atheris.FuzzedDataProvider(data)
    entries = []
    if fdp.ConsumeBool():  # a complete set to mutate, so that loads can get far
        content = images[fdp.ConsumeIntInRange(0, len(images) - 1)]
        entries = [(n + ".jpg", content) for n in names]
    for _ in range(fdp.ConsumeIntInRange(0, 40)):
        kind = fdp.ConsumeIntInRange(0, 3)
        if kind == 0:
            stem = names[fdp.ConsumeIntInRange(0, len(names) - 1)]
        elif kind == 1:
            stem = fdp.ConsumeUnicodeNoSurrogates(40)
        elif kind == 2:
            stem = (f"x tl{fdp.ConsumeIntInRange(0, 999)} pl{fdp.ConsumeIntInRange(0, 999)} "
                    f"tv{fdp.ConsumeIntInRange(0, 999)} pv{fdp.ConsumeIntInRange(0, 999)}")
        else:
            stem = (names[fdp.ConsumeIntInRange(0, len(names) - 1)] +
                    fdp.ConsumeUnicodeNoSurrogates(8))
        name = (_PREFIXES[fdp.ConsumeIntInRange(0, len(_PREFIXES) - 1)] + stem +
                _EXTENSIONS[fdp.ConsumeIntInRange(0, len(_EXTENSIONS) - 1)])
        pick = fdp.ConsumeIntInRange(0, len(images) + 1)
        content = (images[pick] if pick < len(images) else
                   fdp.ConsumeBytes(fdp.ConsumeIntInRange(0, 2048)))
        if entries and fdp.ConsumeBool():  # replace one of the set instead of adding
            entries[fdp.ConsumeIntInRange(0, len(entries) - 1)] = (name, content)
        else:
            entries.append((name, content))
    return entries, fdp.ConsumeBool(), fdp.ConsumeBool()


def make_target(target: str):
    import weft

    work = tempfile.mkdtemp(prefix="weft-fuzz-btf-")
    zpath = os.path.join(work, "in.zip")
    if target == "jpeg":
        def one(data: bytes) -> None:
            try:
                outcome(weft._core.btf_decode_image(data, "fuzz"))
            except weft.Error as e:
                outcome(error=e)
        return one
    if target == "btfzip":
        def one(data: bytes) -> None:
            with open(zpath, "wb") as f:
                f.write(data)
            try:
                outcome(weft.btf.load(zpath, threads=1))
            except weft.Error as e:
                outcome(error=e)
        return one
    names, images = _standard_names(), _tiny_images()
    folder = os.path.join(work, "tree")

    def one(data: bytes) -> None:
        entries, as_zip, deflate = _tree_entries(data, names, images)
        if as_zip:
            buf = io.BytesIO()
            method = zipfile.ZIP_DEFLATED if deflate else zipfile.ZIP_STORED
            with zipfile.ZipFile(buf, "w", method) as z:
                for name, content in entries:
                    # zipfile cuts a name at NUL and drops leading '/': it cannot write an entry
                    # whose name becomes empty (a limit of the harness, not of weft)
                    if zipfile.ZipInfo(name).filename:
                        z.writestr(name, content)
            with open(zpath, "wb") as f:
                f.write(buf.getvalue())
            path = zpath
        else:
            shutil.rmtree(folder, ignore_errors=True)
            os.makedirs(folder)
            for name, content in entries:
                parts = _safe_parts(name)
                if not parts:
                    continue
                target_path = os.path.join(folder, *parts)
                try:
                    os.makedirs(os.path.dirname(target_path), exist_ok=True)
                    with open(target_path, "wb") as f:
                        f.write(content)
                except (IsADirectoryError, NotADirectoryError, FileExistsError, OSError):
                    continue  # a name that is both a file and a folder: the file system says no
            path = folder
        try:
            outcome(weft.btf.load(path, threads=1))
        except weft.Error as e:
            outcome(error=e)
    return one


def write_seeds() -> None:
    import numpy as np
    import weft
    from PIL import Image

    jdir = os.path.join(CORPUS, "jpeg")
    os.makedirs(jdir, exist_ok=True)
    rgb = (np.arange(4 * 4 * 3, dtype=np.uint8).reshape(4, 4, 3) * 5)
    Image.fromarray(rgb).save(os.path.join(jdir, "rgb.jpg"), quality=90)
    Image.fromarray(rgb[..., 0]).save(os.path.join(jdir, "grey.jpg"), quality=90)
    big = np.tile(rgb, (4, 4, 1))
    Image.fromarray(big).save(os.path.join(jdir, "progressive.jpg"), quality=80, progressive=True)
    Image.fromarray(big).save(os.path.join(jdir, "sub420.jpg"), quality=70, subsampling=2)
    weft.save_png(os.path.join(jdir, "grey.png"), rgb[..., :1].copy())
    grey16 = (np.arange(16, dtype=np.uint16).reshape(4, 4) * 4000)
    Image.fromarray(grey16).save(os.path.join(jdir, "rgb16.png"))

    samples, _ = weft.btf.synthesize("wool", 4)
    zdir = os.path.join(CORPUS, "btfzip")
    os.makedirs(zdir, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for fmt in ("jpg", "png"):
            weft.btf.write(os.path.join(tmp, fmt), samples, fmt=fmt, quality=50, zip=True)
            shutil.copy(os.path.join(tmp, fmt), os.path.join(zdir, f"wool_{fmt}.zip"))
        # The writer stores entries; a deflated copy (and a __MACOSX twin of one entry) too.
        with zipfile.ZipFile(os.path.join(tmp, "png")) as src, \
                zipfile.ZipFile(os.path.join(zdir, "wool_png_deflated.zip"), "w",
                                zipfile.ZIP_DEFLATED) as dst:
            for i, info in enumerate(src.infolist()):
                dst.writestr(info.filename, src.read(info))
                if i == 0:
                    dst.writestr("__MACOSX/._" + info.filename, b"\0\5\26\7 mac metadata")
    tdir = os.path.join(CORPUS, "btftree")
    os.makedirs(tdir, exist_ok=True)
    # FuzzedDataProvider input: "complete set" flag, no extras, then zip / folder.
    for name, data in (("set_folder", b"\x01\x00\x00\x00\x00"),
                       ("set_zip", b"\x01\x00" + b"\x01" * 8)):
        with open(os.path.join(tdir, name), "wb") as f:
            f.write(data)
