"""``python -m weft.bench btf``: BTF fitting, time against error (SPEC §3.6).

For each preset a synthetic 256 x 256 x 81 BTF (sensor noise 0.004, JPEG quality 95, frontal
view) is written in the Bonn layout and read back; then timed: load, linear fit (plain and
robust), exponent search (eq. 4.30: every integer 1..4096; eq. 4.29: grid + refinement),
nonlinear Blinn-Phong (built-in LM on every texel; Ceres on a 32 x 32 crop when built with it)
and diffuse + 2 Lafortune lobes (built-in LM).
Errors against the ground truth: normal angular error (mean, 95th percentile), ambient error
(|a - a_true| with a = I_A/|n|), total deviation (SPEC §3.4) of every model.
Peers in the same run: the batched NumPy normal equations (:func:`weft.reference.btf.
batched_normal_equations`, what a user would write; on the first preset) and the memory
bandwidth bound (bytes of float32 samples / measured memcpy bandwidth).
``--quick`` (CI): 32 x 32, two presets, no targets evaluated.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import sys
import tempfile
import time
from typing import Any, Callable, Dict, List, Tuple

import numpy as np

from weft.bench import Progress, machine_info, markdown_table, write_report

DESCRIPTION = "BTF fitting: load / linear / exponent search / Blinn-Phong time against normal " \
              "error and deviation, with NumPy and memory-bandwidth peers"

PRESETS = ("wool", "polyacrylic", "corduroy", "upholstery", "granite")
QUICK_PRESETS = ("wool", "corduroy")
SIZE, QUICK_SIZE = 256, 32
NOISE = 0.004
TARGET_LINEAR_MS, TARGET_SEARCH_MS, TARGET_BP_TEXELS_S = 20.0, 50.0, 50_000.0
CERES_CROP = 32


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--quick", action="store_true", help="32 x 32, two presets (CI)")
    parser.add_argument("--out", default="out/bench/btf", help="output folder")
    parser.add_argument("--presets", nargs="+", choices=PRESETS, default=None)
    parser.add_argument("--size", type=int, default=None, help="texels per side (256)")
    parser.add_argument("--repeats", type=int, default=None, help="timing repeats (best of)")
    parser.add_argument("--no-numpy", dest="numpy", action="store_false",
                        help="skip the batched NumPy peer")


def best_time(fn: Callable[[], Any], repeats: int) -> Tuple[float, Any]:
    best, out = float("inf"), None
    for _ in range(max(repeats, 1)):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def memcpy_bandwidth() -> float:
    """Bytes/s of a large NumPy copy (read + write counted)."""
    src = np.ones(64 * 1024 * 1024 // 4, np.float32)
    dst = np.empty_like(src)
    t, _ = best_time(lambda: np.copyto(dst, src), 5)
    return 2 * src.nbytes / t


def crop(samples: Any, n: int) -> Any:
    import weft

    return weft.BtfSamples(np.ascontiguousarray(samples.values[:, :, :n, :n]), samples.angles)


def run_preset(preset: str, size: int, repeats: int, tmp: str) -> Dict[str, Any]:
    from weft import btf

    samples, truth = btf.synthesize(preset, size, noise=NOISE)
    folder = os.path.join(tmp, preset)
    btf.write(folder, samples, fmt="jpg", quality=95)
    t_load, data = best_time(lambda: btf.load(folder), repeats)
    t_lin, linear = best_time(lambda: btf.fit_linear(data), repeats)
    t_rob, robust = best_time(lambda: btf.fit_linear(data, robust=True), 1)
    t_flat, flat = best_time(lambda: btf.fit_specular(data, linear), repeats)
    t_fitted, fitted = best_time(lambda: btf.fit_specular(data, linear, False), 1)
    t_bp, bp = best_time(lambda: btf.fit_blinn_phong(data, flat.material, "builtin"), 1)
    t_laf, laf = best_time(lambda: btf.fit_lafortune(data, flat.material, 2), 1)
    texels = size * size
    row: Dict[str, Any] = {
        "preset": preset, "size": size, "shadows": truth.shadows,
        "load_ms": t_load * 1e3, "linear_ms": t_lin * 1e3, "robust_ms": t_rob * 1e3,
        "search_eq430_ms": t_flat * 1e3, "search_eq429_ms": t_fitted * 1e3,
        "blinn_phong_s": t_bp, "linear_texels_per_s": texels / t_lin,
        "lafortune2_s": t_laf, "lafortune2_texels_per_s": texels / t_laf,
        "blinn_phong_texels_per_s": texels / t_bp, "bp_mean_iterations": bp.mean_iterations,
        "exponent_eq430": int(flat.exponent), "exponent_eq429": int(fitted.exponent),
        "truth_exponent": truth.material.exponent,
    }
    lin_material = linear.material(data)
    models = {"linear": lin_material, "robust": robust.material(data),
              "spec_eq429": fitted.material, "spec_eq430": flat.material,
              "blinn_phong": bp.material}
    for name, m in models.items():
        row[f"dev_{name}"] = btf.deviation(data, btf.sample_errors(data, m))["total"]
        stats = btf.normal_stats(m.normal, truth.material.normal)
        row[f"normal_mean_{name}"] = stats["mean_deg"]
        row[f"normal_p95_{name}"] = stats["p95_deg"]
    row["dev_lafortune2"] = btf.deviation(data, laf.errors(data))["total"]
    row["normal_mean_lafortune2"] = btf.normal_stats(laf.normal, truth.material.normal)["mean_deg"]
    row["ambient_err_linear"] = float(np.mean(np.abs(lin_material.ambient -
                                                      truth.material.ambient)))
    row["ambient_err_blinn_phong"] = float(np.mean(np.abs(bp.material.ambient *
                                                          bp.material.albedo -
                                                          truth.material.ambient *
                                                          truth.material.albedo)))
    row["bp_gain_vs_eq430"] = row["dev_spec_eq430"] / max(row["dev_blinn_phong"], 1e-300)
    if btf.have_ceres():
        small = crop(data, min(CERES_CROP, size))
        seed = btf.fit_specular(small, btf.fit_linear(small)).material
        t_c, ceres = best_time(lambda: btf.fit_blinn_phong(small, seed, "ceres"), 1)
        t_b, builtin = best_time(lambda: btf.fit_blinn_phong(small, seed, "builtin"), 1)
        n = small.width * small.height
        row["ceres_texels_per_s"] = n / t_c
        row["ceres_vs_builtin_dev"] = (
            btf.deviation(small, btf.sample_errors(small, ceres.material))["total"] /
            btf.deviation(small, btf.sample_errors(small, builtin.material))["total"])
        row["builtin_crop_texels_per_s"] = n / t_b
    return row, samples


def numpy_peer(samples: Any, repeats: int) -> Dict[str, Any]:
    from weft import btf
    from weft.reference import btf as ref

    values = samples.values
    t, x = best_time(lambda: ref.batched_normal_equations(values, samples.light_dirs),
                     max(1, repeats // 2))
    mine = btf.fit_linear(samples)
    diff = btf.angular_error_deg(x[..., :3], mine.normal)
    return {"numpy_linear_ms": t * 1e3, "max_normal_difference_deg": float(diff.max())}


def run(args: argparse.Namespace) -> int:
    quick = bool(args.quick)
    size = args.size or (QUICK_SIZE if quick else SIZE)
    presets = tuple(args.presets or (QUICK_PRESETS if quick else PRESETS))
    repeats = args.repeats or (1 if quick else 5)
    if size < 8 or repeats < 1:
        print("python -m weft.bench btf: error: --size must be >= 8, --repeats >= 1",
              file=sys.stderr)
        return 2
    progress = Progress(len(presets) + 2)
    progress.update("memcpy bandwidth")
    bandwidth = memcpy_bandwidth()
    progress.step("memcpy bandwidth")
    rows: List[Dict[str, Any]] = []
    peer: Dict[str, Any] = {}
    with tempfile.TemporaryDirectory(prefix="weft-bench-btf-") as tmp:
        for i, preset in enumerate(presets):
            progress.update(preset)
            row, samples = run_preset(preset, size, repeats, tmp)
            rows.append(row)
            if i == 0 and args.numpy:
                progress.update(f"{preset}: NumPy peer")
                peer = numpy_peer(samples, repeats)
            progress.step(preset)
    sample_bytes = size * size * 81 * 3 * 4
    bound_ms = sample_bytes / bandwidth * 1e3
    linear_ms = float(np.median([r["linear_ms"] for r in rows]))
    search_ms = float(np.median([r["search_eq430_ms"] for r in rows]))
    bp_rate = float(np.median([r["blinn_phong_texels_per_s"] for r in rows]))
    targets = {
        "evaluated": not quick and size == SIZE,
        "linear_ms": {"measured": linear_ms, "target": TARGET_LINEAR_MS,
                      "met": linear_ms <= TARGET_LINEAR_MS},
        "search_ms": {"measured": search_ms, "target": TARGET_SEARCH_MS,
                      "met": search_ms <= TARGET_SEARCH_MS},
        "blinn_phong_texels_per_s": {"measured": bp_rate, "target": TARGET_BP_TEXELS_S,
                                     "met": bp_rate >= TARGET_BP_TEXELS_S},
        "bp_beats_pipeline_on_all_presets": all(r["dev_blinn_phong"] < r["dev_spec_eq430"]
                                                for r in rows),
        "lafortune2_beats_pipeline_on_all_presets": all(
            r["dev_lafortune2"] < r["dev_spec_eq430"] for r in rows),
    }
    summary = {"memcpy_GBps": bandwidth / 1e9, "sample_bytes": sample_bytes,
               "bandwidth_bound_ms": bound_ms, "linear_vs_bound": linear_ms / bound_ms,
               **peer}
    if peer:
        summary["numpy_vs_weft_linear"] = peer["numpy_linear_ms"] / rows[0]["linear_ms"]
    progress.update("report")
    plot_note = ("matplotlib is not installed: no plot" if importlib.util.find_spec("matplotlib")
                 is None else "no plot drawn: the table holds every figure")
    command = "python -m weft.bench btf" + (" --quick" if quick else "")
    if args.size:
        command += f" --size {args.size}"
    if args.presets:
        command += " --presets " + " ".join(args.presets)
    markdown = render_markdown(rows, summary, targets, size, command)
    data = {"benchmark": "btf", "command": command, "machine": machine_info(), "size": size,
            "noise": NOISE, "presets": list(presets), "results": rows, "summary": summary,
            "targets": targets, "plot": None, "plot_note": plot_note}
    write_report(args.out, data, markdown + f"\n\n{plot_note}\n")
    progress.step("report")
    progress.close()
    print(markdown)
    return 0


def render_markdown(rows: List[Dict[str, Any]], summary: Dict[str, Any],
                    targets: Dict[str, Any], size: int, command: str) -> str:
    def f(v: Any, p: int = 2) -> str:
        return f"{v:.{p}f}" if isinstance(v, float) else str(v)

    time_rows = [[r["preset"], f(r["load_ms"], 1), f(r["linear_ms"]), f(r["robust_ms"], 1),
                  f(r["search_eq430_ms"]), f(r["search_eq429_ms"], 0), f(r["blinn_phong_s"], 3),
                  f"{r['linear_texels_per_s'] / 1e6:.1f} M",
                  f"{r['blinn_phong_texels_per_s'] / 1e3:.1f} k",
                  f"{r['lafortune2_texels_per_s'] / 1e3:.1f} k",
                  f"{r.get('ceres_texels_per_s', float('nan')) / 1e3:.2f} k"] for r in rows]
    err_rows = [[r["preset"], *(f"{r[f'normal_mean_{m}']:.2f} / {r[f'normal_p95_{m}']:.2f}"
                                for m in ("linear", "robust", "blinn_phong")),
                 f(r["ambient_err_linear"], 4),
                 *(f(r[f"dev_{m}"], 4) for m in ("linear", "spec_eq429", "spec_eq430",
                                                 "blinn_phong", "lafortune2")),
                 f"{r['exponent_eq429']} / {r['exponent_eq430']} ({r['truth_exponent']:g})",
                 f"{r['bp_gain_vs_eq430']:.2f}x"] for r in rows]
    lines = [f"# BTF fitting benchmark ({size} x {size} x 81, noise {NOISE}, JPEG 95)", "",
             f"`{command}`", "", "## Times", "",
             markdown_table(["preset", "load ms", "linear ms", "robust ms", "search eq4.30 ms",
                             "search eq4.29 ms", "Blinn-Phong s", "linear texels/s",
                             "BP texels/s", "Lafortune-2 texels/s", "Ceres texels/s"],
                            time_rows), "",
             "## Errors against the ground truth", "",
             markdown_table(["preset", "normal ° linear (mean / p95)", "robust", "Blinn-Phong",
                             "ambient |err|", "dev % linear", "dev % eq4.29", "dev % eq4.30",
                             "dev % BP", "dev % Lafortune-2", "n eq4.29 / eq4.30 (truth)",
                             "BP gain"], err_rows), "",
             "## Peers and targets", ""]
    peer_rows = [["memcpy bandwidth", f"{summary['memcpy_GBps']:.1f} GB/s"],
                 ["bandwidth bound of the linear fit",
                  f"{summary['bandwidth_bound_ms']:.2f} ms ({summary['sample_bytes'] / 1e6:.0f} "
                  f"MB of float32 samples)"],
                 ["linear fit / bound", f"{summary['linear_vs_bound']:.2f}x"]]
    if "numpy_linear_ms" in summary:
        peer_rows += [["batched NumPy normal equations", f"{summary['numpy_linear_ms']:.0f} ms "
                       f"({summary['numpy_vs_weft_linear']:.0f}x weft; normals agree to "
                       f"{summary['max_normal_difference_deg']:.1e}°)"]]
    for key in ("linear_ms", "search_ms", "blinn_phong_texels_per_s"):
        t = targets[key]
        state = ("met" if t["met"] else "MISSED") if targets["evaluated"] else "not evaluated"
        peer_rows.append([f"target {key}", f"{t['measured']:.2f} vs {t['target']:g}: {state}"])
    peer_rows.append(["Blinn-Phong beats linear + specular on every preset",
                      str(targets["bp_beats_pipeline_on_all_presets"])])
    peer_rows.append(["Lafortune (2 lobes) beats linear + specular on every preset",
                      str(targets["lafortune2_beats_pipeline_on_all_presets"])])
    lines.append(markdown_table(["figure", "value"], peer_rows))
    return "\n".join(lines)
