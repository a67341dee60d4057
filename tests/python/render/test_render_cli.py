"""``python -m weft render`` with --scene cloth and --environment (issue 6): a script lights the
cloth scene from a mirror-ball image with shadows from the dome. The CLI's PNG is compared with
the same scene rendered through the API (weft.scenes), and the dome's shadows are measured on the
ground: darker next to the sphere and cloth than on open ground with a dome, uniform without.
Bounce light is off here (--no-bounce): it is measured against the path tracer
(test_picture_reference.py), and these checks are about the dome alone."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from typing import List

import numpy as np
import pytest
import weft
import weft.ibl
import weft.scenes
from ibl_envs import mirror_ball_directions, sky_gradient, sun_disc, to_faces
from weft.__main__ import _CLOTH_STEPS, main
from weft.reference import ibl as ref_ibl

TIMEOUT_S = 300
W, H = 160, 120
LUMA = np.array([0.2126, 0.7152, 0.0722])


def run(args: List[str]) -> subprocess.CompletedProcess:
    env = dict(os.environ, WEFT_VALIDATION="1")
    proc = subprocess.run([sys.executable, *args], capture_output=True, text=True,
                          timeout=TIMEOUT_S, env=env)
    assert proc.returncode == 0, \
        f"{args} exited {proc.returncode}\n--- stdout\n{proc.stdout}\n--- stderr\n{proc.stderr}"
    for marker in ("VUID-", "Validation Error"):
        assert marker not in proc.stdout + proc.stderr, f"validation message:\n{proc.stderr}"
    return proc


@pytest.fixture(scope="module")
def sky(tmp_path_factory) -> Path:
    """A sphere-map PNG: bright sky from above (brightest at the zenith), dark ground below."""
    d = mirror_ball_directions(64)
    up = d[..., 1:2]
    radiance = np.where(up > 0.0, np.array([0.9, 0.95, 1.0]) * (0.6 + 0.4 * up),
                        np.array([0.03, 0.025, 0.02]))
    path = tmp_path_factory.mktemp("env") / "sky.png"
    weft.ibl.save_environment(str(path), radiance.astype(np.float32))
    return path


def ground_rings(debug: dict, image: np.ndarray) -> tuple:
    """Mean luminance (linear) of the PNG's ground pixels next to the sphere's foot (0.5 to 0.7 m
    from its axis: under the draped cloth's skirt, seen past it) and of open ground (> 2 m)."""
    ground = debug["instance"] == 0
    p = debug["position"]
    r = np.hypot(p[..., 0], p[..., 2])
    lum = weft.ibl.srgb_to_linear(image[..., :3]) @ LUMA
    near, far = ground & (r > 0.5) & (r < 0.7), ground & (r > 2.0)
    assert near.sum() > 100 and far.sum() > 100, (near.sum(), far.sum())
    return float(lum[near].mean()), float(lum[far].mean())


def api_render(sky: Path, dome: int) -> tuple:
    """The CLI's scene, built through the API: debug outputs and the sRGB image."""
    scene, camera, _ = weft.scenes.cloth_scene(steps=weft.scenes.DEFAULT_STEPS)
    cube = weft.ibl.load_environment_cube(str(sky), 256, source="sphere")
    weft.scenes.light_with_environment(scene, cube, dome_lights=dome)
    renderer = weft.Renderer(W, H, bounce=False)
    debug = renderer.render_debug(scene, camera)  # one surface per pixel (no MSAA)
    return debug, renderer.render(scene, camera)  # the CLI's defaults


def test_cloth_scene_lit_by_a_mirror_ball_with_dome_shadows(sky: Path, tmp_path: Path) -> None:
    out = tmp_path / "cloth.png"
    proc = run(["-m", "weft", "render", "--scene", "cloth", "--environment", str(sky),
                "--source", "sphere", "--wrap", "1", "--dome", "16", "--no-bounce",
                "--width", str(W), "--height", str(H), "--out", str(out)])
    assert out.is_file() and out.name in proc.stdout and "environment" in proc.stdout
    assert "dome[15]" in proc.stdout and "dome[16]" not in proc.stdout  # 16 dome shadow maps
    image = weft.load_png(str(out))
    assert image.shape == (H, W, 4)
    lum = weft.ibl.srgb_to_linear(image[..., :3]) @ LUMA
    assert lum.std() > 0.05, lum.std()  # not a uniform image
    # the CLI drew exactly the scene weft.scenes builds (same simulation, lighting and dome)
    debug, colour = api_render(sky, 16)
    diff = np.abs(colour.astype(int) - image.astype(int))
    assert np.mean(diff > 1) < 0.002, np.mean(diff > 1)
    # every part of the scene is in view: ground, sphere (below the cloth's edge) and cloth
    for instance in (0, 1, 2):
        assert (debug["instance"] == instance).sum() > 50, instance
    # shadows from the dome: the sphere and the cloth hide much of the bright sky from the
    # ground at their foot (measured 0.64 of the open ground's luminance)
    near, far = ground_rings(debug, image)
    assert near < 0.8 * far, (near, far)
    assert near > 0.3 * far, (near, far)  # the dome subtracts occluded lights, not everything
    # the cloth's top faces the bright zenith: brighter than the ground under the dark horizon
    top = (debug["instance"] == 2) & (debug["normal"][..., 1] > 0.9)
    assert top.sum() > 20 and lum[top].mean() > lum[debug["instance"] == 0].mean()


def test_without_the_dome_the_ground_is_uniform(sky: Path, tmp_path: Path, capsys) -> None:
    out = tmp_path / "nodome.png"
    assert main(["render", "--scene", "cloth", "--environment", str(sky), "--dome", "0",
                 "--no-bounce", "--width", str(W), "--height", str(H), "--out", str(out)]) == 0
    assert "dome[" not in capsys.readouterr().out
    image = weft.load_png(str(out))
    debug, colour = api_render(sky, 0)
    assert np.mean(np.abs(colour.astype(int) - image.astype(int)) > 1) < 0.002
    # a flat ground under SH9 irradiance only: the same light next to the sphere and far off,
    # so the darkening of the dome test comes from the dome's shadows
    near, far = ground_rings(debug, image)
    assert abs(near - far) < 0.01 * far, (near, far)


def test_default_scene_with_an_equirect_npy_environment(tmp_path: Path, capsys) -> None:
    # 2:1 -> equirect (auto); the default scene keeps its meshes, loses its sun
    h = 32
    theta = (np.arange(h) + 0.5) / h * np.pi  # from the zenith
    column = np.where(np.cos(theta)[:, None] > 0, [1.0, 0.9, 0.8], [0.05, 0.05, 0.05])
    env = np.repeat(column[:, None, :], 2 * h, axis=1).astype(np.float32)
    path = tmp_path / "env.npy"
    np.save(path, env)
    out = tmp_path / "default.png"
    assert main(["render", "--environment", str(path), "--width", "64", "--height", "48",
                 "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "default, environment" in text and "dome[15]" in text  # --dome defaults to 16
    image = weft.load_png(str(out))
    assert image.shape == (48, 64, 4) and image[..., :3].std() > 5


def test_default_render_is_unchanged(tmp_path: Path) -> None:
    # no new option given: weft.default_scene() with its sun, as before
    out = tmp_path / "plain.png"
    assert main(["render", "--width", "64", "--height", "48", "--out", str(out)]) == 0
    scene, camera = weft.default_scene()
    expected = weft.Renderer(64, 48).render(scene, camera)
    assert np.mean(np.abs(expected.astype(int) - weft.load_png(str(out)).astype(int)) > 1) < 0.002


def test_cloth_scene_drapes_over_the_sphere() -> None:
    assert _CLOTH_STEPS == weft.scenes.DEFAULT_STEPS
    _, _, flat = weft.scenes.cloth_scene(steps=0)
    assert np.ptp(np.asarray(flat.positions)[:, 1]) == 0.0
    _, _, cloth = weft.scenes.cloth_scene()
    p = np.asarray(cloth.positions, np.float64)
    centre = np.array(weft.scenes.SPHERE_CENTRE)
    assert np.linalg.norm(p - centre, axis=1).min() > 0.99 * weft.scenes.SPHERE_RADIUS
    assert p[:, 1].max() < centre[1] + 0.6 and p[:, 1].min() < centre[1]  # on it, hanging down
    assert p[:, 1].min() > -0.01  # not through the ground
    assert cloth.stats()["max_strain"] < 0.25


@pytest.mark.parametrize("argv, message", [
    (["--dome", "16"], "--dome needs --environment FILE"),
    (["--source", "sphere", "--wrap", "0.9"], "--source and --wrap need --environment FILE"),
    (["--steps", "10"], "--steps applies to --scene cloth"),
    (["--sun-lights", "1"], "--sun-lights needs --environment FILE"),
    (["--background", "{tmp}/missing.png"], "missing.png"),
    (["--environment", "{tmp}/missing.png"], "no such file"),
    (["--environment", "{tmp}/odd.png"], "cannot tell the kind"),
    (["--environment", "{tmp}/notes.txt"], "unsupported environment format"),
])
def test_bad_options_give_clear_errors(tmp_path: Path, capsys, argv, message) -> None:
    weft.save_png(str(tmp_path / "odd.png"), np.full((3, 5, 3), 128, np.uint8))
    (tmp_path / "notes.txt").write_text("not an image")
    out = tmp_path / "never.png"
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    assert main(["render", "--out", str(out), "--width", "32", "--height", "24", *argv]) == 1
    err = capsys.readouterr().err
    assert err.startswith("weft: error:") and message in err, err
    assert not out.exists()


@pytest.mark.parametrize("argv, message", [
    (["--dome", "12"], "multiple of 8"), (["--dome", "72"], "multiple of 8"),
    (["--wrap", "0"], "(0, 1]"), (["--wrap", "1.5"], "(0, 1]"),
    (["--scene", "garden"], "invalid choice"), (["--source", "cubemap"], "invalid choice"),
])
def test_bad_option_values_are_usage_errors(capsys, argv, message) -> None:
    with pytest.raises(SystemExit) as exc:
        main(["render", *argv])
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


def test_scene_api_rejects_bad_arguments(sky: Path) -> None:
    with pytest.raises(weft.InvalidArgument, match="resolution"):
        weft.scenes.cloth_scene(resolution=2)
    with pytest.raises(weft.InvalidArgument, match="steps"):
        weft.scenes.cloth_scene(steps=-1)
    with pytest.raises(weft.InvalidArgument, match="cloth_colour"):
        weft.scenes.cloth_scene(cloth_colour=(1.0, float("nan"), 0.0))
    scene, _, _ = weft.scenes.cloth_scene(steps=0)
    cube = weft.ibl.load_environment_cube(str(sky), 8)
    with pytest.raises(weft.InvalidArgument, match="multiple of 8"):
        weft.scenes.light_with_environment(scene, cube, dome_lights=12)
    with pytest.raises(weft.InvalidArgument, match="Environment or a weft.ibl.CubeMap"):
        weft.scenes.light_with_environment(scene, np.zeros((6, 8, 8, 3), np.float32))
    with pytest.raises(weft.InvalidArgument, match="wrap"):
        weft.ibl.load_environment_cube(str(sky), 8, wrap=0.0)
    with pytest.raises(weft.InvalidArgument, match="source"):
        weft.ibl.load_environment_cube(str(sky), 8, source="panorama")


def test_environment_files_of_every_kind_load_as_the_same_cube(tmp_path: Path) -> None:
    # one smooth environment written as raw faces, a cube cross and an equirect panorama (float
    # files), each read back by load_environment_cube with source="auto"; the equirect goes
    # through two resamplings (measured mean error 0.0009; the others are exact)
    d = weft.ibl.cube_texel_directions(16).reshape(-1, 3)
    faces = (0.2 + 0.8 * np.clip(d[:, 1:2], 0, 1) * np.array([1.0, 0.9, 0.7])
             + 0.1 * (d[:, :1] + 1)).reshape(6, 16, 16, 3).astype(np.float32)
    cube = weft.ibl.CubeMap(faces)
    np.save(tmp_path / "faces.npy", faces)
    weft.ibl.save_environment(str(tmp_path / "cross.exr"), weft.ibl.cube_to_cross(cube))
    weft.ibl.save_environment(str(tmp_path / "pano.exr"),
                              weft.ibl.cube_to_equirect(cube, 128, 64))
    for name, tol in (("faces.npy", 1e-6), ("cross.exr", 1e-5), ("pano.exr", 0.004)):
        got = np.asarray(weft.ibl.load_environment_cube(str(tmp_path / name), 16).faces)
        assert np.abs(got - faces).mean() < tol, (name, np.abs(got - faces).mean())
    assert weft.ibl.load_environment_cube(str(tmp_path / "faces.npy"), 8).size == 8  # resampled
    assert [weft.ibl.guess_source(w, h) for w, h in ((64, 32), (64, 48), (48, 64), (32, 32))] \
        == ["equirect", "cross", "cross", "sphere"]


def test_cloth_composited_over_a_camera_image(sky: Path, tmp_path: Path) -> None:
    """--background: the ground becomes a phantom over the image (AR, SPEC §4.5): open ground
    shows the image unchanged, the ground at the sphere's foot the image darkened by the dome's
    shadows, and the cloth and sphere are drawn as usual."""
    y, x = np.mgrid[0:H, 0:W]
    photo = np.zeros((H, W, 3), np.uint8)
    photo[..., 0] = 60 + 150 * x // (W - 1)
    photo[..., 1] = 80 + 120 * y // (H - 1)
    photo[..., 2] = 120
    bg = tmp_path / "photo.png"
    weft.save_png(str(bg), photo)
    out = tmp_path / "ar.png"
    assert main(["render", "--scene", "cloth", "--environment", str(sky), "--dome", "16",
                 "--background", str(bg), "--width", str(W), "--height", str(H),
                 "--out", str(out)]) == 0
    image = weft.load_png(str(out))[..., :3].astype(int)
    debug, _ = api_render(sky, 16)
    ground = debug["instance"] == 0
    r = np.hypot(debug["position"][..., 0], debug["position"][..., 2])
    # away from silhouettes: MSAA blends edge pixels with what lies beyond them
    inner = ground.copy()
    for axis in (0, 1):
        for shift in (1, -1):
            inner &= np.roll(ground, shift, axis=axis)
    far, near = inner & (r > 2.0), inner & (r > 0.5) & (r < 0.7)
    # the image passes through exactly where nothing shadows the phantom (sRGB decode and
    # re-encode: measured exact)
    assert np.abs(image[far] - photo[far]).max() <= 2
    lum = lambda c: weft.ibl.srgb_to_linear(c.astype(np.uint8)) @ LUMA  # noqa: E731
    ratio = lum(image[near]).mean() / lum(photo[near]).mean()
    assert 0.3 < ratio < 0.85, ratio  # measured 0.64
    cloth = debug["instance"] == 2
    assert np.abs(image[cloth] - photo[cloth]).mean() > 10  # the cloth is drawn, not the photo



def test_extracted_sun_lights_exactly_and_casts_a_sharp_shadow() -> None:
    """light_with_environment(sun_lights=1): the planted sun becomes a shadow-casting directional
    light and the environment lights with the rest of the sky. A sphere must then receive the
    exact irradiance of the whole environment (NumPy cosine convolution) at every normal, which
    SH9 of the full environment misses (a sun is not band-limited: it rings on the far side),
    and the sphere's sharp sun shadow appears on the ground."""
    sun_dir = np.array([0.4, 0.8, 0.3]) / np.linalg.norm([0.4, 0.8, 0.3])
    faces = to_faces(sun_disc(sun_dir, np.radians(3.0), 300.0, sky_gradient()), 64, supersample=2)
    camera = weft.Camera(position=(0.0, 6.0, 0.01), target=(0.0, 0.0, 0.0), fov_y=1.2)

    def scene_with(suns: int, ground: bool, dome: int) -> weft.Scene:
        scene = weft.Scene()
        if ground:
            scene.add_mesh(weft.Mesh.plane(20.0, 20.0), weft.Material(kd=(0.8, 0.8, 0.8)))
        m = np.eye(4, dtype=np.float32)
        m[:3, 3] = (0.0, 1.0, 0.0)
        scene.add_mesh(weft.Mesh.uv_sphere(0.5, 64, 32), weft.Material(kd=(0.8, 0.8, 0.8)),
                       transform=m)
        weft.scenes.light_with_environment(scene, weft.ibl.CubeMap(faces), dome_lights=dome,
                                           sun_lights=suns)
        return scene

    renderer = weft.Renderer(96, 96)
    errors = {}
    for suns in (1, 0):
        debug = renderer.render_debug(scene_with(suns, False, 0), camera)
        mask = debug["mask"]
        n = debug["normal"][mask]
        want = 0.8 * ref_ibl.irradiance(faces.astype(np.float64), n) / np.pi
        got = debug["linear"][mask][:, :3]
        errors[suns] = float(np.mean(np.abs(got - want).max(axis=1) / want.max(axis=1)))
    # measured: extracted sun 0.2%, SH9 of sun + sky 2.6% (mean per pixel)
    assert errors[1] < 0.01 and errors[1] < 0.25 * errors[0], errors

    scene = scene_with(1, True, 16)
    assert len(scene.lights) == 1 and scene.lights[0].cast_shadows
    d = -np.asarray(scene.lights[0].direction)
    assert np.degrees(np.arccos(d @ sun_dir / np.linalg.norm(d))) < 1.0
    debug = renderer.render_debug(scene, camera)
    ground, p = debug["instance"] == 0, debug["position"]
    # the sun's shadow of the sphere (centre 1 m up) falls around -sun.xz / sun.y
    c = -np.array([sun_dir[0], sun_dir[2]]) / sun_dir[1]
    r = np.hypot(p[..., 0] - c[0], p[..., 2] - c[1])
    in_shadow = ground & (r < 0.2)
    open_ground = ground & (r > 1.5) & (np.hypot(p[..., 0], p[..., 2]) > 2.5)
    assert in_shadow.sum() > 5 and open_ground.sum() > 100
    lum = debug["linear"][..., :3] @ LUMA
    assert lum[in_shadow].mean() < 0.5 * lum[open_ground].mean()


def test_render_shows_progress_unless_quiet(tmp_path: Path) -> None:
    """The seconds of simulation and the first frame show as a bar on stderr (tqdm) when asked,
    or on a terminal; --quiet leaves only the result lines on stdout."""
    args = ["-m", "weft", "render", "--scene", "cloth", "--steps", "5", "--width", "32",
            "--height", "24", "--msaa", "1", "--ao", "0", "--out", str(tmp_path / "r.png")]
    shown = run(args + ["--progress"])
    assert "simulating the cloth" in shown.stderr and "rendered" in shown.stderr, shown.stderr
    assert "8/8" in shown.stderr, shown.stderr  # scene, 5 steps, renderer, render
    quiet = run(args + ["--quiet"])
    assert quiet.stderr == "" and "wrote" in quiet.stdout, quiet.stderr
