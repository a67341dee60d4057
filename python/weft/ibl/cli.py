"""``python -m weft ibl {convert,irradiance,extract-lights}``: the IBL tools on files.

Inputs: ``.hdr`` / ``.exr``, ``.npy`` (float image, or cube faces (6, S, S, 3)) and ``.png``
(sRGB decoded). The kind of image is guessed from its shape unless
``--source`` says it: 2:1 equirectangular, 4:3 / 3:4 cube cross, 1:1 mirror-ball sphere map.
Cube outputs are written as a cross (``--as cross``, default), equirectangular (``--as equirect``)
or raw faces (``--as faces``, ``.npy`` only).
"""

from __future__ import annotations

import argparse
import json
import math
import time
from typing import Any, List

import numpy as np

SOURCES = ("auto", "equirect", "cross", "sphere", "fisheye")


def add_ibl_parser(sub: Any) -> None:
    """Adds the ``ibl`` command and its subcommands to the top-level subparsers."""
    ibl = sub.add_parser("ibl", help="image-based lighting tools (convert, irradiance, lights)",
                         description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    cmds = ibl.add_subparsers(dest="ibl_command", metavar="IBL_COMMAND")
    cmds.required = True

    def common(p: argparse.ArgumentParser) -> None:
        p.add_argument("input", help="environment image (.hdr, .exr, .npy, .png)")
        p.add_argument("--source", choices=SOURCES, default="auto", help="kind of input image")
        p.add_argument("--wrap", type=float, default=1.0, help="sphere map wrap value (0, 1]")
        p.add_argument("--fov", type=float, default=180.0, help="fisheye field of view, degrees")
        p.add_argument("--cube-size", type=int, default=128, help="cube face size for the input")

    conv = cmds.add_parser("convert", help="capture -> cube map (cross, equirect or faces)")
    common(conv)
    conv.add_argument("output", help="output file (.hdr, .exr, .npy, .png)")
    conv.add_argument("--as", dest="layout", choices=("cross", "vertical-cross", "equirect",
                                                      "faces"), default="cross")
    conv.set_defaults(handler=cmd_convert)

    irr = cmds.add_parser("irradiance", help="irradiance map (SH9, exact, or the seed's blurs)")
    common(irr)
    irr.add_argument("output", nargs="?", default="", help="irradiance map file (optional)")
    irr.add_argument("--method", choices=("sh9", "exact", "exact-gpu", "box", "rotational"),
                     default="sh9", help="sh9 (default), exact cosine convolution on the CPU or "
                                         "as a Vulkan compute shader, or the seed's blurs")
    irr.add_argument("--size", type=int, default=32, help="output face size (32)")
    irr.add_argument("--as", dest="layout", choices=("cross", "vertical-cross", "equirect",
                                                     "faces"), default="cross")
    irr.set_defaults(handler=cmd_irradiance)

    lights = cmds.add_parser("extract-lights", help="bright lights (threshold or median cut)")
    common(lights)
    lights.add_argument("--method", choices=("threshold", "median-cut"), default="threshold")
    lights.add_argument("--count", type=int, default=16,
                        help="maximum lights (threshold) or lights (median cut, power of two)")
    lights.add_argument("--json", action="store_true", help="print JSON")
    lights.set_defaults(handler=cmd_extract_lights)


def load_cube(args: argparse.Namespace):
    """The input file as a CubeMap (weft.ibl.load_environment_cube; .npy faces keep their size)."""
    import weft
    import weft.ibl as ibl

    image = ibl.load_environment(args.input)
    size = image.shape[1] if image.ndim == 4 else args.cube_size
    if image.ndim == 3 and args.source == "auto":
        h, w = image.shape[:2]
        try:
            ibl.guess_source(w, h)
        except weft.InvalidArgument:
            raise ValueError(f"cannot tell the kind of a {w} x {h} image; pass --source") from None
    return ibl.load_environment_cube(args.input, size, source=args.source, wrap=args.wrap,
                                     fov=math.radians(args.fov))


def write_cube(path: str, cube, layout: str) -> None:
    import weft.ibl as ibl

    if layout == "faces":
        if not path.lower().endswith(".npy"):
            raise ValueError("--as faces writes .npy files")
        np.save(path, np.asarray(cube.faces))
        return
    if layout == "equirect":
        image = ibl.cube_to_equirect(cube, 4 * cube.size, 2 * cube.size)
    else:
        image = ibl.cube_to_cross(cube, "vertical" if layout == "vertical-cross" else "horizontal")
    ibl.save_environment(path, image)


def cmd_convert(args: argparse.Namespace) -> int:
    t0 = time.perf_counter()
    cube = load_cube(args)
    write_cube(args.output, cube, args.layout)
    print(f"wrote {args.output} (cube {cube.size}^2, {1e3 * (time.perf_counter() - t0):.1f} ms)")
    return 0


def cmd_irradiance(args: argparse.Namespace) -> int:
    import weft.ibl as ibl

    cube = load_cube(args)
    t0 = time.perf_counter()
    sh = None
    if args.method == "sh9":
        sh = ibl.project_sh9(cube)
        out = ibl.irradiance_from_sh(sh, args.size)
    elif args.method == "exact":
        out = ibl.irradiance_exact(cube, args.size)
    elif args.method == "exact-gpu":
        out = ibl.irradiance_exact_gpu(cube, args.size)
    elif args.method == "box":
        out = ibl.irradiance_box_blur(cube, args.size)
    else:
        out = ibl.irradiance_rotational_blur(cube, args.size)
    ms = 1e3 * (time.perf_counter() - t0)
    print(f"irradiance ({args.method}, {args.size}^2 faces): {ms:.2f} ms")
    if sh is not None:
        names = ["L00", "L1-1", "L10", "L11", "L2-2", "L2-1", "L20", "L21", "L22"]
        for name, c in zip(names, sh):
            print(f"  {name:<5} {c[0]: .6g} {c[1]: .6g} {c[2]: .6g}")
    if args.output:
        write_cube(args.output, out, args.layout)
        print(f"wrote {args.output}")
    return 0


def cmd_extract_lights(args: argparse.Namespace) -> int:
    import weft.ibl as ibl

    cube = load_cube(args)
    if args.method == "threshold":
        lights = ibl.extract_lights(cube, max_lights=args.count)
    else:
        lights = ibl.median_cut(cube, args.count)
    rows: List[dict] = [dict(direction=l.direction, colour=l.colour, solid_angle=l.solid_angle,
                             power=l.power) for l in lights]
    if args.json:
        print(json.dumps(rows, indent=2))
        return 0
    print(f"{len(rows)} light(s) ({args.method})")
    for i, r in enumerate(rows):
        d, c = r["direction"], r["colour"]
        print(f"  {i:2d} dir ({d[0]: .3f}, {d[1]: .3f}, {d[2]: .3f})  "
              f"colour ({c[0]:.4g}, {c[1]:.4g}, {c[2]:.4g})  {r['solid_angle']:.3g} sr")
    return 0
