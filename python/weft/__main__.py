"""Command line of weft: ``python -m weft {demo,devices,render,btf,ibl,batch} ...``.

    python -m weft demo [--width W] [--height H] [--frames N] [--headless] [--no-vsync]
                        [--out PNG|DIR] [--screenshot PNG] [--stats JSON] [--script FILE]
                        [--shader-dir DIR]
    python -m weft devices [--json]
    python -m weft render [--width W] [--height H] [--out PNG] [--scene default|cloth]
                          [--steps N] [--environment FILE [--source S] [--wrap W]
                          [--dome N] [--sun-lights N]] [--background PNG]
    python -m weft btf {synth PRESET OUT, fit PATH --out DIR} ...   (see weft.btf.cli)
    python -m weft ibl {convert,irradiance,extract-lights} ...   (see python -m weft ibl --help)
    python -m weft batch {btf DATASET... --out DIR, render JOBS.json --out DIR} [--serial |
                         --address HOST:PORT] ...   (Ray; see python -m weft batch --help)

Benchmarks have their own entry point: ``python -m weft.bench --help``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from typing import Any, Dict, List, Optional, Sequence, Tuple


def _checked(convert, ok, expected: str):
    """An argparse type: `convert` the text, then require `ok(value)`; errors say `expected`."""
    def parse(text: str):
        try:
            value = convert(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected {expected}, got {text!r}") from None
        if not ok(value):
            raise argparse.ArgumentTypeError(f"expected {expected}, got {value}")
        return value

    return parse


_positive_int = _checked(int, lambda v: v > 0, "a positive integer")
_non_negative_int = _checked(int, lambda v: v >= 0, "an integer >= 0")
_wrap_value = _checked(float, lambda v: 0.0 < v <= 1.0, "a number in (0, 1]")
_dome_size = _checked(int, lambda v: 0 <= v <= 64 and v % 8 == 0,
                      "0 or a multiple of 8 up to 64")


#: Default --steps of ``render --scene cloth`` (weft.scenes.DEFAULT_STEPS; not imported here so
#: that --help does not load the native module).
_CLOTH_STEPS = 180


def _add_picture_arguments(parser: argparse.ArgumentParser) -> None:
    """The renderer's picture settings, the same for `render` and `demo`."""
    parser.add_argument("--msaa", type=int, choices=(1, 2, 4, 8), default=4,
                        help="multisample anti-aliasing samples per pixel (4)")
    parser.add_argument("--ao", type=_dome_size, default=8, metavar="N",
                        help="ambient occlusion of a constant ambient (scenes without an "
                             "environment): dome shadow lights, 0 (off) or a multiple of 8 up "
                             "to 64 (8)")
    parser.add_argument("--no-bounce", action="store_true",
                        help="no bounce light from the receivers (ground) onto the objects")
    parser.add_argument("--exposure", type=float, default=0.0, metavar="EV",
                        help="exposure in photographic stops: the image shows radiance x 2^EV (0)")
    parser.add_argument("--tone-map", choices=("clamp", "aces", "agx", "neutral"),
                        default="clamp",
                        help="how radiance above 1 is shown: clamp (the seed's look, clips), "
                             "aces (filmic), agx (Blender's) or neutral (Khronos PBR Neutral, "
                             "colours kept); default clamp")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python -m weft",
        description="weft: real-time cloth, hair and fur with BTF materials and image-based "
                    "lighting (Vulkan). Run the demo, list Vulkan devices, render the default "
                    "or the cloth scene to a PNG (lit by a captured environment, composited "
                    "over a photo), synthesise or fit BTFs, convert and filter environments, and "
                    "run batches of BTF fits or frames on a Ray cluster.",
        epilog="Environment: WEFT_DEVICE=<index|name substring> picks the Vulkan device, "
               "WEFT_VALIDATION=1 enables the validation layers. Benchmarks: "
               "python -m weft.bench --help",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True

    demo = sub.add_parser(
        "demo", help="run the demo (window if a display exists, else a headless PNG)",
        description="Runs the seed's cloth environment (terrain, sphere, a cloth held at one "
                    "edge in the wind, sun and moon): a GLFW window when a display exists (and "
                    "--headless is not given), otherwise offscreen to --out. Window controls: "
                    "left-drag grabs the cloth, arrows orbit, 1/2 wind, R wind direction, L "
                    "light, T day-night, N normal map, S shadows, P PCF, H holes, C reset, "
                    "Space pause, Esc quit.")
    demo.add_argument("--width", type=_positive_int, default=1280, help="width in pixels (1280)")
    demo.add_argument("--height", type=_positive_int, default=720, help="height in pixels (720)")
    demo.add_argument("--frames", type=_non_negative_int, default=0,
                      help="stop after N frames, one fixed 60 Hz simulation step each "
                           "(reproducible); 0 = a window runs until closed, headless renders "
                           "one frame after the cloth settled")
    demo.add_argument("--headless", action="store_true",
                      help="render offscreen even when a display is available")
    demo.add_argument("--no-vsync", dest="vsync", action="store_false",
                      help="present without waiting for vertical sync")
    demo.add_argument("--out", default="out/demo.png",
                      help="headless output: a PNG (default out/demo.png), or with --frames a "
                           "directory for frame_NNNN.png and stats.json")
    demo.add_argument("--shader-dir", default=os.environ.get("WEFT_SHADER_DIR", ""),
                      metavar="DIR",
                      help="shader hot reload: watch DIR (laid out like glsl/); edited shaders "
                           "are recompiled and used from the next frame (default "
                           "$WEFT_SHADER_DIR)")
    demo.add_argument("--environment", default="", metavar="FILE",
                      help="light the scene with a captured environment instead of the sun and "
                           "moon: an equirectangular (2:1) or sphere-map (square) .hdr/.exr/.png "
                           "(SH9 diffuse, blurred shadows from a dome of 16 lights)")
    demo.add_argument("--time", type=float, default=None, metavar="HOURS", dest="hour",
                      help="time of day in hours 0..24 (6 sunrise, 12 noon, 18 sunset): the "
                           "analytic sky (Preetham 1999) and its sun, or the moon at night")
    demo.add_argument("--script", default="", metavar="FILE",
                      help="scripted input: lines '<frame> key <K>', '<frame> grab <x> <y>', "
                           "'<frame> drag <x> <y>', '<frame> release'")
    demo.add_argument("--screenshot", default="",
                      help="window mode: save the last presented frame to this PNG")
    demo.add_argument("--stats", default="", metavar="JSON",
                      help="write the last frame's statistics to this JSON file")
    _add_picture_arguments(demo)
    demo.set_defaults(handler=_cmd_demo)

    devices = sub.add_parser("devices", help="list the Vulkan devices and the selected one",
                             description="Lists every Vulkan device; '*' marks the one weft "
                                         "renders with (override with WEFT_DEVICE).")
    devices.add_argument("--json", action="store_true", help="print JSON instead of a table")
    devices.set_defaults(handler=_cmd_devices)

    render = sub.add_parser(
        "render", help="render the default or the cloth scene headless to a PNG",
        description="Renders a scene offscreen, writes a PNG and prints its path and the frame "
                    "statistics. --scene cloth drops a cloth onto a sphere on a ground plane and "
                    "simulates it for --steps 60 Hz steps first. --environment lights the scene "
                    "with a captured environment instead of its sun: SH9 diffuse light, GGX "
                    "reflections and shadows from a dome of --dome shadow lights (SPEC §4.5).",
        epilog="Example: python -m weft render --scene cloth --environment ball.png "
               "--source sphere --wrap 0.9 --dome 16 --out out/cloth.png")
    render.add_argument("--width", type=_positive_int, default=1280, help="width in pixels (1280)")
    render.add_argument("--height", type=_positive_int, default=720, help="height in pixels (720)")
    render.add_argument("--out", default="out/render.png", help="output PNG (out/render.png)")
    render.add_argument("--scene", choices=("default", "cloth"), default="default",
                        help="default: ground, sphere, box and sun (weft.default_scene); cloth: "
                             "a cloth draped over a sphere on a ground plane "
                             "(weft.scenes.cloth_scene)")
    render.add_argument("--steps", type=_non_negative_int, default=None,
                        help="--scene cloth: simulation steps (1/60 s each) before rendering "
                             "(default %d, enough to drape)" % _CLOTH_STEPS)
    render.add_argument("--environment", default="", metavar="FILE",
                        help="light the scene with an environment image (.hdr, .exr, .npy, "
                             ".png): equirectangular, cube cross, sphere map (mirror ball) or "
                             "fisheye; .npy may also hold cube faces (6, S, S, 3)")
    render.add_argument("--source", choices=("auto", "equirect", "cross", "sphere", "fisheye"),
                        default=None,
                        help="kind of --environment image (default auto: 2:1 equirect, 4:3 or "
                             "3:4 cross, square sphere map)")
    render.add_argument("--wrap", type=_wrap_value, default=None,
                        help="sphere-map wrap value in (0, 1]: 1 = full 360-degree sphere map, "
                             "less for a photographed mirror ball's visible part (default 1)")
    render.add_argument("--sun-lights", type=_non_negative_int, default=None, metavar="N",
                        help="extract up to N bright lights (suns) from --environment as "
                             "directional lights with sharp shadows; the dome lights with the "
                             "rest of the sky (default 0)")
    render.add_argument("--background", default="", metavar="PNG",
                        help="AR: composite over this camera image (PNG); the ground becomes a "
                             "phantom that shows the image with the shadows it receives")
    render.add_argument("--dome", type=_dome_size, default=None, metavar="N",
                        help="shadow lights in the environment's dome: 0 or a multiple of 8 up "
                             "to 64 (default 16 with --environment)")
    _add_picture_arguments(render)
    from weft.reporting import add_progress_arguments

    add_progress_arguments(render)
    render.add_argument("--quiet", action="store_true",
                        help="no progress bar (as --no-progress); the result lines still print")
    render.set_defaults(handler=_cmd_render)

    from weft.btf import cli as btf_cli

    btf_cli.add_parsers(sub)

    from weft.ibl.cli import add_ibl_parser

    add_ibl_parser(sub)

    from weft.batch.cli import add_parser as add_batch_parser

    add_batch_parser(sub)
    return parser


def _cmd_demo(args: argparse.Namespace) -> int:
    import weft

    return int(weft.run_demo(width=args.width, height=args.height, frames=args.frames,
                             headless=args.headless, vsync=args.vsync, out=args.out,
                             screenshot=args.screenshot, stats_json=args.stats,
                             script=args.script, shader_dir=args.shader_dir,
                             environment=args.environment, hour=args.hour, msaa=args.msaa,
                             ambient_occlusion=args.ao, bounce=not args.no_bounce,
                             exposure=args.exposure, tone_map=args.tone_map))


def format_table(rows: List[Dict[str, Any]], columns: Sequence[str]) -> str:
    """Plain-text table with a header row and left-aligned columns."""
    cells = [[str(c) for c in columns]] + [[str(row.get(c, "")) for c in columns] for row in rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(columns))]
    lines = ["  ".join(v.ljust(w) for v, w in zip(r, widths)).rstrip() for r in cells]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def _cmd_devices(args: argparse.Namespace) -> int:
    import weft

    devices = weft.devices()
    if args.json:
        print(json.dumps(devices, indent=2))
        return 0
    rows = [dict(d, sel="*" if d.get("selected") else "") for d in devices]
    print(format_table(rows, ["sel", "index", "name", "type", "api_version", "driver"]))
    if not devices:
        print("no Vulkan devices found", file=sys.stderr)
        return 1
    return 0


def format_stats(stats: Dict[str, Any]) -> str:
    """Human-readable frame statistics (one line per pass)."""
    def ms(value: Optional[float]) -> str:
        return "n/a" if value is None or value < 0 else f"{value:.3f} ms"

    lines = [f"frame {stats.get('frame_index')}: cpu {ms(stats.get('cpu_ms'))}, "
             f"gpu {ms(stats.get('gpu_ms'))}"]
    for p in stats.get("passes", []):
        lines.append(f"  {p['name']:<12} cpu {ms(p.get('cpu_ms')):>12}   gpu {ms(p.get('gpu_ms'))}")
    if stats.get("culled"):
        lines.append("  culled: " + ", ".join(stats["culled"]))
    return "\n".join(lines)


def _check_render_args(args: argparse.Namespace) -> None:
    """Options that only make sense together: raises ValueError naming the missing one."""
    if not args.environment:
        given = [f"--{n.replace('_', '-')}" for n in ("source", "wrap", "dome", "sun_lights")
                 if getattr(args, n) is not None]
        if given:
            verb = "needs" if len(given) == 1 else "need"
            raise ValueError(f"{' and '.join(given)} {verb} --environment FILE")
    if args.steps is not None and args.scene != "cloth":
        raise ValueError("--steps applies to --scene cloth")


def _cmd_render(args: argparse.Namespace) -> int:
    import weft
    from weft.reporting import Progress

    _check_render_args(args)
    steps = (_CLOTH_STEPS if args.steps is None else args.steps) if args.scene == "cloth" else 0
    # The seconds go to reading the environment, simulating the cloth and the first frame
    # (pipelines, captures): one bar over them, each simulation step one unit.
    units = 3 + steps + (2 if args.environment else 0) + (1 if args.background else 0)
    with Progress(units, enabled=False if args.quiet else args.progress) as bar:
        image, renderer, cube = _render(args, steps, bar)
    directory = os.path.dirname(args.out)
    if directory:
        os.makedirs(directory, exist_ok=True)
    weft.save_png(args.out, image)
    what = args.scene + (f", environment {args.environment}" if cube is not None else "")
    print(f"wrote {os.path.abspath(args.out)} ({args.width}x{args.height}, {what}, "
          f"{renderer.device_name})")
    print(format_stats(renderer.stats))
    return 0


def _render(args: argparse.Namespace, steps: int, bar: Any) -> Tuple[Any, Any, Any]:
    """The render command's work, reported to ``bar`` (weft.reporting.Progress) step by step:
    returns (image, renderer, environment cube or None)."""
    import weft

    cube = None
    if args.environment:  # read (and reject) the environment before any simulation or GPU work
        import weft.ibl

        bar.update(f"reading {os.path.basename(args.environment)}")
        # 256 texels per face: it is also the background the camera sees
        cube = weft.ibl.load_environment_cube(
            args.environment, 256, source=args.source or "auto",
            wrap=1.0 if args.wrap is None else args.wrap)
        bar.step()
    bar.update("building the scene")
    if args.scene == "cloth":
        import weft.scenes

        # The scene draws the cloth as it is now, so stepping it here equals cloth_scene(steps).
        scene, camera, cloth = weft.scenes.cloth_scene(steps=0)
        bar.step()
        bar.update(f"simulating the cloth ({steps} steps)")
        for _ in range(steps):
            cloth.step(1.0 / 60.0)
            bar.step()
    else:
        scene, camera = weft.default_scene()
        bar.step()
    if cube is not None:
        import weft.scenes

        bar.update("lighting with the environment")
        weft.scenes.light_with_environment(scene, cube,
                                           dome_lights=16 if args.dome is None else args.dome,
                                           sun_lights=args.sun_lights or 0)
        bar.step()
    if args.background:
        import weft.scenes

        bar.update("compositing over the background")
        weft.scenes.composite_over(scene, weft.load_png(args.background))
        bar.step()
    bar.update("creating the renderer")
    renderer = weft.Renderer(args.width, args.height, msaa=args.msaa, exposure=args.exposure,
                             tone_map=args.tone_map, ambient_occlusion=args.ao,
                             bounce=not args.no_bounce)
    bar.step()
    bar.update("rendering (pipelines, captures)")
    image = renderer.render(scene, camera)
    bar.step("rendered")
    return image, renderer, cube


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.handler(args)
    except (ValueError, OSError, RuntimeError) as exc:
        print(f"weft: error: {exc}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
