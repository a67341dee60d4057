"""Importers of the seed's scene / renderer / light files (SPEC §4.6)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import weft
from weft.ibl import files

SCENE = """\
# the seed's listing 3.1
MODEL 0 ../data/models/teapot.3ds      ../data/images/
MODEL 1 ../data/models/plane.3ds       ../data/images/
MODEL 2 ../data/models/watch.3ds       ../data/images/

EFFECT 0 CubeLighting
EFFECT 1 ManyShadows
EFFECT 2 ShadowOnly   // trailing comment
"""

RENDERER = "IBLMODEL\t0\t1\t60.0\t100.0\t0.0\t0.0\t0.0\t0.0\t1.0\t1.0\t1.0\n" \
           "IBLMODEL\t6\t0\t0.0\t0.0\t0.0\t0.0\t90.0\t0.0\t1.0\t1.0\t1.0\n"

LIGHTS = """\
PERSPLIGHT 0  0 0 0   10 20 10   45.0 1.0 1.0 100.0
DIRLIGHT 1  0.3 1.0 0.2
DIRLIGHT 2  0 1 0  1.0 0.9 0.8
"""


def write(tmp_path: Path, name: str, text: str) -> str:
    p = tmp_path / name
    p.write_text(text)
    return str(p)


def test_scene_file(tmp_path: Path) -> None:
    scene = files.load_scene(write(tmp_path, "scene.txt", SCENE))
    assert sorted(scene.models) == [0, 1, 2]
    assert scene.models[0].path == "../data/models/teapot.3ds"
    assert scene.models[2].texture_dir == "../data/images/" and scene.models[2].line == 4
    assert [scene.effects[i].name for i in range(3)] == ["CubeLighting", "ManyShadows",
                                                         "ShadowOnly"]


def test_renderer_file_and_references(tmp_path: Path) -> None:
    renderer = files.load_renderer(write(tmp_path, "renderer.txt", RENDERER))
    first, second = renderer.models
    assert (first.model_id, first.effect_id) == (0, 1)
    assert first.position == (60.0, 100.0, 0.0) and first.scale == (1.0, 1.0, 1.0)
    assert second.rotation_radians[1] == pytest.approx(math.pi / 2)
    scene = files.parse_scene(SCENE)
    with pytest.raises(weft.InvalidArgument, match="line 2: unknown model id 6"):
        files.check_references(scene, renderer)
    files.check_references(scene, files.parse_renderer(RENDERER.splitlines()[0]))


def test_light_file(tmp_path: Path) -> None:
    lights = files.load_lights(write(tmp_path, "lights.txt", LIGHTS)).lights
    spot = lights[0]
    assert isinstance(spot, files.PerspLight)
    assert spot.at == (0.0, 0.0, 0.0) and spot.position == (10.0, 20.0, 10.0)
    assert (spot.fov_degrees, spot.aspect, spot.near, spot.far) == (45.0, 1.0, 1.0, 100.0)
    assert isinstance(lights[1], files.DirLight) and lights[1].colour == (1.0, 1.0, 1.0)
    assert lights[2].colour == (1.0, 0.9, 0.8)


@pytest.mark.parametrize("parser, text, message", [
    (files.parse_scene, "MODEL 0 a.3ds\n", r"<scene>:1: MODEL expects"),
    (files.parse_scene, "EFFECT 0 A\nEFFECT zero B\n", r":2: effect id must be an integer"),
    (files.parse_scene, "MODEL 0 a b\nMODEL 0 c d\n", r":2: duplicate model id 0"),
    (files.parse_scene, "\n\nLIGHT 0\n", r":3: unknown keyword 'LIGHT'"),
    (files.parse_renderer, "IBLMODEL 0 1 0 0 0 0 0 0 1 1\n", r":1: IBLMODEL expects"),
    (files.parse_renderer, "IBLMODEL 0 1 0 nan 0 0 0 0 1 1 1\n", r":1: position.y must be finite"),
    (files.parse_renderer, "IBLMODEL 0 1 0 0 0 0 0 0 1 0 1\n", r":1: scale components"),
    (files.parse_lights, "PERSPLIGHT 0 0 0 0 1 1 1 190 1 1 10\n", r":1: fov must be in"),
    (files.parse_lights, "PERSPLIGHT 0 0 0 0 1 1 1 45 1 10 1\n", r":1: need 0 < near < far"),
    (files.parse_lights, "DIRLIGHT 0 0 0 0\n", r":1: direction must be non-zero"),
    (files.parse_lights, "DIRLIGHT 0 0 1 0\nDIRLIGHT 0 1 0 0\n", r":2: duplicate light id 0"),
    (files.parse_lights, "DIRLIGHT 0 0 1\n", r":1: DIRLIGHT expects"),
])
def test_malformed_lines_name_file_and_line(parser, text: str, message: str) -> None:
    with pytest.raises(weft.IoError, match=message):
        parser(text)


def test_missing_and_binary_files(tmp_path: Path) -> None:
    with pytest.raises(weft.IoError, match="nope.txt"):
        files.load_scene(str(tmp_path / "nope.txt"))
    p = tmp_path / "binary.txt"
    p.write_bytes(b"\xff\xfe\x00MODEL")
    with pytest.raises(weft.IoError, match="not a text file"):
        files.load_scene(str(p))
