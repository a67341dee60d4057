"""Picture benchmark (issue 18): weft's frame against Mitsuba 3's path tracer, per reference
scene and setting, with its frame time.

For every reference scene (weft.reference.picture.scenes) Mitsuba renders the truth once
(``path``, full global illumination; ``direct`` as well, to tell missing bounce light from
errors of the direct light), plus a second frame of another seed whose FLIP against the first
is the reference's own noise floor. weft then renders each setting -- dome lights, GGX prefilter
samples, MSAA where the renderer has it, one bounce off -- timed (median of ``--frames`` renders
after a warm-up; maps reused, the scene is static) and compared: mean FLIP (LDR) and relative
error over the whole image, the covered pixels, the objects, the geometric edges and the
objects' unlit side. The anti-aliasing reference (4x4 supersampled frame) scores mesh and hair
edges. Writes bench.json, bench.md, error_vs_time.png and, per scene, ``<scene>.png`` (weft |
Mitsuba | FLIP).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

from weft.bench import Progress, machine_info, markdown_table, write_report
from weft.reporting import add_progress_arguments, pyplot, save_figure

DESCRIPTION = ("the rendered picture against Mitsuba 3's path tracer: FLIP / relative error vs "
               "frame time per scene and setting, and the anti-aliasing edge error")

REGIONS = ("whole", "covered", "objects", "edges", "unlit")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--quick", action="store_true",
                        help="96x72, 32 spp, one setting per scene (a CI smoke run)")
    parser.add_argument("--out", default="out/bench/picture",
                        help="output folder (out/bench/picture)")
    parser.add_argument("--size", type=int, nargs=2, default=None, metavar=("W", "H"),
                        help="frame size (default 256 192; 96 72 with --quick)")
    parser.add_argument("--spp", type=int, default=None,
                        help="Mitsuba samples per pixel (default 1024; 32 with --quick)")
    parser.add_argument("--frames", type=int, default=None,
                        help="timed weft frames per setting (default 5; 2 with --quick)")
    parser.add_argument("--scenes", nargs="+", default=None, help="reference scenes to run")
    add_progress_arguments(parser)


def _settings(name: str, quick: bool, has_msaa: bool) -> List[Dict[str, Any]]:
    """The weft settings to run for scene ``name`` (the first is the default)."""
    out: List[Dict[str, Any]] = [{}]
    if not quick:
        if name != "cloth":
            out += [{"dome_lights": 0}, {"dome_lights": 64}]
            out += [{"specular_samples": 1024}]
        if has_msaa:
            out += [{"msaa": m} for m in (1, 4, 8)]
        out += [{"bounce": False}]
    return out


def _label(setting: Dict[str, Any]) -> str:
    return ", ".join(f"{k} {v}" for k, v in setting.items()) or "default"


def _time_frames(renderer, scene, camera, frames: int) -> float:
    renderer.render(scene, camera)
    times = []
    for _ in range(frames):
        start = time.perf_counter()
        renderer.render(scene, camera)
        times.append((time.perf_counter() - start) * 1e3)
    return float(statistics.median(times))


def _save_png(path: str, image: np.ndarray) -> None:
    import weft

    rgba = np.concatenate([image, np.full(image.shape[:2] + (1,), 255, np.uint8)], axis=-1)
    weft.save_png(path, np.ascontiguousarray(rgba))


def bench_scene(name: str, width: int, height: int, spp: int, frames: int, quick: bool,
                out_dir: str, progress: Optional[Progress]) -> Dict[str, Any]:
    import weft
    from weft.reference.picture import compare as cmp
    from weft.reference.picture import evaluate as ev
    from weft.reference.picture import scenes
    from weft.reference.picture.mitsuba_export import export_scene

    base = scenes.build(name)
    if progress:
        progress.update(f"{name}: Mitsuba path, {spp} spp")
    start = time.perf_counter()
    reference = ev.render_reference(base, width, height, spp)
    ref_s = time.perf_counter() - start
    direct = ev.render_reference(base, width, height, spp, integrator="direct")
    notes = export_scene(base.scene, base.camera, 8, 8, 1,
                         environment=base.reference_environment,
                         lights=base.reference_lights).notes
    has_msaa = hasattr(weft.Renderer, "msaa")
    rows: List[Dict[str, Any]] = []
    floor: Dict[str, float] = {}
    for k, setting in enumerate(_settings(name, quick, has_msaa)):
        if progress:
            progress.update(f"{name}: weft {_label(setting)}")
        build_kw = {k2: v for k2, v in setting.items() if k2 in ("dome_lights", "specular_samples")}
        ref = scenes.build(name, **build_kw) if build_kw else base
        renderer = weft.Renderer(width, height)
        for key in ("msaa", "bounce"):  # renderer settings
            if key in setting:
                setattr(renderer, key, setting[key])
        e = ev.evaluate(ref, renderer, spp, reference=reference)
        ms = _time_frames(renderer, ref.scene, ref.camera, frames)
        vs_direct = cmp.compare(e.weft_linear, direct, e.regions, ref.exposure)["regions"]
        if k == 0:
            floor = ev.noise_floor(base, width, height, spp, reference, e.regions)
            _save_png(os.path.join(out_dir, f"{name}.png"),
                      cmp.side_by_side(e.result["weft_display"], e.result["reference_display"],
                                       e.result["flip_map"], scale=2 if width < 200 else 1))
        rows.append({"setting": _label(setting), "frame_ms": ms,
                     "regions": e.result["regions"],
                     "vs_direct": {r: v["flip"] for r, v in vs_direct.items()}})
    return {"scene": name, "description": base.description, "reference_seconds": ref_s,
            "background_drawn": base.background_drawn, "noise_floor": floor,
            "notes": notes, "rows": rows}


def bench_aa(width: int, height: int) -> Dict[str, Any]:
    import weft
    from weft.reference.picture import antialias as aa

    out: Dict[str, Any] = {"size": f"{width}x{height}", "factor": aa.FACTOR,
                           "msaa": getattr(weft.Renderer(8, 8), "msaa", None)}
    scene, camera = weft.default_scene()
    r = aa.aa_edge_error(scene, camera, weft.Renderer(width, height))
    out["mesh_edges"], out["mesh_edge_pixels"] = r["mesh_edges"], r["mesh_edges_pixels"]
    out["interior"] = r["interior"]
    hscene, hcamera, hw = aa.hair_scene(width, height)
    renderer = weft.Renderer(width, height)
    renderer.hair_primitive = "ribbons"
    renderer.hair_width = hw
    h = aa.aa_edge_error(hscene, hcamera, renderer)
    out["hair_edges"], out["hair_edge_pixels"] = h["hair_edges"], h["hair_edges_pixels"]
    out["hair_width_m"] = hw
    return out


def plot_error_vs_time(results: Sequence[Dict[str, Any]], path: str) -> Optional[str]:
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    cmap = plt.get_cmap("tab10")
    for ax, region in zip(axes, ("covered", "objects")):
        for i, s in enumerate(results):
            xs = [r["frame_ms"] for r in s["rows"]]
            ys = [r["regions"].get(region, {}).get("flip", np.nan) for r in s["rows"]]
            ax.scatter(xs, ys, color=cmap(i % 10), label=s["scene"])
            for x, y, r in zip(xs, ys, s["rows"]):
                ax.annotate(r["setting"], (x, y), fontsize=6, alpha=0.7)
            nf = s["noise_floor"].get(region)
            if nf is not None:
                ax.axhline(nf, color=cmap(i % 10), ls=":", lw=0.8)
        ax.axhline(0.04 if region == "covered" else 0.08, color="black", ls="--", lw=1)
        ax.set_xlabel("weft frame time (ms, lavapipe)")
        ax.set_ylabel(f"mean FLIP vs Mitsuba, {region}")
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("weft against Mitsuba 3 (path traced): error vs frame time "
                 "(dashed: issue 18 target, dotted: reference noise floor)")
    fig.tight_layout()
    save_figure(fig, path, dpi=100)
    return None


def to_markdown(report: Dict[str, Any]) -> str:
    m = report["machine"]
    f3 = lambda v: "n/a" if v is None else f"{v:.3f}"  # noqa: E731
    lines = ["# weft picture benchmark (against Mitsuba 3)", "",
             f"`{report['command']}` on {m.get('processor', '?')} ({m.get('cpu_count')} CPUs), "
             f"device {m.get('device', {}).get('name', '?')}; {report['size']}, Mitsuba "
             f"{report['mitsuba']} `scalar_rgb` path tracer at {report['spp']} spp.", "",
             "FLIP: mean per-pixel LDR-FLIP of exposure + clamp + sRGB of both frames; rel: "
             "sum |dY| / sum Y of the linear luminance; bias: sum dY / sum Y (< 0: weft too "
             "dark). Regions: whole image, covered (background masked out until weft draws "
             "the sky), objects (not the ground), geometric edges, unlit side of the objects "
             "(n.l <= 0 for the key light). Noise floor: FLIP of a second reference frame "
             "(another seed) against the first. `vs direct`: FLIP against Mitsuba's direct-"
             "lighting-only frame (what is left when bounce light is not counted).", ""]
    header = ["scene", "setting", "ms", *[f"FLIP {r}" for r in REGIONS], "rel covered",
              "rel objects", "bias unlit", "FLIP covered vs direct"]
    rows = []
    for s in report["scenes"]:
        for r in s["rows"]:
            g = r["regions"]
            rows.append([s["scene"], r["setting"], f"{r['frame_ms']:.1f}",
                         *[f3(g.get(x, {}).get("flip")) for x in REGIONS],
                         f3(g.get("covered", {}).get("rel")), f3(g.get("objects", {}).get("rel")),
                         f3(g.get("unlit", {}).get("bias")),
                         f3(r["vs_direct"].get("covered"))])
        nf = s["noise_floor"]
        rows.append([s["scene"], "*noise floor*", "", *[f3(nf.get(x)) for x in REGIONS],
                     "", "", "", ""])
    lines.append(markdown_table(header, rows))
    lines += ["", "Side by side (weft | Mitsuba | FLIP): " + ", ".join(
        f"`{s['scene']}.png`" for s in report["scenes"])]
    for s in report["scenes"]:
        if s["notes"]:
            lines += ["", f"Export notes, {s['scene']}: " + "; ".join(s["notes"])]
    a = report["aa"]
    lines += ["", f"## Anti-aliasing ({a['size']}, against the {a['factor']}x{a['factor']} "
              f"supersampled frame; MSAA: {a['msaa'] if a['msaa'] is not None else 'not built'})",
              "", markdown_table(
                  ["edges", "mean abs diff (1/255)", "pixels", "target"],
                  [["mesh silhouettes (default scene)", f3(a["mesh_edges"]),
                    a["mesh_edge_pixels"], "<= 4"],
                   ["hair (1-pixel ribbons)", f3(a["hair_edges"]), a["hair_edge_pixels"],
                    "<= 6"],
                   ["interior (default scene)", f3(a["interior"]), "", ""]])]
    if report.get("plot"):
        lines += ["", f"Error against time: `{report['plot']}`"]
    elif report.get("plot_note"):
        lines += ["", f"Error against time: {report['plot_note']}"]
    return "\n".join(lines) + "\n"


def run(args: argparse.Namespace) -> int:
    import mitsuba

    from weft.reference.picture import scenes as ref_scenes

    quick = bool(args.quick)
    width, height = args.size or ((96, 72) if quick else (256, 192))
    spp = args.spp or (32 if quick else 1024)
    frames = args.frames or (2 if quick else 5)
    names = args.scenes or list(ref_scenes.SCENES)
    for n in names:
        if n not in ref_scenes.SCENES:
            print(f"unknown scene {n!r}; known: {', '.join(ref_scenes.SCENES)}")
            return 2
    os.makedirs(args.out, exist_ok=True)
    progress = Progress(len(names) + 2, enabled=args.progress)
    t0 = time.perf_counter()
    results = []
    for n in names:
        results.append(bench_scene(n, width, height, spp, frames, quick, args.out, progress))
        progress.step(n)
    progress.update("anti-aliasing")
    aa = bench_aa(width, height)
    progress.step("anti-aliasing")
    plot_note = plot_error_vs_time(results, os.path.join(args.out, "error_vs_time.png"))
    command = "python -m weft.bench picture" + (" --quick" if quick else "")
    if args.size:
        command += f" --size {width} {height}"
    if args.spp:
        command += f" --spp {spp}"
    report = {"benchmark": "picture", "command": command, "size": f"{width}x{height}",
              "spp": spp, "frames": frames, "mitsuba": mitsuba.__version__,
              "scenes": results, "aa": aa, "machine": machine_info(),
              "plot": None if plot_note else "error_vs_time.png", "plot_note": plot_note,
              "seconds": time.perf_counter() - t0}
    progress.step("report")
    progress.close()
    markdown = to_markdown(report)
    paths = write_report(args.out, report, markdown)
    print(markdown)
    print("wrote " + " and ".join(paths))
    return 0
