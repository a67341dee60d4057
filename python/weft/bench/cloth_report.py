"""The cloth benchmark's report (weft.bench.cloth): the Markdown tables and the Pareto plot
(steps/s against mean strain) from a run's results."""

from __future__ import annotations

import math
from typing import Any, Dict, Optional, Sequence

from weft.bench import markdown_table
from weft.bench.cloth import (
    GS_RATIO_TARGET,
    NUMPY_RATIO_TARGET,
    PEER_RATIO_TARGET,
    REST_ENERGY,
    STRAIN_SLACK,
    STRAIN_STEPS,
    TARGET_MAX,
    TARGET_MEAN,
    TARGET_SIZE,
    TARGET_SPEED,
    XPBD,
    pareto_front,
)
from weft.reporting import pyplot, save_figure


def _pct(v: Optional[float]) -> str:
    if v is None or not math.isfinite(v):
        return "n/a"
    return f"{100.0 * v:.3g}%"


def _num(v: Optional[float], fmt: str = ".1f") -> str:
    return "n/a" if v is None or not math.isfinite(v) else format(v, fmt)


def to_markdown(report: Dict[str, Any]) -> str:
    m = report["machine"]
    lines = [
        "# weft cloth benchmark: time against error",
        "",
        f"- machine: {m.get('platform')}, {m.get('cpu_count')} CPUs"
        + (f" ({m['processor']})" if m.get("processor") else "")
        + f"; weft {m.get('weft', '?')}, Python {m.get('python')}, NumPy {m.get('numpy')}",
        f"- command: `{report['command']}`",
        "- scene: 1 m cloth hanging from its two top corners (XY plane), dt = 1/60 s, gravity, "
        "12-neighbour pattern (k = 2), damping 0.99; weft with "
        f"{report['weft_threads'] or 'all'} thread(s).",
        f"- steps/s: median of {report['repeats']} timed runs after a warm-up; strain "
        f"|len - rest| / rest after {STRAIN_STEPS} steps from rest (mean, max over all "
        "constraints); equilibrium error: mean vertex distance to the converged reference at "
        f"rest (kinetic energy < {REST_ENERGY:g} J or {report['rest_steps']} steps), relative "
        "to the cloth size.",
        f"- reference: {report['reference']['setting']}; its own error (distance to "
        f"{report['reference']['check_setting']}) per size: "
        + ", ".join(f"{n}²: {_num(v, '.1e')}"
                    for n, v in report["reference"]["check_error"].items()) + ".",
        "- peers: NumPy = `weft.reference.cloth.ClothReference` (same algorithm, float64, "
        "vectorised per batch){}; Warp: {}. Peers run the same settings; where a NumPy strain "
        "run would exceed the time budget its strain is weft's (same algorithm).".format(
            "" if report["numpy"] else " — not run", report["warp"]),
        "- settings: `itK` = K relaxation iterations per substep, `subK` = K substeps per "
        "step, `tethers` = long-range attachments to the pinned corners, `xpbd` = compliance "
        "(stretch/shear/bend m/N) "
        + "/".join(f"{c:g}" for c in XPBD) + " (its strain includes that intended give); "
        "rest steps = steps until the kinetic energy fell below the threshold (the maximum: "
        "never at rest); strain spread = largest relative change of weft's mean strain when "
        "the rest state moves by ±1 float32 ulp in the cloth's plane (rounding alone; the "
        "equal-accuracy slack where above 1%).",
        "",
    ]
    header = ["N", "setting", "sweeps/step", "weft steps/s", "mean strain", "strain spread",
              "max strain", "equilibrium err", "rest steps", "NumPy steps/s", "weft/NumPy"]
    if any(r["engine"] == "warp" for r in report["results"]):
        header += ["Warp steps/s", "weft/Warp", "Warp mean strain"]
    if any(r["engine"] == "gs-natural" for r in report["results"]):
        header += ["GS steps/s", "weft/GS", "GS mean strain"]
    rows = []
    for r in report["results"]:
        if r["engine"] != "weft":
            continue
        peer = {p["engine"]: p for p in report["results"] if p["engine"] != "weft"
                and p["n"] == r["n"] and p["setting"] == r["setting"]}
        row = [f"{r['n']}²", r["setting"], r["sweeps"], _num(r["steps_per_s"]),
               _pct(r["mean_strain"]), _pct(r.get("strain_spread")), _pct(r["max_strain"]),
               _num(r["equilibrium_error"], ".2e"),
               r["equilibrium_steps"]]
        np_r = peer.get("numpy")
        row += [_num(np_r["steps_per_s"], ".2f") if np_r else "—",
                _num(r["steps_per_s"] / np_r["steps_per_s"], ".0f") + "x" if np_r else "—"]
        if "Warp steps/s" in header:
            wr = peer.get("warp")
            row += [_num(wr["steps_per_s"]) if wr else "—",
                    _num(r["steps_per_s"] / wr["steps_per_s"], ".1f") + "x" if wr else "—",
                    _pct(wr["mean_strain"]) if wr else "—"]
        if "GS steps/s" in header:
            gr = peer.get("gs-natural")
            row += [_num(gr["steps_per_s"]) if gr else "—",
                    _num(r["steps_per_s"] / gr["steps_per_s"], ".1f") + "x" if gr else "—",
                    (_pct(gr["mean_strain"]) if gr["mean_strain"] is not None
                     else ("diverged" if "diverged" in gr["strain_source"] else "n/a"))
                    if gr else "—"]
        rows.append(row)
    lines.append(markdown_table(header, rows))

    s = report["summary"]
    lines += ["", "## Ratios", ""]
    for peer in ("numpy", "warp"):
        key = f"weft_vs_{peer}_equal_settings"
        if key in s:
            parts = [f"{n}²: {_num(v['min'], '.0f')}–{_num(v['max'], '.0f')}x "
                     f"(median {_num(v['median'], '.0f')}x)" for n, v in s[key].items()]
            target = f" (target ≥ {NUMPY_RATIO_TARGET:g}x)" if peer == "numpy" else ""
            lines.append(f"- weft / {peer} steps/s at equal settings{target}: " + "; ".join(parts))
    for n, v in s["pareto_vs_peers"].items():
        worst = min((p for p in v["points"] if p["ratio"] is not None),
                    key=lambda p: p["ratio"], default=None)
        detail = (f"; tightest: {worst['peer']} {worst['setting']} at "
                  f"{_pct(worst['peer_mean_strain'])}, {worst['peer_steps_per_s']:.1f} steps/s vs "
                  f"weft {worst['weft_setting']} {worst['weft_steps_per_s']:.1f} steps/s "
                  f"(slack {100 * worst.get('slack', STRAIN_SLACK):.2g}%)"
                  if worst else "")
        wide = sorted({f"{p['setting']} {100 * p['slack']:.2g}%" for p in v["points"]
                       if p.get("slack", STRAIN_SLACK) > STRAIN_SLACK})
        spread_note = (f"; measured spread above {100 * STRAIN_SLACK:g}%: " + ", ".join(wide)
                       if wide else "")
        lines.append(f"- {n}²: at every mean strain a peer reaches, weft's fastest setting at "
                     f"that strain or lower (slack: the larger of {100 * STRAIN_SLACK:g}% and "
                     f"weft's float32 trajectory spread at the peer's setting{spread_note}) runs "
                     f"≥ {_num(v['min_ratio'], '.1f')}x the peer's steps/s "
                     f"(target ≥ {PEER_RATIO_TARGET:g}x){detail}")
    for key, v in (s.get("equal_accuracy_vs_gs_natural") or {}).items():
        pts = v["points"]
        diverged = [p["setting"] for p in pts if p["gs_mean_strain"] is None]
        matched = [p for p in pts if p["ratio"] is not None]
        worst = min(matched, key=lambda p: p["ratio"], default=None)
        text = (f"- {v['n']}² {'with' if v['tethers'] else 'without'} tethers, natural-order "
                f"Gauss-Seidel peer (target ≥ {GS_RATIO_TARGET:g}x at equal accuracy): ")
        if worst:
            text += (f"weft ≥ {worst['ratio']:.1f}x; tightest: gs {worst['setting']} at "
                     f"{_pct(worst['gs_mean_strain'])}, {worst['gs_steps_per_s']:.1f} steps/s vs "
                     f"weft {worst['weft_setting']} {worst['weft_steps_per_s']:.1f} steps/s")
        else:
            text += "no point to compare"
        if v["unmatched"]:
            text += "; no weft setting as accurate as gs " + ", ".join(v["unmatched"])
        if diverged:
            text += "; no accuracy point (diverged or over budget): " + ", ".join(diverged)
        lines.append(text)
    t = s["target_128"]
    if t["evaluated"]:
        if t["met"]:
            best = max((a for a in t["accurate_enough_settings"]
                        if a["setting"] in t["settings_meeting"]), key=lambda a: a["steps_per_s"])
            lines.append(f"- target at {TARGET_SIZE}²: mean strain ≤ {_pct(TARGET_MEAN)} and max "
                         f"≤ {_pct(TARGET_MAX)} at ≥ {TARGET_SPEED:g} steps/s: **met** by "
                         + ", ".join(t["settings_meeting"])
                         + f" (fastest: {best['setting']}, {best['steps_per_s']:.0f} steps/s, "
                         f"mean {_pct(best['mean_strain'])}, max {_pct(best['max_strain'])})")
        else:
            acc = ", ".join(f"{a['setting']} ({a['steps_per_s']:.0f} steps/s)"
                            for a in t["accurate_enough_settings"]) or "none"
            lines.append(f"- target at {TARGET_SIZE}²: mean strain ≤ {_pct(TARGET_MEAN)} and max "
                         f"≤ {_pct(TARGET_MAX)} at ≥ {TARGET_SPEED:g} steps/s: **not met**; "
                         f"settings accurate enough: {acc}")
    else:
        lines.append(f"- target at {TARGET_SIZE}²: not evaluated (size not in this run)")
    if report.get("plot"):
        lines += ["", f"Pareto plot (steps/s against mean strain): `{report['plot']}`"]
    elif report.get("plot_note"):
        lines += ["", f"Pareto plot: {report['plot_note']}"]
    notes = report.get("notes") or []
    if notes:
        lines += ["", "Notes:"] + [f"- {n}" for n in notes]
    return "\n".join(lines) + "\n"


def plot_pareto(results: Sequence[Dict[str, Any]], sizes: Sequence[int], path: str
                ) -> Optional[str]:
    """Steps/s against mean strain (log-log) per size, weft's Pareto front drawn; returns None
    (the note of a run that could not plot, kept for the callers)."""
    plt = pyplot()
    fig, axes = plt.subplots(1, len(sizes), figsize=(6.5 * len(sizes), 5.2), squeeze=False)
    style = {"weft": ("o", "tab:blue"), "numpy": ("s", "tab:orange"), "warp": ("^", "tab:green"),
             "gs-natural": ("D", "tab:red")}
    for ax, n in zip(axes[0], sizes):
        for engine, (marker, colour) in style.items():
            pts = [r for r in results if r["engine"] == engine and r["n"] == n
                   and r["mean_strain"] is not None and r["mean_strain"] > 0]
            if not pts:
                continue
            xs = [r["mean_strain"] for r in pts]
            ys = [r["steps_per_s"] for r in pts]
            ax.scatter(xs, ys, marker=marker, color=colour, label=engine, zorder=3)
            if engine == "weft":
                front = pareto_front(list(zip(xs, ys)))
                ax.step([xs[i] for i in front], [ys[i] for i in front], where="post",
                        color=colour, alpha=0.6, zorder=2, label="weft Pareto front")
                for r in pts:
                    ax.annotate(r["setting"], (r["mean_strain"], r["steps_per_s"]), fontsize=6,
                                xytext=(3, 3), textcoords="offset points")
        ax.axvline(TARGET_MEAN, color="grey", ls=":", lw=1)
        ax.axhline(TARGET_SPEED, color="grey", ls=":", lw=1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(f"mean strain after {STRAIN_STEPS} steps")
        ax.set_ylabel("steps / s")
        ax.set_title(f"hanging cloth {n} x {n}")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    return None


# --------------------------------------------------------------------------------------------
# Driver
# --------------------------------------------------------------------------------------------
