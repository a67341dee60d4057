"""Fuzz targets for weft's loaders (issue 13), run with atheris (PyPI) over the Python entry
points: every input must give a result or a weft.Error (InvalidArgument / IoError) -- any other
exception, a crash, a hang or a sanitizer report is a finding.

    python tests/fuzz/fuzz_loaders.py TARGET [libFuzzer flags] [CORPUS_DIR ...]
    python tests/fuzz/fuzz_loaders.py hair -runs=1000000 tests/fuzz/corpus/hair

Targets: hair (.hair bytes), obj (OBJ text), png, hdr (Radiance), exr (here); btfzip, btftree,
jpeg (fuzz_btf.py); scene, renderer, lights, script, env (fuzz_text.py).
Seeds: ``python tests/fuzz/fuzz_loaders.py --write-seeds`` writes small valid files of every kind
into tests/fuzz/corpus/TARGET/ (checked in).
"""

from __future__ import annotations

import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")
SUFFIX = {"hair": ".hair", "obj": ".obj", "png": ".png", "hdr": ".hdr", "exr": ".exr"}
BTF_TARGETS = ("btfzip", "btftree", "jpeg")
TEXT_TARGETS = ("scene", "renderer", "lights", "script", "env")
TARGETS = tuple(SUFFIX) + BTF_TARGETS + TEXT_TARGETS

sys.path.insert(0, HERE)
from outcome_feedback import file_target, outcome  # noqa: E402


def _loader(target: str):
    import weft

    return {"obj": weft.load_obj, "png": weft.load_png, "hdr": weft.load_hdr,
            "exr": weft.load_exr}[target]


def make_target(target: str):
    import weft

    if target in BTF_TARGETS:
        import fuzz_btf
        return fuzz_btf.make_target(target)
    if target in TEXT_TARGETS:
        import fuzz_text
        return fuzz_text.make_target(target)
    if target == "hair":
        def one(data: bytes) -> None:
            try:
                outcome(weft.hair_from_bytes(data))
            except weft.Error as e:
                outcome(error=e)
        return one
    load = _loader(target)
    fd, path = tempfile.mkstemp(suffix=SUFFIX[target], prefix="weft-fuzz-")
    os.close(fd)
    return file_target(load, path)


def write_seeds() -> None:
    import numpy as np
    import weft

    for target in SUFFIX:
        os.makedirs(os.path.join(CORPUS, target), exist_ok=True)
    hair = weft.generate_hair(3, 18, seed=2)
    weft.save_hair(os.path.join(CORPUS, "hair", "three.hair"), hair)
    with open(os.path.join(CORPUS, "obj", "quad.obj"), "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf -1 -2 -3\n")
    rgba = (np.arange(4 * 4 * 4, dtype=np.uint8).reshape(4, 4, 4) * 3)
    weft.save_png(os.path.join(CORPUS, "png", "rgba.png"), rgba)
    weft.save_png(os.path.join(CORPUS, "png", "grey.png"), rgba[..., :1].copy())
    img = np.linspace(0.0, 4.0, 3 * 4 * 3, dtype=np.float32).reshape(3, 4, 3)
    weft.save_hdr(os.path.join(CORPUS, "hdr", "ramp.hdr"), img)
    weft.save_exr(os.path.join(CORPUS, "exr", "ramp.exr"), img)
    import fuzz_btf
    import fuzz_text
    fuzz_btf.write_seeds()
    fuzz_text.write_seeds()


def main(argv) -> None:
    if len(argv) > 1 and argv[1] == "--write-seeds":
        write_seeds()
        return
    if len(argv) < 2 or argv[1] not in TARGETS:
        sys.exit(__doc__)
    import atheris

    target = argv[1]
    # Python-level coverage of weft's wrappers and Python parsers only: instrumenting what they
    # import (NumPy, json, the standard library) took 7 s per start and adds only noise edges
    with atheris.instrument_imports(include=["weft"]):
        import weft  # noqa: F401
        import weft.btf  # noqa: F401
        import weft.ibl  # noqa: F401
        import weft.ibl.files  # noqa: F401
    one = make_target(target)
    import outcome_feedback
    outcome_feedback.instrument()
    atheris.Setup([argv[0]] + argv[2:], one)
    atheris.Fuzz()


if __name__ == "__main__":
    main(sys.argv)
