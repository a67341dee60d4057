"""The demo's day-night cycle under the analytic sky (weft.ibl.sky, Preetham 1999): the sun light
comes from the sky model (dims and reddens towards sunset, off at night), the scene is lit by the
sky as an environment, and the visible sky changes with the time of day."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import weft
import weft.ibl as ibl

SKY_SCALE = 1.0 / 32.0  # the demo's radiance scale (DemoScene.cpp)


def sun_of(scene):
    return scene.lights[0]  # the sun is the demo's first light, the moon its second


def test_the_sun_light_is_the_sky_models_sun():
    noon, late, night = (weft.demo_scene(hour=h)[0] for h in (12.0, 17.0, 23.0))
    for scene in (noon, late, night):
        assert isinstance(scene.environment, ibl.Environment)  # lit by the analytic sky
        assert scene.ambient == pytest.approx((0.0, 0.0, 0.0))  # ... instead of a constant
    sun = sun_of(late)
    to_sun = -np.asarray(sun.direction, np.float64)
    expected = ibl.sun_light(tuple(to_sun / np.linalg.norm(to_sun)), 3.0, scale=SKY_SCALE)
    np.testing.assert_allclose(np.asarray(sun.color) * sun.intensity,
                               np.asarray(expected.color) * expected.intensity, rtol=0.02)
    a, b = sun_of(noon), sun_of(late)
    assert 0.6 < a.intensity < 1.5  # the seed's sun had intensity ~1 at noon
    assert b.intensity < 0.7 * a.intensity
    assert b.color[2] / b.color[0] < 0.8 * a.color[2] / a.color[0]  # redder late in the day
    assert sun_of(night).intensity == 0.0 and not sun_of(night).cast_shadows
    assert night.lights[1].intensity > 0.0  # the moon


def test_the_sky_environment_follows_the_sun():
    noon = weft.demo_scene(hour=12.0)[0].environment.radiance
    night = weft.demo_scene(hour=23.0)[0].environment.radiance
    up = np.asarray(noon.faces)[2].mean(axis=(0, 1))  # the +Y face: the sky overhead
    assert up[2] > up[0]  # blue
    assert np.asarray(night.faces)[2].mean() < 0.2 * up.mean()


@pytest.mark.parametrize("hour", [12.0, 18.0, 23.0])
def test_demo_renders_the_time_of_day(tmp_path: Path, hour: float):
    out = tmp_path / f"h{hour}.png"
    assert weft.run_demo(width=96, height=54, headless=True, out=str(out), hour=hour) == 0
    image = weft.load_png(str(out))[..., :3].astype(np.float64)
    top = image[:4].reshape(-1, 3).mean(axis=0)  # the sky above the hills
    if hour == 12.0:
        assert image.mean() > 80.0 and top.mean() > 120.0
    elif hour == 18.0:  # the sun is on the horizon ahead: a warm glow
        assert top[0] > top[2]
    else:
        assert image.mean() < 50.0 and top[2] > top[0]  # a dark blue night


def test_bad_time_is_rejected(tmp_path: Path):
    with pytest.raises(weft.InvalidArgument):
        weft.run_demo(width=32, height=32, headless=True, out=str(tmp_path / "x.png"), hour=25.0)
    with pytest.raises(weft.InvalidArgument):
        weft.demo_scene(hour=float("nan"))
    cmd = [sys.executable, "-m", "weft", "demo", "--headless", "--time", "-1", "--out",
           str(tmp_path / "y.png")]
    exe = os.environ.get("WEFT_DEMO_EXE")
    if exe:
        cmd = [exe] + cmd[4:]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    assert proc.returncode != 0 and "time" in proc.stderr.lower(), proc.stderr


def test_python_demo_takes_the_renderers_picture_settings(tmp_path: Path):
    """`python -m weft demo` and run_demo have weft-demo's picture options."""
    dark, bright = tmp_path / "ev0.png", tmp_path / "ev2.png"
    common = dict(width=48, height=27, headless=True, hour=12.0, msaa=1, ambient_occlusion=0,
                  bounce=False, tone_map="neutral")
    assert weft.run_demo(out=str(dark), exposure=0.0, **common) == 0
    assert weft.run_demo(out=str(bright), exposure=2.0, **common) == 0
    a = weft.load_png(str(dark))[..., :3].astype(np.float64)
    b = weft.load_png(str(bright))[..., :3].astype(np.float64)
    assert b.mean() > a.mean() + 30.0  # two stops brighter (tone-mapped)
    with pytest.raises(weft.InvalidArgument):
        weft.run_demo(out=str(dark), tone_map="sepia", **{k: v for k, v in common.items()
                                                          if k != "tone_map"})
    with pytest.raises(weft.InvalidArgument):
        weft.run_demo(out=str(dark), **dict(common, msaa=3))
    usage = subprocess.run([sys.executable, "-m", "weft", "demo", "--help"], capture_output=True,
                           text=True, timeout=60).stdout
    for option in ("--msaa", "--ao", "--no-bounce", "--exposure", "--tone-map"):
        assert option in usage, option
