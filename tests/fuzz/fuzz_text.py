"""Fuzz targets for weft's text inputs and environment files (issue 13).

- ``scene`` / ``renderer`` / ``lights``: the seed's text files (weft.ibl.files.load_scene,
  load_renderer, load_lights), the input's bytes as the file.
- ``script``: the demo's ``--script`` file (weft.load_demo_script, the parser run_demo uses).
- ``env``: an environment file through weft.ibl.load_environment_cube (what the CLI's and the
  demo's --environment read): the input's first byte picks the extension (.hdr, .exr, .npy,
  .png) and the source (auto, equirect, cross, sphere, fisheye), the rest is the file.
"""

from __future__ import annotations

import os
import tempfile

from outcome_feedback import file_target, outcome  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")

ENV_EXTENSIONS = [".hdr", ".exr", ".npy", ".png"]
ENV_SOURCES = ["auto", "equirect", "cross", "sphere", "fisheye"]


def make_target(target: str):
    import weft
    import weft.ibl.files as files

    fd, path = tempfile.mkstemp(prefix="weft-fuzz-text-")
    os.close(fd)
    if target == "env":
        paths = {ext: path + ext for ext in ENV_EXTENSIONS}

        def one(data: bytes) -> None:
            if not data:
                return
            ext = ENV_EXTENSIONS[data[0] % len(ENV_EXTENSIONS)]
            source = ENV_SOURCES[(data[0] // len(ENV_EXTENSIONS)) % len(ENV_SOURCES)]
            with open(paths[ext], "wb") as f:
                f.write(data[1:])
            try:
                cube = weft.ibl.load_environment_cube(paths[ext], size=4, source=source)
            except weft.Error as e:
                outcome(error=e)
                return
            outcome(cube.faces)
            import numpy as np
            faces = np.asarray(cube.faces)
            if not np.all(np.isfinite(faces)) or np.any(faces < 0):
                raise AssertionError("environment cube with non-finite or negative radiance")
        return one
    load = {"scene": files.load_scene, "renderer": files.load_renderer,
            "lights": files.load_lights, "script": weft.load_demo_script}[target]
    return file_target(load, path)


SEEDS = {
    "scene": {"seed.scene": "# the seed's scene file\nMODEL 1 models/cloth.obj textures\n"
                            "MODEL 2 models/sphere.obj textures // a comment\nEFFECT 1 phong\n"
                            "EFFECT 2 ibl_diffuse\n"},
    "renderer": {"seed.renderer": "IBLMODEL 1 1 0 0 0 0 90 0 1 1 1\n"
                                  "IBLMODEL 2 2 0.5 -1 2.5 10 20 30 0.5 0.5 0.5\n"},
    "lights": {"seed.lights": "DIRLIGHT 1 0 1 0\nDIRLIGHT 2 1 1 1 0.5 0.4 0.3\n"
                              "PERSPLIGHT 3 0 0 0 4 4 4 60 1.0 0.1 100\n"},
    "script": {"seed.script": "# frame action args\n0 key SPACE\n3 grab 320 240\n4 drag 330.5 250\n"
                              "6 release\n8 key a\n9 key LEFT\n10 set exposure 1.5\n"
                              "11 set fur marschner\n"},
}


def write_seeds() -> None:
    import numpy as np
    import weft

    for target, seeds in SEEDS.items():
        os.makedirs(os.path.join(CORPUS, target), exist_ok=True)
        for name, text in seeds.items():
            with open(os.path.join(CORPUS, target, name), "w") as f:
                f.write(text)
    edir = os.path.join(CORPUS, "env")
    os.makedirs(edir, exist_ok=True)
    rng = np.random.default_rng(3)
    with tempfile.TemporaryDirectory() as tmp:
        def seed(name, ext, source, write):
            p = os.path.join(tmp, "x" + ext)
            write(p)
            selector = ENV_EXTENSIONS.index(ext) + len(ENV_EXTENSIONS) * ENV_SOURCES.index(source)
            with open(p, "rb") as f, open(os.path.join(edir, name), "wb") as out:
                out.write(bytes([selector]) + f.read())
        equirect = rng.uniform(0, 3, (4, 8, 3)).astype(np.float32)
        cross = rng.uniform(0, 3, (6, 8, 3)).astype(np.float32)
        seed("equirect_hdr", ".hdr", "auto", lambda p: weft.save_hdr(p, equirect))
        seed("cross_exr", ".exr", "cross", lambda p: weft.save_exr(p, cross))
        seed("sphere_png", ".png", "sphere",
             lambda p: weft.save_png(p, (rng.uniform(0, 255, (6, 6, 3))).astype(np.uint8)))
        seed("fisheye_exr", ".exr", "fisheye", lambda p: weft.save_exr(p, equirect[:, :4].copy()))
        seed("cube_npy", ".npy", "auto",
             lambda p: np.save(p, rng.uniform(0, 2, (6, 2, 2, 3)).astype(np.float32)))
        seed("equirect_npy", ".npy", "equirect",
             lambda p: np.save(p, equirect.astype(np.float64)))
