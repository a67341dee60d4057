"""The Filament peer of the render benchmark (issue 19, "Lavapipe frame time").

Filament, through Open3D's ``open3d.visualization.rendering.OffscreenRenderer`` (PyPI
``open3d``, the optional extra ``weft[filament]``), renders a scene matched to
``weft.default_scene()`` on the same Vulkan driver, and its frame time is measured in the same
run as weft's, frame by frame alternately, so that both see the same machine load:

- ``defaults``: Filament as Open3D sets it up (4x MSAA, FXAA, SSAO, ACES colour grading),
  weft's ``Renderer(width, height)`` defaults (MSAA 4, its default tone map, bounce light,
  ambient occlusion);
- ``post_off``: Filament with ``view.set_post_processing(False)`` and ``set_sample_count(1)``
  (no MSAA, FXAA, SSAO or colour grading), weft with ``msaa=1``, ``tone_map='clamp'``,
  ``ambient_occlusion=0``.

Both re-render their shadow map every frame (weft with ``reuse_shadow_maps=False``; Filament
does so itself). A frame is the wall time of one ``render`` call that returns the 8-bit image
(drawing and read-back, both sides).

The matched scene is exported from weft's own scene (meshes, transforms, materials, the sun,
the camera), not restated here: the meshes with their normals and UVs; the materials as
Filament's ``defaultLit`` (metallic 0, reflectance 0.5, base colour = weft's base colour x kd,
the ground's texture image as the albedo map) with the roughness from weft's Blinn-Phong
shininess (:func:`shininess_to_roughness`); weft's sun (direction, colour) in lux such that a
Lambertian surface gets the same radiance at Filament's default camera exposure
(:func:`sun_illuminance`); weft's uniform ambient by Open3D's default image-based light,
scaled to the same mean irradiance (:data:`IBL_INTENSITY_PER_AMBIENT`): directional where
weft's is uniform, one of the differences listed under ``unmatched`` in the report.

Where open3d is not installed or cannot make an offscreen renderer, :func:`measure_peer`
returns ``{"skipped": True, "note": ...}`` and raises nothing. The renderer is first made in a
child process (:func:`probe`), so that a driver or window-system failure that aborts the
process ends the probe, not the benchmark.
"""

from __future__ import annotations

import math
import os
import re
import statistics
import subprocess
import sys
import time
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

PEER = "Filament (Open3D OffscreenRenderer)"
MODES: Tuple[str, ...] = ("defaults", "post_off")

#: Open3D's default camera exposure (aperture f/16, 1/125 s, ISO 100): EV100 = log2(16^2 *
#: 125) and exposure = 1 / (1.2 * 2^EV100), by which Filament multiplies scene luminance.
FILAMENT_EXPOSURE = 1.0 / (1.2 * 16.0 ** 2 * 125.0)

#: Open3D's default IBL intensity per unit of weft ambient (the mean of weft's ambient RGB):
#: measured on the shadowed ground of the matched scene (sun off, post-processing off, 320x180)
#: as the IBL intensity whose mean linear colour there equals weft's (ambient x texture).
IBL_INTENSITY_PER_AMBIENT = 75000.0

#: Measured factor on :func:`sun_illuminance`'s Lambertian estimate: with it, the sunlit ground
#: minus the shadowed ground (the sun's share) has weft's mean linear colour (same measurement
#: as :data:`IBL_INTENSITY_PER_AMBIENT`; the three channels agreed within 1%). Without it
#: Filament's ground got 1/1.85 of weft's sunlight.
SUN_CALIBRATION = 1.85

#: Warm-up frames before timing: Filament compiles its pipelines over the first frames.
WARMUP_FRAMES = 2

_PROBE_TIMEOUT_S = 120.0


class PeerUnavailable(RuntimeError):
    """open3d is not importable or cannot make an offscreen renderer here."""


# --------------------------------------------------------------------------------------------
# Conversions between weft's shading model and Filament's
# --------------------------------------------------------------------------------------------

def shininess_to_roughness(shininess: float) -> float:
    """Filament's perceptual roughness for a Blinn-Phong exponent: the Beckmann slope alpha
    with the same highlight width, alpha^2 = 2 / (shininess + 2) (Walter et al. 2007), and
    Filament's roughness = sqrt(alpha)."""
    if not shininess >= 0.0:
        raise ValueError(f"shininess must be >= 0, got {shininess}")
    alpha = math.sqrt(2.0 / (shininess + 2.0))
    return float(math.sqrt(alpha))


def sun_illuminance(intensity: float, exposure: float = FILAMENT_EXPOSURE,
                    calibration: float = SUN_CALIBRATION) -> float:
    """Filament sun illuminance (lux) for weft's sun ``intensity``: a Lambertian surface of
    albedo rho gets rho x intensity x cos from weft and exposure x rho / pi x E x cos from
    Filament, so E = intensity x pi / exposure, times the measured ``calibration``."""
    return float(intensity) * math.pi / exposure * calibration


def linear_to_srgb(value: Any) -> np.ndarray:
    """sRGB encoding of linear values in [0, 1] (Open3D takes the background colour encoded)."""
    x = np.clip(np.asarray(value, dtype=np.float64), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1.0 / 2.4) - 0.055)


# --------------------------------------------------------------------------------------------
# The scene, exported from weft
# --------------------------------------------------------------------------------------------

def _vec(value: Any) -> np.ndarray:
    return np.asarray(tuple(value), dtype=np.float64)


def export_scene(scene: Any, camera: Any) -> Dict[str, Any]:
    """What the peer needs of a ``weft.Scene`` and ``weft.Camera``, as NumPy arrays and
    floats: per instance the mesh (positions, normals, uvs, indices), transform and material;
    the first directional light as the sun; ambient, background and camera. Lights beyond the
    first directional light are listed under ``"unmatched"``."""
    import weft

    meshes: List[Dict[str, Any]] = []
    for index in range(int(scene.instance_count)):
        mesh = scene.mesh(index)
        material = scene.material(index)
        texture = material.texture
        image = None if texture is None else np.asarray(texture.image, dtype=np.uint8)
        color = _vec(material.base_color) * _vec(material.kd)
        meshes.append({
            "positions": np.asarray(mesh.positions, dtype=np.float64),
            "normals": np.asarray(mesh.normals, dtype=np.float64),
            "uvs": np.asarray(mesh.uvs, dtype=np.float64),
            "indices": np.asarray(mesh.indices, dtype=np.int32).reshape(-1, 3),
            "transform": np.asarray(scene.transform(index), dtype=np.float64),
            "base_color": color,
            "texture": image,
            "texture_srgb": True if texture is None else bool(texture.srgb),
            "ks": _vec(material.ks),
            "shininess": float(material.shininess),
        })
    sun: Optional[Dict[str, Any]] = None
    unmatched: List[str] = []
    for i, light in enumerate(scene.lights):
        if sun is None and isinstance(light, weft.DirectionalLight):
            sun = {"direction": _vec(light.direction), "color": _vec(light.color),
                   "intensity": float(light.intensity), "shadows": bool(light.cast_shadows)}
        else:
            unmatched.append(f"light {i} ({type(light).__name__}) is not exported")
    if int(getattr(scene, "hair_count", 0)):
        unmatched.append("hair is not exported")
    return {
        "meshes": meshes,
        "sun": sun,
        "ambient": _vec(scene.ambient),
        "background": _vec(scene.background),
        "camera": {"position": _vec(camera.position), "target": _vec(camera.target),
                   "up": _vec(camera.up), "fov_y": float(camera.fov_y),
                   "near": float(camera.near), "far": float(camera.far)},
        "unmatched": unmatched,
    }


# --------------------------------------------------------------------------------------------
# Open3D
# --------------------------------------------------------------------------------------------

def import_open3d() -> Any:
    """The ``open3d`` module; :class:`PeerUnavailable` when it does not import."""
    try:
        import open3d  # type: ignore[import-not-found]
        import open3d.visualization.rendering  # type: ignore[import-not-found]  # noqa: F401
    except Exception as exc:  # ImportError, or OSError for a missing shared library
        raise PeerUnavailable(f"open3d does not import ({type(exc).__name__}: {exc}); "
                              "install the optional extra: pip install 'weft[filament]' "
                              "(open3d 0.20 needs Debian's libusb-1.0-0)") from exc
    return open3d


_PROBE_SCRIPT = """
import open3d.visualization.rendering as r
ren = r.OffscreenRenderer(16, 16)
print("open3d-offscreen-ok", flush=True)
"""


def probe(timeout_s: float = _PROBE_TIMEOUT_S) -> Dict[str, Any]:
    """Makes an Open3D offscreen renderer in a child process: ``{"ok", "log", "note"}``, where
    ``log`` is its output (Filament names its backend and device there). A crash or hang of the
    child is reported in ``note``."""
    try:
        proc = subprocess.run([sys.executable, "-c", _PROBE_SCRIPT], capture_output=True,
                              text=True, timeout=timeout_s)
    except subprocess.TimeoutExpired:
        return {"ok": False, "log": "", "note": f"open3d's OffscreenRenderer did not start "
                                                 f"within {timeout_s:.0f} s"}
    log = proc.stdout + proc.stderr
    if proc.returncode == 0 and "open3d-offscreen-ok" in proc.stdout:
        return {"ok": True, "log": log, "note": ""}
    tail = " | ".join(line.strip() for line in log.strip().splitlines()[-3:])
    return {"ok": False, "log": log,
            "note": f"open3d's OffscreenRenderer failed (exit {proc.returncode}): {tail}"}


def backend_info(log: str) -> Dict[str, Optional[str]]:
    """Filament's backend and device as Open3D/Filament print them when the engine starts."""
    def find(pattern: str) -> Optional[str]:
        match = re.search(pattern, log)
        return match.group(1).strip() if match else None

    return {"backend": find(r"FEngine resolved backend:\s*(\S+)"),
            "device": find(r"Selected physical device '([^']+)'"),
            "driver": find(r"Vulkan device driver:\s*(.+)"),
            "selection": find(r"EngineInstance:\s*(.+)")}


class FilamentScene:
    """The matched scene in an Open3D ``OffscreenRenderer`` (one per process: Open3D keeps one
    Filament engine)."""

    def __init__(self, o3d: Any, width: int, height: int, exported: Dict[str, Any]) -> None:
        rendering = o3d.visualization.rendering
        self.width, self.height = int(width), int(height)
        self.renderer = rendering.OffscreenRenderer(self.width, self.height)
        self._rendering = rendering
        self.settings: Dict[str, Any] = {}
        scene = self.renderer.scene
        scene.show_skybox(False)
        scene.show_axes(False)
        scene.set_background([*map(float, linear_to_srgb(exported["background"])), 1.0])
        for i, mesh in enumerate(exported["meshes"]):
            name = f"mesh{i}"
            scene.add_geometry(name, self._mesh(o3d, mesh), self._material(o3d, mesh), False)
            scene.set_geometry_transform(name, mesh["transform"])

        sun = exported["sun"]
        filament = scene.scene
        if sun is not None:
            direction = sun["direction"] / np.linalg.norm(sun["direction"])
            filament.set_sun_light(direction.astype(np.float32),
                                   sun["color"].astype(np.float32),
                                   sun_illuminance(sun["intensity"]))
            filament.enable_sun_light(True)
        else:
            filament.enable_sun_light(False)
        ambient = float(np.mean(exported["ambient"]))
        filament.enable_indirect_light(ambient > 0.0)
        filament.set_indirect_light_intensity(IBL_INTENSITY_PER_AMBIENT * ambient)

        cam = exported["camera"]
        self.renderer.setup_camera(math.degrees(cam["fov_y"]),
                                   cam["target"].astype(np.float32),
                                   cam["position"].astype(np.float32),
                                   cam["up"].astype(np.float32), cam["near"], cam["far"])

    @staticmethod
    def _mesh(o3d: Any, mesh: Dict[str, Any]) -> Any:
        out = o3d.geometry.TriangleMesh()
        out.vertices = o3d.utility.Vector3dVector(mesh["positions"])
        out.vertex_normals = o3d.utility.Vector3dVector(mesh["normals"])
        out.triangles = o3d.utility.Vector3iVector(mesh["indices"])
        # Open3D takes UVs per triangle corner, with v up (image row 0 at v = 1); weft's v
        # runs down the image.
        uv = mesh["uvs"][mesh["indices"].reshape(-1)].copy()
        uv[:, 1] = 1.0 - uv[:, 1]
        out.triangle_uvs = o3d.utility.Vector2dVector(uv)
        return out

    @staticmethod
    def _material(o3d: Any, mesh: Dict[str, Any]) -> Any:
        material = o3d.visualization.rendering.MaterialRecord()
        material.shader = "defaultLit"
        material.base_color = [*map(float, mesh["base_color"]), 1.0]
        material.base_metallic = 0.0
        material.base_reflectance = 0.5
        material.base_roughness = shininess_to_roughness(mesh["shininess"])
        if mesh["texture"] is not None:
            rgb = np.ascontiguousarray(mesh["texture"][..., :3])
            material.albedo_img = o3d.geometry.Image(rgb)
        return material

    def configure(self, mode: str) -> Dict[str, Any]:
        """Sets the view to ``mode`` ("defaults" or "post_off"); returns what was set. The
        defaults are set explicitly (they are Open3D's own), so that the modes can alternate."""
        view = self.renderer.scene.view
        rendering = self._rendering
        if mode == "defaults":
            view.set_post_processing(True)
            view.set_sample_count(4)
            view.set_antialiasing(True, False)
            view.set_ambient_occlusion(True, False)
            view.set_color_grading(rendering.ColorGrading(rendering.ColorGrading.Quality.HIGH,
                                                          rendering.ColorGrading.ToneMapping.ACES))
            settings = {"post_processing": True, "msaa": 4, "fxaa": True, "ssao": True,
                        "tone_map": "ACES (colour grading HIGH)", "shadows": "PCF"}
        elif mode == "post_off":
            view.set_post_processing(False)
            view.set_sample_count(1)
            settings = {"post_processing": False, "msaa": 1, "fxaa": False, "ssao": False,
                        "tone_map": "none", "shadows": "PCF"}
        else:
            raise ValueError(f"mode must be one of {MODES}, got {mode!r}")
        self.settings = settings
        return dict(settings)

    def render(self) -> np.ndarray:
        """One frame as an (H, W, 3) uint8 image."""
        return np.asarray(self.renderer.render_to_image())[..., :3]


# --------------------------------------------------------------------------------------------
# weft's side
# --------------------------------------------------------------------------------------------

def weft_settings(mode: str) -> Dict[str, Any]:
    """The ``weft.Renderer`` keyword arguments of a mode (shadow maps re-rendered each frame,
    as Filament does)."""
    if mode == "defaults":
        return {"reuse_shadow_maps": False}
    if mode == "post_off":
        return {"reuse_shadow_maps": False, "msaa": 1, "tone_map": "clamp",
                "ambient_occlusion": 0}
    raise ValueError(f"mode must be one of {MODES}, got {mode!r}")


def _describe_weft(renderer: Any, kwargs: Dict[str, Any]) -> Dict[str, Any]:
    out: Dict[str, Any] = {"kwargs": dict(kwargs)}
    for key in ("msaa", "tone_map", "exposure", "shadow_map_size", "bounce",
                "ambient_occlusion"):
        if hasattr(renderer, key):
            value = getattr(renderer, key)
            out[key] = value if isinstance(value, (bool, int, float, str)) else str(value)
    return out


# --------------------------------------------------------------------------------------------
# Measuring
# --------------------------------------------------------------------------------------------

def _median(values: Sequence[float]) -> Optional[float]:
    return float(statistics.median(values)) if values else None


def _timed(fn: Callable[[], Any]) -> Tuple[float, Any]:
    start = time.perf_counter()
    result = fn()
    return (time.perf_counter() - start) * 1e3, result


def _rgb(image: np.ndarray) -> np.ndarray:
    image = np.asarray(image)
    return image[..., :3] if image.ndim == 3 else np.repeat(image[..., None], 3, axis=2)


def side_by_side(rows: Sequence[Tuple[np.ndarray, np.ndarray]], gap: int = 4) -> np.ndarray:
    """One RGB picture: per row weft's image left, Filament's right, white gaps between."""
    parts = []
    for left, right in rows:
        left, right = _rgb(left), _rgb(right)
        height = max(left.shape[0], right.shape[0])
        pad = lambda im: np.pad(im, ((0, height - im.shape[0]), (0, 0), (0, 0)),  # noqa: E731
                                constant_values=255)
        parts.append(np.concatenate([pad(left), np.full((height, gap, 3), 255, np.uint8),
                                     pad(right)], axis=1))
    width = max(p.shape[1] for p in parts)
    out = []
    for i, part in enumerate(parts):
        if i:
            out.append(np.full((gap, width, 3), 255, np.uint8))
        out.append(np.pad(part, ((0, 0), (0, width - part.shape[1]), (0, 0)),
                          constant_values=255))
    return np.ascontiguousarray(np.concatenate(out, axis=0))


def unmatched_notes(exported: Dict[str, Any]) -> List[str]:
    """What the matched scene does not reproduce of weft's (for the report)."""
    textured = any(m["texture"] is not None for m in exported["meshes"])
    return [
        "shading models differ: weft's Blinn-Phong (kd, ks, shininess) vs Filament's "
        "defaultLit (GGX, metallic 0, reflectance 0.5 i.e. F0 = 4%, roughness = "
        "(2 / (shininess + 2))^(1/4)); ks is not carried over",
        "ambient: weft's uniform ambient is Open3D's default image-based light scaled to the "
        "same mean irradiance (directional, not uniform)",
        "sun in lux for Open3D's default exposure (f/16, 1/125 s, ISO 100), calibrated so that "
        "the ground's sunlit radiance matches weft's before tone mapping",
        "shadow maps: Filament's own size, cascades and PCF (Open3D exposes neither), weft's "
        "2048 with PCF radius 1",
        "weft's bounce light has no Filament counterpart; Filament's SSAO is matched by weft's "
        "ambient occlusion in 'defaults' and both are off in 'post_off'",
        "Filament with post-processing off writes linear colour without the sRGB encoding "
        "(darker picture); weft's 'clamp' encodes sRGB",
    ] + (["ground texture passed as Filament's albedo map (sRGB)"] if textured else []) \
        + list(exported["unmatched"])


def measure_peer(width: int, height: int, frames: int, progress: Any = None,
                 picture_path: Optional[str] = None, modes: Sequence[str] = MODES,
                 do_probe: bool = True) -> Dict[str, Any]:
    """Times Filament and weft on the matched default scene, alternately frame by frame, for
    each mode; returns per mode the median ms of both and weft / Filament. Never raises for a
    missing or failing open3d: returns ``{"skipped": True, "note": ...}`` instead."""
    import weft

    result: Dict[str, Any] = {"peer": PEER, "width": width, "height": height,
                              "frames": frames, "warmup_frames": WARMUP_FRAMES}
    try:
        o3d = import_open3d()
    except PeerUnavailable as exc:
        return {**result, "skipped": True, "note": str(exc)}
    result["open3d"] = getattr(o3d, "__version__", "?")
    if do_probe:
        if progress:
            progress.update("Filament peer: probing open3d's offscreen renderer")
        checked = probe()
        if not checked["ok"]:
            return {**result, "skipped": True, "note": checked["note"]}
        result["filament"] = backend_info(checked["log"])

    scene, camera = weft.default_scene()
    exported = export_scene(scene, camera)
    try:
        filament = FilamentScene(o3d, width, height, exported)
    except Exception as exc:  # Open3D raises RuntimeError for an engine it cannot make
        return {**result, "skipped": True,
                "note": f"open3d's OffscreenRenderer failed: {type(exc).__name__}: {exc}"}

    result["scene"] = {
        "meshes": len(exported["meshes"]),
        "triangles": int(sum(len(m["indices"]) for m in exported["meshes"])),
        "roughness": [round(shininess_to_roughness(m["shininess"]), 4)
                      for m in exported["meshes"]],
        "sun_lux": sun_illuminance(exported["sun"]["intensity"]) if exported["sun"] else None,
        "ibl_intensity": IBL_INTENSITY_PER_AMBIENT * float(np.mean(exported["ambient"])),
    }
    result["unmatched"] = unmatched_notes(exported)
    result["modes"] = {}
    pictures: List[Tuple[np.ndarray, np.ndarray]] = []
    for mode in modes:
        kwargs = weft_settings(mode)
        renderer = weft.Renderer(width, height, **kwargs)
        fil_settings = filament.configure(mode)
        for i in range(WARMUP_FRAMES):
            if progress:
                progress.update(f"Filament peer {mode}: warm-up {i + 1}/{WARMUP_FRAMES}")
            weft_image = renderer.render(scene, camera)
            fil_image = filament.render()
        fil_ms: List[float] = []
        weft_ms: List[float] = []
        for i in range(frames):
            if progress:
                progress.update(f"Filament peer {mode}: frame {i + 1}/{frames}")
            ms, fil_image = _timed(filament.render)
            fil_ms.append(ms)
            ms, weft_image = _timed(lambda r=renderer: r.render(scene, camera))
            weft_ms.append(ms)
        f_med, w_med = _median(fil_ms), _median(weft_ms)
        fil_rgb = _rgb(fil_image)
        result["modes"][mode] = {
            "filament_ms": f_med,
            "weft_ms": w_med,
            "ratio_weft_over_filament": (w_med / f_med) if f_med and w_med else None,
            # the median of frame-pair ratios: each pair ran back to back, under one load
            "ratio_pairs_median": _median([w / f for w, f in zip(weft_ms, fil_ms) if f > 0]),
            "filament_frames_ms": fil_ms,
            "weft_frames_ms": weft_ms,
            "filament_settings": fil_settings,
            "weft_settings": _describe_weft(renderer, kwargs),
            "filament_image_std": float(fil_rgb.astype(np.float64).std()),
            "filament_image_mean": float(fil_rgb.astype(np.float64).mean()),
            "weft_image_mean": float(_rgb(weft_image).astype(np.float64).mean()),
        }
        pictures.append((np.asarray(weft_image), fil_rgb))
        del renderer
    if picture_path:
        os.makedirs(os.path.dirname(os.path.abspath(picture_path)), exist_ok=True)
        weft.save_png(picture_path, side_by_side(pictures))
        result["picture"] = picture_path
        result["picture_layout"] = ("rows: " + ", ".join(modes)
                                    + "; left weft, right Filament")
    result["skipped"] = False
    return result


# --------------------------------------------------------------------------------------------
# Reporting
# --------------------------------------------------------------------------------------------

def _fmt(value: Optional[float], digits: int = 1) -> str:
    return "n/a" if value is None else f"{value:.{digits}f}"


def to_markdown(peer: Dict[str, Any]) -> str:
    """The peer's section of the render benchmark's Markdown report."""
    from weft.bench import markdown_table

    lines = ["## Peer: Filament on the same device", ""]
    if peer.get("skipped"):
        return "\n".join(lines + [f"Skipped: {peer.get('note', 'not run')}", ""])
    fil = peer.get("filament") or {}
    lines += [
        f"- {peer['peer']}, open3d {peer.get('open3d', '?')}: Filament backend "
        f"{fil.get('backend') or '?'} on {fil.get('device') or '?'}"
        + (f" ({fil['driver']})" if fil.get("driver") else ""),
        f"- default scene matched ({peer['scene']['meshes']} meshes, "
        f"{peer['scene']['triangles']} triangles) at {peer['width']}x{peer['height']}; "
        f"{peer['frames']} timed frame(s) per mode after {peer['warmup_frames']} warm-up, "
        "Filament and weft alternating frame by frame; medians of wall ms per frame "
        "(render + 8-bit read-back)",
        "",
    ]
    header = ["mode", "Filament settings", "weft settings", "Filament ms", "weft ms",
              "weft / Filament", "median pair ratio"]
    rows = []
    for mode, m in peer["modes"].items():
        f, w = m["filament_settings"], m["weft_settings"]
        fil_text = (f"MSAA {f['msaa']}, FXAA {'on' if f['fxaa'] else 'off'}, SSAO "
                    f"{'on' if f['ssao'] else 'off'}, tone map {f['tone_map']}")
        weft_text = (f"MSAA {w.get('msaa', '?')}, tone map {w.get('tone_map', '?')}, AO "
                     f"{w.get('ambient_occlusion', '?')}, bounce {w.get('bounce', '?')}")
        rows.append([mode, fil_text, weft_text, _fmt(m["filament_ms"]), _fmt(m["weft_ms"]),
                     _fmt(m["ratio_weft_over_filament"], 3),
                     _fmt(m.get("ratio_pairs_median"), 3)])
    lines.append(markdown_table(header, rows))
    lines += ["", "Not matched: " + "; ".join(peer.get("unmatched", [])) + "."]
    if peer.get("picture"):
        lines += ["", f"Pictures ({peer['picture_layout']}): `{peer['picture']}`"]
    return "\n".join(lines) + "\n"
