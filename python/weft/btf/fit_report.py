"""``python -m weft btf fit``: fit every model to one dataset and write maps, metrics and a report.

Models: the linear fit (plus the robust one with ``--robust``), linear + specular (eq. 4.29 and
4.30), per-texel Blinn-Phong with the highlight around n and around n_s = (0, 0, 1) (the one with
the lower deviation as drawn is chosen, both are reported), and diffuse + Lafortune lobes. Every
drawable model is scored as the renderer draws it; Lafortune cannot be drawn and is scored as
fitted, marked "not drawn". The best model (lowest deviation as drawn) leads every table and
figure; with a ground truth, every model is compared with it.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

import weft
from weft.bench import Progress, json_safe, markdown_table
from weft.btf import fit as btf_fit
from weft.btf import report, scoring
from weft.btf.material import BtfMaterial
from weft.btf.scoring import Scored


def truth_folder(path: str) -> Optional[str]:
    """The synthetic truth written next to a dataset by ``btf synth`` (OUT/truth, OUT.truth)."""
    for candidate in (os.path.join(path, "truth"), path.rstrip("/") + ".truth"):
        if os.path.isfile(os.path.join(candidate, "material.json")):
            return candidate
    return None


def parse_views(text: str) -> Any:
    if text in ("frontal", "all"):
        return text
    try:
        return [tuple(float(v) for v in part.split(",")) for part in text.split(";")]
    except ValueError:
        raise weft.InvalidArgument(f"--views must be 'frontal', 'all' or 'T,P;T,P', "
                                   f"got {text!r}") from None


class Fitter:
    """Runs the fits in order, timing each one and showing progress."""

    def __init__(self, samples: Any, steps: int, progress: Optional[bool]) -> None:
        self.samples = samples
        self.progress = Progress(steps, enabled=progress)
        self.scored: List[Scored] = []

    def run(self, label: str, fn: Any, *a: Any, **k: Any) -> Tuple[Any, float]:
        self.progress.update(label)
        t0 = time.perf_counter()
        out = fn(*a, **k)
        seconds = time.perf_counter() - t0
        self.progress.step(label)
        return out, seconds

    def add(self, name: str, model: Any, seconds: float, **extra: Any) -> Scored:
        s = scoring.score(self.samples, name, model, seconds, **extra)
        self.scored.append(s)
        return s


@dataclass
class Fitted:
    """One fitted model before scoring: its name, the model, fit seconds and report extras."""

    name: str
    model: Any
    seconds: float
    extra: Dict[str, Any] = field(default_factory=dict)


@dataclass
class SeedFits:
    """The whole-dataset fits (one pass over all texels each; the specular exponent is chosen
    over all texels): the per-texel fits start from ``flat`` and ``fitted``."""

    models: List[Fitted]
    linear: btf_fit.LinearFit
    flat: btf_fit.SpecularFit
    fitted: btf_fit.SpecularFit


def lafortune_lobes(args: argparse.Namespace) -> List[int]:
    return sorted({int(v) for v in args.lafortune if int(v) > 0})


def fit_steps(args: argparse.Namespace) -> int:
    """How many fits :func:`fit_all` runs for these options."""
    pooled = int(args.nonlinear and getattr(args, "pooled_exponent", False))
    return 4 + int(args.robust) + 2 * int(args.nonlinear) + pooled + len(lafortune_lobes(args))


def _threads(args: argparse.Namespace) -> int:
    return int(getattr(args, "threads", 0) or 0)


def seed_fits(samples: Any, args: argparse.Namespace, run: Any) -> SeedFits:
    """Linear (and robust linear) fit and both specular fits. ``run(label, fn, *a, **k)``
    returns (result, seconds) (:meth:`Fitter.run`)."""
    threads = _threads(args)
    models: List[Fitted] = []
    linear, t = run("linear fit", btf_fit.fit_linear, samples, threads=threads)
    models.append(Fitted("linear", linear.material(samples), t))
    seed_fit = linear
    if args.robust:
        seed_fit, t = run("robust linear fit", btf_fit.fit_linear, samples, robust=True,
                          threads=threads)
        models.append(Fitted("linear_robust", seed_fit.material(samples), t))
    search_max = args.max_exponent or 4096
    flat, t = run("specular (n_s = (0,0,1))", btf_fit.fit_specular, samples, seed_fit, True,
                  search_max, args.per_texel_exponent, threads=threads)
    models.append(Fitted("specular_eq4.30", flat.material, t))
    fitted, t = run("specular (fitted n)", btf_fit.fit_specular, samples, seed_fit, False,
                    search_max, threads=threads)
    models.append(Fitted("specular_eq4.29", fitted.material, t))
    return SeedFits(models, linear, flat, fitted)


def blinn_phong_fits(samples: Any, flat: BtfMaterial, fitted: BtfMaterial,
                     args: argparse.Namespace, run: Any,
                     noise: Optional[Dict[str, float]] = None) -> List[Fitted]:
    """Per-texel Blinn-Phong with both highlights, seeded by the specular fits ``fitted``
    (eq. 4.29) and ``flat`` (eq. 4.30). Every texel is fitted on its own (the exponent bound
    comes from the light directions only, the cast-shadow test's noise level from ``noise``,
    model name -> :func:`weft.btf.fit.shadow_noise` of the whole dataset, or estimated here when
    None), so a band of texels, samples and seeds cropped alike, given the whole dataset's
    noise, gives those rows of these maps."""
    out: List[Fitted] = []
    if not args.nonlinear:
        return out
    for name, seed, flat_ns in (("blinn_phong_n", fitted, False),
                                ("blinn_phong_flat", flat, True)):
        label = "Blinn-Phong (n_s = " + ("(0,0,1))" if flat_ns else "n)")
        bp, t = run(label, btf_fit.fit_blinn_phong, samples, seed, args.solver,
                    max_exponent=args.max_exponent, flat_specular_normal=flat_ns,
                    visibility=args.visibility, threads=_threads(args),
                    luminance_normals=getattr(args, "luminance_normals", False),
                    noise=(noise or {}).get(name))
        out.append(Fitted(name, bp.material, t, dict(
            solver=bp.solver, mean_iterations=bp.mean_iterations,
            shadowed_fraction=getattr(bp, "shadowed_fraction", None), noise=bp.noise)))
    return out


def shadow_noise_levels(samples: Any, flat: BtfMaterial, fitted: BtfMaterial,
                        args: argparse.Namespace) -> Optional[Dict[str, float]]:
    """The whole dataset's noise level per Blinn-Phong fit of :func:`blinn_phong_fits`
    (None when those fits or their visibility pass are off): what a fit in bands passes."""
    if not args.nonlinear or not args.visibility:
        return None
    return {name: btf_fit.shadow_noise(samples, seed, flat_ns, max_exponent=args.max_exponent,
                                       luminance_normals=getattr(args, "luminance_normals",
                                                                 False),
                                       threads=_threads(args))
            for name, seed, flat_ns in (("blinn_phong_n", fitted, False),
                                        ("blinn_phong_flat", flat, True))}


def blinn_phong_choice(samples: Any, scored: List[Scored]) -> Dict[str, Any]:
    """Which Blinn-Phong highlight (n_s = n or (0, 0, 1)) is drawn
    (:func:`weft.btf.scoring.highlight_choice`); {} without the Blinn-Phong fits."""
    by = {s.name: s for s in scored}
    if "blinn_phong_n" not in by or "blinn_phong_flat" not in by:
        return {}
    pick = scoring.highlight_choice(
        samples, {k: (by[k], by[k].extra.get("shadowed_fraction"))
                  for k in ("blinn_phong_n", "blinn_phong_flat")})
    return {"chosen": pick["chosen"], "deviation_n": by["blinn_phong_n"].deviation,
            "deviation_flat": by["blinn_phong_flat"].deviation, "rule": pick["rule"]}


def pooled_fits(samples: Any, scored: List[Scored], choice: Dict[str, Any],
                args: argparse.Namespace, run: Any) -> List[Fitted]:
    """With ``--pooled-exponent``: the chosen Blinn-Phong fit with its exponents pooled over the
    material (``exponent="pooled"`` from that per-texel fit; model ``blinn_phong_pooled``); []
    otherwise or without the Blinn-Phong fits. It needs every texel (the material's exponent
    spread), so a batch pools on the whole dataset too."""
    if not choice or not getattr(args, "pooled_exponent", False):
        return []
    flat_ns = choice["chosen"] == "blinn_phong_flat"
    seed = next(s.model for s in scored
                if s.name == ("specular_eq4.30" if flat_ns else "specular_eq4.29"))
    chosen = next(s for s in scored if s.name == choice["chosen"])
    first = btf_fit.NonlinearFit(chosen.model, chosen.extra["solver"],
                                 chosen.extra["mean_iterations"],
                                 chosen.extra["shadowed_fraction"] or 0.0, chosen.extra["noise"])
    bp, t = run("Blinn-Phong, pooled exponent", btf_fit.fit_blinn_phong, samples, seed,
                args.solver, max_exponent=args.max_exponent, flat_specular_normal=flat_ns,
                visibility=args.visibility, threads=_threads(args),
                luminance_normals=getattr(args, "luminance_normals", False),
                exponent="pooled", per_texel=first)
    pool = bp.exponent_pool or {}
    return [Fitted("blinn_phong_pooled", bp.material, t, dict(
        solver=bp.solver, mean_iterations=bp.mean_iterations,
        shadowed_fraction=bp.shadowed_fraction, highlight=choice["chosen"],
        pooled_exponent=pool.get("mean"), pooled_spread=pool.get("spread"),
        pooled_error_scale=pool.get("error_scale")))]


def lafortune_seed(flat: BtfMaterial, scored: List[Scored],
                   choice: Dict[str, Any]) -> Tuple[BtfMaterial, bool]:
    """(seed, fixed_normal) of the Lafortune fits: the chosen Blinn-Phong fit with its normal
    kept when there is one (with a frontal view the lobe depends on l_z only and trades off with
    the diffuse term), else the eq. 4.30 specular fit."""
    if not choice:
        return flat, False
    return next(s.model for s in scored if s.name == choice["chosen"]), True


def lafortune_fits(samples: Any, seed: BtfMaterial, fixed_normal: bool,
                   args: argparse.Namespace, run: Any) -> List[Fitted]:
    """Per-texel diffuse + Lafortune lobes (every count asked for), seeded by ``seed``; per
    texel like :func:`blinn_phong_fits`, so it splits into bands the same way."""
    out: List[Fitted] = []
    for count in lafortune_lobes(args):
        laf, t = run(f"Lafortune ({count} lobe{'s' if count > 1 else ''})",
                     btf_fit.fit_lafortune, samples, seed, count, threads=_threads(args),
                     fixed_normal=fixed_normal)
        out.append(Fitted(f"lafortune_{count}", laf, t,
                          dict(mean_iterations=laf.mean_iterations)))
    return out


def score_all(samples: Any, models: List[Fitted]) -> List[Scored]:
    return [scoring.score(samples, m.name, m.model, m.seconds, **m.extra) for m in models]


def fit_all(samples: Any, args: argparse.Namespace) -> Tuple[List[Scored], Dict[str, Any],
                                                               btf_fit.LinearFit]:
    """Fits every model; returns (scored models, Blinn-Phong choice, plain linear fit)."""
    f = Fitter(samples, fit_steps(args), args.progress)
    seeds = seed_fits(samples, args, f.run)
    scored = score_all(samples, seeds.models + blinn_phong_fits(
        samples, seeds.flat.material, seeds.fitted.material, args, f.run))
    choice = blinn_phong_choice(samples, scored)
    scored += score_all(samples, pooled_fits(samples, scored, choice, args, f.run))
    seed, fixed = lafortune_seed(seeds.flat.material, scored, choice)
    scored += score_all(samples, lafortune_fits(samples, seed, fixed, args, f.run))
    f.progress.close()
    return scored, choice, seeds.linear


def model_results(scored: List[Scored], best: Scored) -> Dict[str, Dict[str, Any]]:
    out: Dict[str, Dict[str, Any]] = {}
    for s in scored:
        r: Dict[str, Any] = {
            "label": ("★ " if s is best else "") + s.label, "drawn": s.drawable,
            "deviation": s.drawn or s.fitted, "fitted_deviation": s.fitted,
            "drawn_vs_fitted": (s.drawn["total"] / max(s.fitted["total"], 1e-300)
                                if s.drawn else None),
            "sample_deviation": (s.errors * 100).tolist(), "seconds": s.seconds,
            "outside_physical_space": scoring.physical_violations(s.model), **s.extra}
        if isinstance(s.model, BtfMaterial) and s.model.specular is not None:
            r["exponent"] = ("per-texel" if s.model.exponent_map is not None
                             else int(s.model.exponent))
        out[s.name] = r
    return out


def reconstruction(samples: Any, s: Scored) -> np.ndarray:
    """(S, 3, H, W) values of a model as drawn (Lafortune: as fitted)."""
    if s.drawable:
        return btf_fit.sample_errors(samples, s.model, reconstruct=True, drawn=True)[1]
    return scoring.lafortune_reconstruction(s.model, samples)


def write_figures(out: str, samples: Any, ordered: List[Scored]) -> Dict[str, Any]:
    """Difference figures per model, polar figures per texel (every model a row), histogram."""
    fig_dir = os.path.join(out, "figures")
    os.makedirs(fig_dir, exist_ok=True)
    angles = np.asarray(samples.angles)
    values = samples.values
    frontal = np.flatnonzero((angles[:, 2] == angles[0, 2]) & (angles[:, 3] == angles[0, 3]))
    firsts = [int(frontal[np.flatnonzero(angles[frontal, 0] == t)[0]])
              for t in np.unique(angles[frontal, 0])]
    h, w = samples.height, samples.width
    texels = [(w // 2, h // 2), (w // 4, h // 4)]
    series: Dict[str, np.ndarray] = {}
    files: Dict[str, Any] = {"difference": {}, "polar": [], "scales": {}}
    for k, s in enumerate(ordered):
        recon = reconstruction(samples, s)
        if k == 0:  # the best model's worst texel is the third polar plot
            err = ((recon[frontal] - values[frontal]) ** 2).sum(axis=(0, 1))
            y, x = np.unravel_index(int(np.argmax(err)), err.shape)
            texels.append((int(x), int(y)))
        series[s.label] = recon[frontal][:, :, [t[1] for t in texels], [t[0] for t in texels]]
        name = f"{s.name}_difference.png"
        top = report.plot_differences(os.path.join(fig_dir, name), f"{s.label}: |measured − "
                                      f"model|, first sample of each θ_l group", values[firsts],
                                      recon[firsts], angles[firsts, 0])
        files["difference"][s.name] = name
        files["scales"][f"{s.name}_difference"] = top
        del recon
    meas = values[frontal][:, :, [t[1] for t in texels], [t[0] for t in texels]]
    for i, (x, y) in enumerate(texels):
        name = f"polar_{x}_{y}.png"
        scale = report.plot_polar(os.path.join(fig_dir, name), (x, y), angles[frontal][:, :2],
                                  meas[:, :, i], {k: v[:, :, i] for k, v in series.items()})
        files["polar"].append(name)
        files["scales"][name] = scale
    files["texels"] = texels
    return files


def write_fit(args: argparse.Namespace, samples: Any, scored: List[Scored],
              choice: Dict[str, Any], linear: btf_fit.LinearFit,
              load_s: float) -> Tuple[Scored, Dict[str, Dict[str, Any]]]:
    """Ranks the scored models and writes maps, metrics.json, report.md and figures into
    ``args.out``; returns (best model, per-model results)."""
    best = scoring.best_of(scored)
    accurate = scoring.best_of(scored, drawable_only=False)
    ordered = [best] + [s for s in scored if s is not best]
    results = model_results(ordered, best)
    truth_dir = args.truth or truth_folder(args.path)
    truth = truth_table(truth_dir, ordered) if truth_dir else None
    write_outputs(args, samples, ordered, results, choice, best, accurate, linear, truth, load_s)
    return best, results


def cmd_fit(args: argparse.Namespace) -> int:
    t0 = time.perf_counter()
    samples = btf_fit.load(args.path, parse_views(args.views), args.gamma)
    load_s = time.perf_counter() - t0
    scored, choice, linear = fit_all(samples, args)
    best, results = write_fit(args, samples, scored, choice, linear, load_s)
    print(f"wrote maps, metrics.json, report.md and figures to {args.out}")
    print(f"best model (deviation as drawn): {best.name} {best.deviation:.4f}%")
    print(report.seed_tables(results))
    return 0


def truth_table(folder: str, scored: List[Scored]) -> Dict[str, Any]:
    truth = BtfMaterial.load(folder)
    out: Dict[str, Any] = {"folder": folder}
    for s in scored:
        try:
            out[s.name] = scoring.truth_errors(s.model, truth)
        except ValueError as exc:
            raise weft.InvalidArgument(f"ground truth {folder!r}: {exc}") from None
    return out


def write_maps(out: str, s: Scored) -> Dict[str, str]:
    folder = os.path.join(out, "maps", s.name)
    if isinstance(s.model, BtfMaterial):
        s.model.save(folder)
    else:
        os.makedirs(folder, exist_ok=True)
        for name in ("normal", "diffuse", "ambient"):
            weft.save_exr(os.path.join(folder, f"{name}.exr"), getattr(s.model, name))
        for j in range(s.model.lobe_shape.shape[2]):
            weft.save_exr(os.path.join(folder, f"lobe{j}_albedo.exr"),
                          np.ascontiguousarray(s.model.lobe_albedo[:, :, j]))
            weft.save_exr(os.path.join(folder, f"lobe{j}_shape.exr"),
                          np.ascontiguousarray(s.model.lobe_shape[:, :, j]))
    return report.write_previews(folder, report.model_maps(s.model))


def write_outputs(args: argparse.Namespace, samples: Any, ordered: List[Scored],
                  results: Dict[str, Dict[str, Any]], choice: Dict[str, Any], best: Scored,
                  accurate: Scored, linear: btf_fit.LinearFit, truth: Optional[Dict[str, Any]],
                  load_s: float) -> None:
    out = args.out
    draw = getattr(args, "figures", True)  # --no-figures: matplotlib is most of a small fit's time
    os.makedirs(os.path.join(out, "maps"), exist_ok=True)
    previews = {s.name: write_maps(out, s) for s in ordered}
    texture, how = report.preview("texture", linear.texture)
    weft.save_png(os.path.join(out, "maps", "texture.png"), texture)
    previews["texture"] = {"texture": how}
    errors = {s.label: s.errors * 100 for s in ordered}
    figures: Dict[str, Any] = {}
    if draw:
        figures = write_figures(out, samples, ordered)
        for s in ordered:
            name = f"{s.name}_maps.png"
            report.plot_maps(os.path.join(out, "figures", name), f"{s.label}: fitted maps",
                             report.model_maps(s.model))
            figures.setdefault("maps", {})[s.name] = name
        bins = report.plot_histogram(os.path.join(out, "figures", "histogram.png"), errors,
                                     best.label)
    else:
        bins = report.histogram_rows(errors, best.label)
    h, w = samples.height, samples.width
    metrics = {"path": os.path.abspath(args.path), "samples": samples.count, "size": [w, h],
               "gamma": args.gamma, "robust": args.robust, "best": best.name,
               "best_rule": "lowest total deviation as drawn among drawable models",
               "most_accurate": accurate.name, "blinn_phong_choice": choice,
               "dark_texels": linear.dark_texels, "dark_channels": linear.dark_channels,
               "times_s": {"load": load_s, **{s.name: s.seconds for s in ordered}},
               "models": results, "truth": truth, "histogram": bins, "figures": figures,
               "previews": previews}
    with open(os.path.join(out, "metrics.json"), "w", encoding="utf-8") as f:
        json.dump(json_safe(metrics), f, indent=2)
    with open(os.path.join(out, "report.md"), "w", encoding="utf-8") as f:
        f.write(markdown(args, samples, ordered, results, choice, best, accurate, linear, truth,
                         figures, previews, bins))


def markdown(args: argparse.Namespace, samples: Any, ordered: List[Scored],
             results: Dict[str, Dict[str, Any]], choice: Dict[str, Any], best: Scored,
             accurate: Scored, linear: btf_fit.LinearFit, truth: Optional[Dict[str, Any]],
             figures: Dict[str, Any], previews: Dict[str, Dict[str, str]],
             bins: List[Any]) -> str:
    h, w = samples.height, samples.width
    fmt = report.fmt
    lines = [f"# BTF fit of `{args.path}`", "",
             f"{samples.count} samples of {w}x{h}, gamma '{args.gamma}', robust {args.robust}; "
             f"{linear.dark_texels} dark texels (no equations; normal set to (0,0,1)), "
             f"{linear.dark_channels} dark channels.", "",
             f"**Best model: {best.name}** — the lowest total deviation as the renderer draws it "
             f"({best.deviation:.4f}%). It comes first in every table and figure (★)."]
    if accurate is not best:
        lines.append(f"The most accurate fit is {accurate.label} ({accurate.deviation:.4f}%), "
                     "which the renderer cannot draw.")
    if choice:
        lines += ["", f"Blinn-Phong highlight: n_s = n gives {choice['deviation_n']:.4f}%, "
                  f"n_s = (0,0,1) (eq. 4.30) {choice['deviation_flat']:.4f}% as drawn: "
                  f"**{choice['chosen']}** is chosen for this dataset."]
    lines += ["", "## Deviation (%) per θ_l group and in total (the seed's tables 4.1-4.3)", "",
              "Drawable models as drawn (8-bit maps, clamps, per-texel exponent); Lafortune as "
              "fitted (not drawn).", "", report.seed_tables(results), "",
              "## Models", ""]
    rows = []
    for s in ordered:
        r = results[s.name]
        rows.append([r["label"], fmt(s.drawn["total"] if s.drawn else None),
                     fmt(s.fitted["total"]), fmt(r["drawn_vs_fitted"], 3),
                     r["outside_physical_space"]["texels"], f"{s.seconds:.3f}"])
    lines += [markdown_table(["model", "deviation as drawn %", "as fitted %", "drawn / fitted",
                              "texels outside physical space", "fit s"], rows), ""]
    if truth:
        lines += ["## Against the ground truth", "", f"Truth: `{truth['folder']}`. Ambient term "
                  "= albedo x ambient (the additive constant); k_s and exponent: median relative "
                  "error over texels.", ""]
        rows = [[results[s.name]["label"], fmt(t["mean_deg"], 3), fmt(t["p95_deg"], 3),
                 fmt(t["albedo_abs_error"]), fmt(t["ambient_abs_error"]),
                 fmt(t["k_s_median_rel_error"], 3), fmt(t["exponent_median_rel_error"], 3)]
                for s in ordered for t in [truth[s.name]]]
        lines += [markdown_table(["model", "normal mean °", "normal p95 °", "albedo |err|",
                                  "ambient term |err|", "k_s rel. err", "exponent rel. err"],
                                 rows), ""]
    lines += ["## Fitted maps", "", "Previews in `maps/<model>/<map>_preview.png` are value / "
              f"scale (scale = the {report.PREVIEW_PERCENTILE:g}th percentile, so a few extreme "
              "texels do not turn the rest black); normals are (n + 1) / 2.", ""]
    for s in ordered:
        scales = ", ".join(f"{k}: {v}" for k, v in previews[s.name].items())
        lines += [f"**{results[s.name]['label']}** ({scales})", ""]
        if figures:
            lines += [f"![{s.name} maps](figures/{figures['maps'][s.name]})", ""]
    lines += [f"Texture T: {previews['texture']['texture']}.", "",
              f"## Per-sample deviation histogram (best: {best.name}, filled)", ""]
    if figures:
        lines += ["![histogram](figures/histogram.png)", ""]
    lines += [markdown_table(["from %", "to %", f"samples ({best.name})"],
                             [[f"{a:.4f}", f"{b:.4f}", c] for a, b, c in bins if c]), ""]
    if not figures:
        lines += ["Figures were not drawn (--no-figures).", ""]
        return "\n".join(lines)
    lines += ["## Difference images (first sample of each θ_l group; colour bar in luminance)",
              ""]
    for s in ordered:
        lines += [f"**{results[s.name]['label']}**", "",
                  f"![{s.name} difference](figures/{figures['difference'][s.name]})", ""]
    lines += ["## Polar plots (radius θ_l, angle φ_l; measurement | model | |difference|)", "",
              "Texels: the centre, a quarter in, and the best model's worst texel. Colours are "
              "value / scale with the scale in each figure's title.", ""]
    for name in figures["polar"]:
        lines += [f"![{name}](figures/{name})", ""]
    return "\n".join(lines)
