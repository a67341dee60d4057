"""``python -m weft btf {synth,fit}``: synthetic datasets and the fitting report.

    python -m weft btf synth PRESET OUT [--size 256] [--views 1] [--zip] [--noise 0.004] ...
    python -m weft btf fit PATH --out DIR [--views frontal|all] [--gamma raw|linear] [--robust]
                                          [--solver auto|builtin|ceres] [--no-nonlinear]
                                          [--lafortune 0|1|2] ...

``synth`` writes the Bonn layout (folder, or a zip with --zip) and the ground truth as a
BtfMaterial folder (OUT/truth, or OUT.truth next to a zip). ``fit`` writes the maps of every
model (EXR + PNG + JSON), metrics.json and report.md with figures into DIR; when the dataset has
a ground truth (or --truth is given) the normal and ambient errors are reported too.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

import weft
from weft.bench import Progress, json_safe, markdown_table
from weft.btf import fit as btf_fit
from weft.btf import report, synth
from weft.btf.material import BtfMaterial


def add_parsers(sub: Any) -> None:
    """Adds the ``btf`` command with its ``synth`` and ``fit`` subcommands."""
    btf = sub.add_parser("btf", help="BTF datasets: synthesise one, or fit one and report",
                         description="BTF fitting (SPEC §3): 'synth' writes a synthetic dataset "
                                     "in the Bonn layout, 'fit' fits it and writes a report.")
    cmds = btf.add_subparsers(dest="btf_command", metavar="{synth,fit}")
    cmds.required = True

    s = cmds.add_parser("synth", help="write a synthetic BTF with its ground truth")
    s.add_argument("preset", choices=sorted(synth.PRESETS))
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
    s.add_argument("--seed", type=int, default=0)
    s.add_argument("--prefix", default="", help="file names 'PREFIX_NNNNN_tl.._pl.._tv.._pv..'")
    s.set_defaults(handler=cmd_synth)

    f = cmds.add_parser("fit", help="fit a BTF folder/zip and write maps, metrics and a report")
    f.add_argument("path", help="BTF folder or zip (Bonn layout)")
    f.add_argument("--out", required=True, help="output folder")
    f.add_argument("--views", default="frontal", help="'frontal', 'all' or 'T,P;T,P' degrees")
    f.add_argument("--gamma", choices=("raw", "linear"), default="raw")
    f.add_argument("--robust", action="store_true", help="outlier-robust linear fit (IRLS)")
    f.add_argument("--max-exponent", type=int, default=4096)
    f.add_argument("--per-texel-exponent", action="store_true")
    f.add_argument("--no-nonlinear", dest="nonlinear", action="store_false",
                   help="skip the per-texel Blinn-Phong fit")
    f.add_argument("--solver", choices=("auto", "builtin", "ceres"), default="builtin")
    f.add_argument("--lafortune", type=int, choices=(0, 1, 2), default=0,
                   help="also fit diffuse + this many Lafortune lobes (0 = no)")
    f.add_argument("--truth", default=None, help="ground-truth BtfMaterial folder")
    f.add_argument("--no-progress", dest="progress", action="store_false")
    f.set_defaults(handler=cmd_fit)


def truth_folder(path: str) -> Optional[str]:
    for candidate in (os.path.join(path, "truth"), path.rstrip("/") + ".truth"):
        if os.path.isfile(os.path.join(candidate, "material.json")):
            return candidate
    return None


def cmd_synth(args: argparse.Namespace) -> int:
    samples, truth = synth.synthesize(args.preset, args.size, views=args.views, noise=args.noise,
                                      seed=args.seed, shadows=args.shadows)
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


def _views(text: str) -> Any:
    if text in ("frontal", "all"):
        return text
    try:
        return [tuple(float(v) for v in part.split(",")) for part in text.split(";")]
    except ValueError:
        raise weft.InvalidArgument(f"--views must be 'frontal', 'all' or 'T,P;T,P', "
                                   f"got {text!r}") from None


def cmd_fit(args: argparse.Namespace) -> int:
    steps = 6 + int(args.nonlinear) + int(args.lafortune > 0)
    progress = Progress(steps, enabled=args.progress)
    times: Dict[str, float] = {}

    def timed(label: str, fn: Any, *a: Any, **k: Any) -> Any:
        progress.update(label)
        t0 = time.perf_counter()
        out = fn(*a, **k)
        times[label] = time.perf_counter() - t0
        progress.step(label)
        return out

    samples = timed("load", btf_fit.load, args.path, _views(args.views), args.gamma)
    linear = timed("linear fit", btf_fit.fit_linear, samples, robust=args.robust)
    spec_ns = timed("specular (n_s = (0,0,1))", btf_fit.fit_specular, samples, linear, True,
                    args.max_exponent, args.per_texel_exponent)
    spec_n = timed("specular (fitted n)", btf_fit.fit_specular, samples, linear, False,
                   args.max_exponent)
    models: Dict[str, BtfMaterial] = {"linear": linear.material(samples),
                                      "specular_eq4.29": spec_n.material,
                                      "specular_eq4.30": spec_ns.material}
    if args.nonlinear:
        bp = timed("Blinn-Phong", btf_fit.fit_blinn_phong, samples, spec_ns.material,
                   args.solver)
        models["blinn_phong"] = bp.material
    lafortune = None
    if args.lafortune:
        lafortune = timed("Lafortune", btf_fit.fit_lafortune, samples, spec_ns.material,
                          args.lafortune)
    progress.update("errors")
    results: Dict[str, Dict[str, Any]] = {}
    recons: Dict[str, np.ndarray] = {}
    for name, material in models.items():
        errors, recon = btf_fit.sample_errors(samples, material, reconstruct=True)
        recons[name] = recon
        results[name] = {"deviation": btf_fit.deviation(samples, errors),
                         "sample_deviation": (errors * 100).tolist()}
        if material.specular is not None:
            results[name]["exponent"] = ("per-texel" if material.exponent_map is not None
                                         else int(material.exponent))
    if lafortune is not None:
        errors = lafortune.errors(samples)
        results[f"lafortune_{args.lafortune}"] = {
            "deviation": btf_fit.deviation(samples, errors),
            "sample_deviation": (errors * 100).tolist()}
        folder = os.path.join(args.out, "maps", f"lafortune_{args.lafortune}")
        os.makedirs(folder, exist_ok=True)
        for name in ("normal", "diffuse", "ambient"):
            weft.save_exr(os.path.join(folder, f"{name}.exr"), getattr(lafortune, name))
        for j in range(args.lafortune):
            weft.save_exr(os.path.join(folder, f"lobe{j}_albedo.exr"),
                          np.ascontiguousarray(lafortune.lobe_albedo[:, :, j]))
            weft.save_exr(os.path.join(folder, f"lobe{j}_shape.exr"),
                          np.ascontiguousarray(lafortune.lobe_shape[:, :, j]))
    progress.step("errors")
    truth_dir = args.truth or truth_folder(args.path)
    truth_metrics = _truth_metrics(truth_dir, models) if truth_dir else None
    progress.update("report")
    write_outputs(args.out, samples, models, results, recons, linear, times, truth_metrics,
                  args)
    progress.step("report")
    progress.close()
    print(f"wrote maps, metrics.json and report.md to {args.out}")
    print(report.seed_tables(results))
    return 0


def _truth_metrics(folder: str, models: Dict[str, BtfMaterial]) -> Dict[str, Any]:
    truth = BtfMaterial.load(folder)
    out: Dict[str, Any] = {"folder": folder}
    for name, m in models.items():
        if m.shape != truth.shape:
            raise weft.InvalidArgument(f"ground truth {folder!r} has another size")
        stats = btf_fit.normal_stats(m.normal, truth.normal)
        stats["ambient_abs_error"] = float(np.mean(np.abs(m.ambient - truth.ambient)))
        out[name] = stats
    return out


def write_outputs(out: str, samples: Any, models: Dict[str, BtfMaterial],
                  results: Dict[str, Dict[str, Any]], recons: Dict[str, np.ndarray],
                  linear: btf_fit.LinearFit, times: Dict[str, float],
                  truth: Optional[Dict[str, Any]], args: argparse.Namespace) -> None:
    os.makedirs(out, exist_ok=True)
    for name, material in models.items():
        material.save(os.path.join(out, "maps", name))
    weft.save_png(os.path.join(out, "maps", "texture.png"), report.to_u8(linear.texture))
    h, w = samples.height, samples.width
    texels = [(w // 2, h // 2), (w // 4, h // 4), (3 * w // 4, h // 3)]
    figures = {name: report.write_figures(os.path.join(out, "figures"), samples, name,
                                          recons[name], texels) for name in models}
    best = list(models)[-1]  # figures and histogram of the last BtfMaterial model
    hist, bins = report.histogram_image(np.asarray(results[best]["sample_deviation"]))
    weft.save_png(os.path.join(out, "figures", "histogram.png"), hist)
    metrics = {"path": os.path.abspath(args.path), "samples": samples.count,
               "size": [w, h], "gamma": args.gamma, "robust": args.robust,
               "dark_texels": linear.dark_texels, "dark_channels": linear.dark_channels,
               "times_s": times, "models": results, "truth": truth, "histogram": bins,
               "figures": figures}
    with open(os.path.join(out, "metrics.json"), "w", encoding="utf-8") as f:
        json.dump(json_safe(metrics), f, indent=2)
    lines = [f"# BTF fit of `{args.path}`", "",
             f"{samples.count} samples of {w}x{h}, gamma '{args.gamma}', "
             f"robust {args.robust}; {linear.dark_texels} dark texels "
             f"(no equations; normal set to (0,0,1)), {linear.dark_channels} dark channels.", "",
             "## Deviation (%) per θ_l group and in total (the seed's tables 4.1-4.3)", "",
             report.seed_tables(results), "",
             "## Times", "", markdown_table(["step", "s"], [[k, f"{v:.3f}"]
                                                            for k, v in times.items()]), ""]
    if truth:
        rows = [[n, f"{t['mean_deg']:.3f}", f"{t['p95_deg']:.3f}", f"{t['ambient_abs_error']:.4f}"]
                for n, t in truth.items() if n != "folder"]
        lines += ["## Against the ground truth", "",
                  markdown_table(["model", "normal mean °", "normal p95 °", "ambient |err|"],
                                 rows), ""]
    lines += [f"## Per-sample deviation histogram ({best})", "", "![](figures/histogram.png)",
              "", markdown_table(["from %", "to %", "samples"],
                                 [[f"{a:.4f}", f"{b:.4f}", c] for a, b, c in bins]), "",
              "## Difference images (x4, first sample of each θ_l group)", ""]
    for name, files in figures.items():
        lines.append(f"**{name}**: " + " ".join(f"![{f}](figures/{f})"
                                                for f in files["difference"]))
        lines.append("")
    lines += ["## Polar plots (measurement | reconstruction; radius θ_l, angle φ_l)", ""]
    for name, files in figures.items():
        lines.append(f"**{name}**: " + " ".join(f"![{f}](figures/{f})" for f in files["polar"]))
        lines.append("")
    with open(os.path.join(out, "report.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines))


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Runs ``btf ...`` on its own (``python -m weft.btf.cli synth ...``)."""
    parser = argparse.ArgumentParser(prog="python -m weft")
    add_parsers(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["btf", *(argv or [])])
    return int(args.handler(args))


if __name__ == "__main__":
    import sys

    sys.exit(main(sys.argv[1:]))
