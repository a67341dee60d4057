"""``python -m weft btf {synth,fit}``: synthetic datasets and the fitting report.

    python -m weft btf synth PRESET OUT [--size 256] [--views 1] [--zip] [--noise 0.004] ...
    python -m weft btf fit PATH --out DIR [--views frontal|all] [--gamma raw|linear] [--robust]
                                          [--solver auto|builtin|ceres] [--no-nonlinear]
                                          [--lafortune 0|1|2 ...] [--truth DIR] ...
    python -m weft btf synth random OUT --seed N [--shadows] [--no-specular] [--highlight flat]

``synth`` writes the Bonn layout (folder, or a zip with --zip) and the ground truth as a
BtfMaterial folder (OUT/truth, or OUT.truth next to a zip). ``fit`` writes the maps of every
model (EXR + PNG + JSON), metrics.json and report.md with figures into DIR
(:mod:`weft.btf.fit_report`); when the dataset has a ground truth (or --truth is given) every
model is compared with it.
"""

from __future__ import annotations

import argparse
import os
from typing import Any, Optional, Sequence

import numpy as np

from weft.btf import fit_report, synth
from weft.reporting import add_progress_arguments


def add_parsers(sub: Any) -> None:
    """Adds the ``btf`` command with its ``synth`` and ``fit`` subcommands."""
    btf = sub.add_parser("btf", help="BTF datasets: synthesise one, or fit one and report",
                         description="BTF fitting (SPEC §3): 'synth' writes a synthetic dataset "
                                     "in the Bonn layout, 'fit' fits it and writes a report.")
    cmds = btf.add_subparsers(dest="btf_command", metavar="{synth,fit}")
    cmds.required = True

    s = cmds.add_parser("synth", help="write a synthetic BTF with its ground truth")
    s.add_argument("preset", choices=sorted(synth.PRESETS) + ["random"],
                   help="a preset, or 'random': a material drawn from --seed")
    s.add_argument("out", help="output folder (or zip file with --zip)")
    s.add_argument("--size", type=int, default=256, help="texels per side (256)")
    s.add_argument("--views", type=int, default=1, help="view directions, 1..81 (1 = frontal)")
    s.add_argument("--zip", action="store_true", help="write one zip archive")
    s.add_argument("--noise", type=float, default=0.004, help="sensor noise std (0.004)")
    s.add_argument("--format", choices=("jpg", "png"), default="jpg")
    s.add_argument("--quality", type=int, default=95, help="JPEG quality (95)")
    s.add_argument("--gamma", choices=("raw", "linear"), default="raw",
                   help="raw: values are stored as they are (the seed's convention); linear: "
                        "values are gamma-encoded with 1/2.2 (load with --gamma linear)")
    shadows = s.add_mutually_exclusive_group()
    shadows.add_argument("--shadows", dest="shadows", action="store_true", default=None,
                         help="cast shadows from the height field (preset default)")
    shadows.add_argument("--no-shadows", dest="shadows", action="store_false")
    s.add_argument("--seed", type=int, default=0,
                   help="random seed (noise; with 'random' the whole material)")
    s.add_argument("--no-specular", dest="specular", action="store_false",
                   help="'random': no specular lobe")
    s.add_argument("--highlight", choices=("random", "n", "flat"), default="random",
                   help="'random': the truth's highlight around n, around n_s = (0,0,1) "
                        "('flat', eq. 4.30) or drawn from the seed (default)")
    s.add_argument("--prefix", default="", help="file names 'PREFIX_NNNNN_tl.._pl.._tv.._pv..'")
    s.set_defaults(handler=cmd_synth)

    f = cmds.add_parser("fit", help="fit a BTF folder/zip and write maps, metrics and a report")
    f.add_argument("path", help="BTF folder or zip (Bonn layout)")
    f.add_argument("--out", required=True, help="output folder")
    add_fit_options(f)
    add_progress_arguments(f)
    f.set_defaults(handler=fit_report.cmd_fit)


def add_fit_options(f: Any, truth: bool = True) -> None:
    """The fit options of ``btf fit`` (also taken by ``python -m weft batch btf``, where each
    dataset's truth is found next to it: ``truth=False`` leaves out --truth)."""
    f.add_argument("--views", default="frontal", help="'frontal', 'all' or 'T,P;T,P' degrees")
    f.add_argument("--gamma", choices=("raw", "linear"), default="raw")
    f.add_argument("--robust", action="store_true", help="outlier-robust linear fit (IRLS)")
    f.add_argument("--max-exponent", type=int, default=None,
                   help="largest exponent (default: 4096 for the specular search, the "
                        "resolvable exponent of the light directions for Blinn-Phong)")
    f.add_argument("--per-texel-exponent", action="store_true")
    f.add_argument("--no-nonlinear", dest="nonlinear", action="store_false",
                   help="skip the per-texel Blinn-Phong fits")
    f.add_argument("--solver", choices=("auto", "builtin", "ceres"), default="builtin")
    f.add_argument("--luminance-normals", action="store_true",
                   help="Blinn-Phong: fit normals and exponents to the luma, colours to RGB "
                        "(for JPEG input, whose chroma is subsampled)")
    f.add_argument("--no-visibility", dest="visibility", action="store_false",
                   help="Blinn-Phong: fit every sample (no cast-shadow estimation)")
    f.add_argument("--pooled-exponent", action="store_true",
                   help="also fit the chosen Blinn-Phong highlight with its exponents pooled "
                        "over the material (model blinn_phong_pooled: one exponent where the "
                        "texels agree, weft.btf.exponent_pool)")
    f.add_argument("--lafortune", type=int, choices=(0, 1, 2), nargs="+", default=[1],
                   help="also fit diffuse + this many Lafortune lobes, e.g. '1 2' (0 = none; "
                        "default 1)")
    f.add_argument("--no-figures", dest="figures", action="store_false",
                   help="write maps, metrics.json and report.md without the matplotlib figures "
                        "(most of a small dataset's time)")
    if truth:
        f.add_argument("--truth", default=None, help="ground-truth BtfMaterial folder")


def cmd_synth(args: argparse.Namespace) -> int:
    if args.preset == "random":
        flat = {"random": None, "n": False, "flat": True}[args.highlight]
        samples, truth = synth.synthesize_random(args.seed, args.size, views=args.views,
                                                 noise=args.noise, specular=args.specular,
                                                 shadows=bool(args.shadows),
                                                 flat_specular_normal=flat)
    else:
        samples, truth = synth.synthesize(args.preset, args.size, views=args.views,
                                          noise=args.noise, seed=args.seed,
                                          shadows=args.shadows,
                                          specular=None if args.specular else 0.0)
    if args.zip:
        parent = os.path.dirname(os.path.abspath(args.out))
        os.makedirs(parent, exist_ok=True)
        truth_dir = args.out.rstrip("/") + ".truth"
    else:
        os.makedirs(args.out, exist_ok=True)
        truth_dir = os.path.join(args.out, "truth")
    synth.write(args.out, samples, fmt=args.format, quality=args.quality, zip=args.zip,
                gamma=args.gamma, prefix=args.prefix)
    truth.material.save(truth_dir)
    np.save(os.path.join(truth_dir, "height.npy"), truth.height)
    print(f"wrote {samples.count} images of {args.size}x{args.size} ({args.preset}) to "
          f"{args.out}; ground truth in {truth_dir}")
    return 0


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Runs ``btf ...`` on its own (``python -m weft.btf.cli synth ...``)."""
    parser = argparse.ArgumentParser(prog="python -m weft")
    add_parsers(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["btf", *(argv or [])])
    return int(args.handler(args))


if __name__ == "__main__":
    import sys

    sys.exit(main(sys.argv[1:]))
