"""The BTF benchmark's report: the issue's targets (pass / fail), Markdown tables and the error
against time plot (:mod:`weft.bench.btf` measures)."""

from __future__ import annotations

from typing import Any, Dict, List, Optional

import numpy as np

from weft.bench import markdown_table
from weft.reporting import pyplot, save_figure

NONLINEAR = ("Blinn-Phong", "Lafortune")
CHOSEN = "Blinn-Phong (chosen)"
#: the recommended pipeline (the chosen highlight, exponents pooled): what the accuracy
#: targets judge; runs without it (older JSON) judge CHOSEN
POOLED = "Blinn-Phong (chosen, pooled exponent)"


def _worst(rows: List[Dict[str, Any]], key: str, highest: bool = True) -> Optional[Dict[str, Any]]:
    rows = [r for r in rows if r.get(key) is not None]
    if not rows:
        return None
    return (max if highest else min)(rows, key=lambda r: r[key])


def _target(label: str, rows: List[Dict[str, Any]], key: str, limit: float,
            higher_is_better: bool = False, by_format: bool = True) -> Dict[str, Any]:
    """The worst row of ``rows`` against ``limit``, per file format (PNG and JPEG hurt the fits
    very differently) unless ``by_format`` is False."""
    groups = {"png": [r for r in rows if r.get("format") == "png"],
              "jpg": [r for r in rows if r.get("format") == "jpg"]} if by_format else \
        {"all": rows}
    out: Dict[str, Any] = {"target": label, "limit": limit, "per_format": {}}
    for fmt, sel in groups.items():
        worst = _worst(sel, key, highest=not higher_is_better)
        if worst is None:
            out["per_format"][fmt] = {"measured": None, "met": None, "where": "-"}
            continue
        value = worst[key]
        met = value >= limit if higher_is_better else value <= limit
        out["per_format"][fmt] = {"measured": value, "met": bool(met),
                                  "where": f"{worst['case']} {worst['model']}"}
    verdicts = [g["met"] for g in out["per_format"].values() if g["met"] is not None]
    out["met"] = all(verdicts) if verdicts else None
    return out


def targets(rows: List[Dict[str, Any]], speed: Dict[str, Any], evaluated: bool) -> Dict[str, Any]:
    """Issue 12's targets, each judged on its worst row (per format for the accuracy ones)."""
    nonlinear = [r for r in rows if r["model"].startswith(NONLINEAR) and r["model"] != CHOSEN]
    chosen = [r for r in rows if r["model"] == CHOSEN]
    best = [r for r in rows if r["model"] == POOLED] or chosen
    clear = [r for r in best if not r["shadows"]]
    shadowed = [r for r in best if r["shadows"]]
    with_spec = [r for r in clear if r["specular"]]
    bp_all = [r for r in rows if r["model"].startswith("Blinn-Phong") and r["model"] != CHOSEN]
    bp_rate = min(v for k, v in speed.items() if k.startswith("blinn_phong_")
                  and k.endswith("texels_per_s") and not k.endswith("cpu_texels_per_s"))
    bp_speed_row = {"case": f"random{speed.get('seed', '')} {speed['size']}²",
                    "model": "Blinn-Phong (slowest of n / (0,0,1), with / without shadows)",
                    "rate": bp_rate}
    cpu_rates = [v for k, v in speed.items() if k.endswith("cpu_texels_per_s")]
    bp_cpu_row = {"case": bp_speed_row["case"], "model": bp_speed_row["model"],
                  "rate": min(cpu_rates) if cpu_rates else float("nan")}
    laf_shadowed = [r for r in rows if r["model"].startswith("Lafortune") and r["shadows"]]
    lin_row = {"case": f"{speed['size']}²", "model": "linear / read pass",
               "ratio": speed["linear_vs_read_pass"]}
    items = [
        _target("no texel outside the physical space (every nonlinear model and solver)",
                nonlinear, "outside", 0),
        _target("unshadowed: normals mean <= 0.5°", clear, "normal_mean_deg", 0.5),
        _target("unshadowed: exponent median relative error <= 10%", with_spec,
                "exponent_rel", 0.10),
        _target("unshadowed: k_s median relative error <= 10%", with_spec, "k_s_rel", 0.10),
        _target("cast shadows: normals mean <= 2°", shadowed, "normal_mean_deg", 2.0),
        _target("cast shadows: normals p95 <= 6°", shadowed, "normal_p95_deg", 6.0),
        _target("cast shadows: Lafortune normals p95 <= 6°", laf_shadowed, "normal_p95_deg",
                6.0),
        _target("as drawn <= 1.2x as fitted (every Blinn-Phong fit)", bp_all,
                "drawn_vs_fitted", 1.2),
        _target("unshadowed: as drawn <= 2x noise floor", clear, "drawn_vs_floor", 2.0),
        _target("linear fit <= 2x one read pass of the samples", [lin_row], "ratio", 2.0,
                by_format=False),
        _target("Blinn-Phong >= 150 k texels/s on 2 cores (non-preset data)", [bp_speed_row],
                "rate", 150_000.0, higher_is_better=True, by_format=False),
        _target("Blinn-Phong >= 150 k texels/s, from CPU time (2 free cores; load-independent)",
                [bp_cpu_row], "rate", 150_000.0, higher_is_better=True, by_format=False),
    ]
    picks = [r for r in chosen if r["specular"]]
    want = {r["case"]: "n_s=(0,0,1)" if r["truth_flat"] else "n_s=n" for r in picks}
    right = sum(r["chosen"] == want[r["case"]] for r in picks)
    # the same choice made on the float model's deviation: tells a fit problem (both wrong)
    # from a drawing problem (the drawn maps lose what the fit found)
    by_fitted = 0
    for case, truth_pick in want.items():
        pair = {r["model"][len("Blinn-Phong "):]: r["dev_fitted"] for r in rows
                if r["case"] == case and r["model"] in ("Blinn-Phong n_s=n",
                                                        "Blinn-Phong n_s=(0,0,1)")}
        by_fitted += min(pair, key=pair.get) == truth_pick
    return {"evaluated": bool(evaluated), "items": items,
            "all_met": all(t["met"] for t in items if t["met"] is not None),
            "highlight_choice": {"matches_truth": right, "datasets": len(picks),
                                 "matches_truth_by_fitted_deviation": by_fitted}}


def _f(v: Any, digits: int = 3) -> str:
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "–"
    if isinstance(v, float):
        return f"{v:.{digits}f}"
    return str(v)


def summary_by_model(rows: List[Dict[str, Any]]) -> List[List[str]]:
    """Per model over all datasets: worst outside count, median / worst of the errors."""
    out = []
    for model in dict.fromkeys(r["model"] for r in rows):
        rs = [r for r in rows if r["model"] == model]
        clear = [r for r in rs if not r["shadows"]]
        shade = [r for r in rs if r["shadows"]]

        def med(key: str, sel: List[Dict[str, Any]]) -> Optional[float]:
            v = [r[key] for r in sel if r.get(key) is not None]
            return float(np.median(v)) if v else None

        def top(key: str, sel: List[Dict[str, Any]]) -> Optional[float]:
            v = [r[key] for r in sel if r.get(key) is not None]
            return float(np.max(v)) if v else None

        out.append([model, str(max(r["outside"] for r in rs)),
                    f"{_f(med('normal_mean_deg', clear), 2)} / "
                    f"{_f(top('normal_mean_deg', clear), 2)}",
                    f"{_f(med('normal_mean_deg', shade), 2)} / "
                    f"{_f(top('normal_p95_deg', shade), 2)}",
                    _f(med("exponent_rel", clear)), _f(med("k_s_rel", clear)),
                    _f(top("drawn_vs_fitted", rs)), _f(med("drawn_vs_floor", clear), 2),
                    f"{med('texels_per_s', rs) / 1e3:.1f} k"])
    return out


def target_table(tg: Dict[str, Any]) -> str:
    """Targets with the worst PNG and JPEG rows (speed targets: one value)."""
    verdict = (lambda met: "–" if met is None else ("pass" if met else "**FAIL**"))

    def cell(g: Optional[Dict[str, Any]]) -> str:
        if not g or g["measured"] is None:
            return "–"
        return f"{_f(float(g['measured']), 3)} {verdict(g['met'])} ({g['where']})"

    rows = []
    for t in tg["items"]:
        pf = t["per_format"]
        if "all" in pf:
            rows.append([t["target"], f"{t['limit']:g}", cell(pf["all"]), "(not per "
                         "format)", verdict(t["met"])])
        else:
            rows.append([t["target"], f"{t['limit']:g}", cell(pf.get("png")),
                         cell(pf.get("jpg")), verdict(t["met"])])
    return markdown_table(["target", "limit", "PNG: worst (where)", "JPEG q90: worst (where)",
                           "result"], rows)


def render_markdown(data: Dict[str, Any]) -> str:
    rows, speed, tg = data["results"], data["speed"], data["targets"]
    judged = "" if tg["evaluated"] else " (quick run: shown, not judged)"
    lines = [f"# BTF fitting benchmark ({data['size']} x {data['size']} x 81, noise "
             f"{data['noise']}, PNG and JPEG q{data['jpeg_quality']})", "", f"`{data['command']}`",
             "", f"## Targets (issue 12){judged}", "",
             target_table(tg), "",
             f"The Blinn-Phong highlight chosen by deviation as drawn (n_s = n or (0,0,1); over "
             f"θ_l <= 45° where a fit found cast shadows, `scoring.highlight_choice`) is "
             f"the truth's on {tg['highlight_choice']['matches_truth']} of "
             f"{tg['highlight_choice']['datasets']} datasets with a specular lobe (chosen by the "
             f"float model's deviation instead: "
             f"{tg['highlight_choice']['matches_truth_by_fitted_deviation']}).", "",
             "## Per model over all datasets", "",
             "normal ° unshadowed: median / worst mean; shadowed: median mean / worst p95; "
             "exponent and k_s: median over datasets of the median relative error; drawn / "
             "fitted: worst; drawn / floor: median on unshadowed data (Lafortune is not "
             "drawable: –).", "",
             markdown_table(["model", "outside (worst)", "normal ° unshadowed",
                             "normal ° shadowed", "exponent rel", "k_s rel", "drawn / fitted",
                             "drawn / noise floor", "texels/s"], summary_by_model(rows)), "",
             "## Speed", ""]
    speed_rows = [
        ["read pass over the samples (NumPy sum)",
         f"{speed['read_pass_ms']:.2f} ms ({speed['sample_bytes'] / 1e6:.0f} MB float32)"],
        ["linear fit", f"{speed['linear_ms']:.2f} ms = {speed['linear_vs_read_pass']:.2f}x "
                       f"the read pass"],
        ["memcpy bound", f"{speed['bandwidth_bound_ms']:.2f} ms ({speed['memcpy_GBps']:.1f} "
                         f"GB/s)"],
    ]
    for suffix, where in (("", ""), ("_shadows", ", cast shadows")):
        for key, label in (("n", "n"), ("flat", "(0,0,1)")):
            name = f"blinn_phong_{key}{suffix}"
            if f"{name}_texels_per_s" not in speed:
                continue
            cpu = speed.get(f"{name}_cpu_texels_per_s")
            speed_rows.append([f"Blinn-Phong n_s = {label}, 2 threads{where}",
                               f"{speed[f'{name}_texels_per_s'] / 1e3:.1f} k texels/s"
                               + ("" if cpu is None else
                                  f" (CPU time: {cpu / 1e3:.1f} k on 2 free cores)")])
    if "numpy_linear_ms" in speed:
        speed_rows.append(["batched NumPy normal equations",
                           f"{speed['numpy_linear_ms']:.0f} ms (normals agree to "
                           f"{speed['numpy_max_normal_difference_deg']:.1e}°)"])
    lines += [f"{speed['size']} x {speed['size']} x 81, random material:", "",
              markdown_table(["figure", "value"], speed_rows), "", "## Every dataset and model",
              ""]
    header = ["dataset", "model", "outside", "normal ° mean / p95", "exp rel", "k_s rel",
              "dev % fitted", "dev % drawn", "drawn/fitted", "floor %", "drawn/floor", "s",
              "texels/s"]
    body = [[r["case"], r["model"] + (f" [{r['chosen']}]" if r.get("chosen") else ""),
             r["outside"], f"{r['normal_mean_deg']:.2f} / {r['normal_p95_deg']:.2f}",
             _f(r["exponent_rel"]), _f(r["k_s_rel"]), _f(r["dev_fitted"], 4),
             _f(r["dev_drawn"], 4) if r["drawable"] else "not drawn",
             _f(r["drawn_vs_fitted"], 2), _f(r["noise_floor"], 4), _f(r["drawn_vs_floor"], 2),
             f"{r['seconds']:.3f}", f"{r['texels_per_s'] / 1e3:.1f} k"] for r in rows]
    lines.append(markdown_table(header, body))
    if data.get("plot"):
        lines += ["", f"Error against time: `{data['plot']}`"]
    elif data.get("plot_note"):
        lines += ["", f"Error against time: {data['plot_note']}"]
    return "\n".join(lines)


def plot_error_vs_time(rows: List[Dict[str, Any]], path: str) -> Optional[str]:
    """Normal error and deviation as drawn / noise floor against fit time per texel, one colour
    per model (small points: datasets, large: medians); returns a note when it cannot plot."""
    plt = pyplot()
    models = [m for m in dict.fromkeys(r["model"] for r in rows) if m != CHOSEN]
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    cmap = plt.get_cmap("tab10")
    panels = (("normal_mean_deg", "normal error, mean (°)"),
              ("drawn_vs_floor", "deviation as drawn / noise floor (Lafortune: as fitted)"))
    for ax, (key, label) in zip(axes, panels):
        for i, model in enumerate(models):
            rs = [r for r in rows if r["model"] == model]
            ys = [r[key] if r[key] is not None else r["dev_fitted"] / r["noise_floor"]
                  for r in rs]
            xs = [r["seconds"] / r["texels"] * 1e6 for r in rs]
            ys_ok = [max(y, 1e-4) for y in ys]
            # ten colours, then the same colours with square markers
            style = dict(color=cmap(i % 10), marker="os"[i // 10 % 2])
            ax.scatter(xs, ys_ok, s=10, alpha=0.35, **style)
            ax.scatter([np.median(xs)], [np.median(ys_ok)], s=90, edgecolors="black",
                       label=model, zorder=3, **style)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("fit time per texel (µs, 2 cores)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].axhline(0.5, color="grey", ls=":", lw=1)
    axes[1].axhline(2.0, color="grey", ls=":", lw=1)
    axes[1].legend(fontsize=7, loc="upper right")
    fig.suptitle("BTF fits against the generator's truth: error against time "
                 "(large markers: medians over datasets)")
    fig.tight_layout()
    save_figure(fig, path, dpi=100)
    return None
