"""Importers for the seed's text formats (SPEC §4.6, seed 001 §3.1): one keyword per line,
fields separated by white space, blank lines and ``#`` / ``//`` comments ignored.

- scene file: ``MODEL id path texdir`` and ``EFFECT id name``;
- renderer file: ``IBLMODEL modelId effectId px py pz rx ry rz sx sy sz`` (rotation as written in
  the file; the seed's are degrees);
- light file: ``PERSPLIGHT id atx aty atz posx posy posz fov aspect near far`` (fov in degrees,
  (0, 180]) and ``DIRLIGHT id dx dy dz [r g b]`` (the seed names DIRLIGHT without its fields; weft
  reads a direction towards the light and an optional colour, default white).

Malformed lines raise :class:`weft.IoError` with ``file:line:``; renderer entries that name a
model or effect the scene lacks raise :class:`weft.InvalidArgument` in :func:`check_references`.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Sequence, Tuple

from weft._core import InvalidArgument, IoError

Vec3 = Tuple[float, float, float]


@dataclass(frozen=True)
class ModelEntry:
    id: int
    path: str
    texture_dir: str
    line: int = 0


@dataclass(frozen=True)
class EffectEntry:
    id: int
    name: str
    line: int = 0


@dataclass
class SceneFile:
    models: Dict[int, ModelEntry] = field(default_factory=dict)
    effects: Dict[int, EffectEntry] = field(default_factory=dict)


@dataclass(frozen=True)
class IblModel:
    model_id: int
    effect_id: int
    position: Vec3
    rotation: Vec3
    scale: Vec3
    line: int = 0

    @property
    def rotation_radians(self) -> Vec3:
        """``rotation`` read as degrees (the seed's unit), in radians."""
        return tuple(math.radians(v) for v in self.rotation)  # type: ignore[return-value]


@dataclass
class RendererFile:
    models: List[IblModel] = field(default_factory=list)


@dataclass(frozen=True)
class DirLight:
    id: int
    direction: Vec3
    colour: Vec3 = (1.0, 1.0, 1.0)
    line: int = 0


@dataclass(frozen=True)
class PerspLight:
    id: int
    at: Vec3
    position: Vec3
    fov_degrees: float
    aspect: float
    near: float
    far: float
    line: int = 0


@dataclass
class LightFile:
    lights: Dict[int, object] = field(default_factory=dict)


class _Line:
    def __init__(self, name: str, number: int, fields: Sequence[str]) -> None:
        self.name, self.number, self.fields = name, number, list(fields)

    def fail(self, message: str) -> IoError:
        return IoError(f"{self.name}:{self.number}: {message}")

    def expect(self, counts: Sequence[int], usage: str) -> None:
        if len(self.fields) - 1 not in counts:
            raise self.fail(f"{self.fields[0]} expects {usage}, got {len(self.fields) - 1} fields")

    def int(self, k: int, what: str) -> int:
        try:
            return int(self.fields[k])
        except ValueError:
            raise self.fail(f"{what} must be an integer, got {self.fields[k]!r}") from None

    def float(self, k: int, what: str) -> float:
        try:
            v = float(self.fields[k])
        except ValueError:
            raise self.fail(f"{what} must be a number, got {self.fields[k]!r}") from None
        if not math.isfinite(v):
            raise self.fail(f"{what} must be finite, got {self.fields[k]!r}")
        return v

    def vec3(self, k: int, what: str) -> Vec3:
        return (self.float(k, what + ".x"), self.float(k + 1, what + ".y"),
                self.float(k + 2, what + ".z"))


def _lines(text: str, name: str):
    for number, raw in enumerate(text.splitlines(), start=1):
        body = raw.split("#", 1)[0].split("//", 1)[0].strip()
        if body:
            yield _Line(name, number, body.split())


def _read(path: str) -> str:
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except UnicodeDecodeError:
        raise IoError(f"{path}: not a text file") from None
    except OSError as exc:
        raise IoError(f"{path}: {exc.strerror or exc}") from None


def _unique(table: Dict[int, object], key: int, line: _Line, what: str) -> None:
    if key in table:
        raise line.fail(f"duplicate {what} id {key}")


def parse_scene(text: str, name: str = "<scene>") -> SceneFile:
    """Parses scene-file text (MODEL / EFFECT lines)."""
    scene = SceneFile()
    for line in _lines(text, name):
        key = line.fields[0]
        if key == "MODEL":
            line.expect([3], "'id path texdir'")
            mid = line.int(1, "model id")
            _unique(scene.models, mid, line, "model")
            scene.models[mid] = ModelEntry(mid, line.fields[2], line.fields[3], line.number)
        elif key == "EFFECT":
            line.expect([2], "'id name'")
            eid = line.int(1, "effect id")
            _unique(scene.effects, eid, line, "effect")
            scene.effects[eid] = EffectEntry(eid, line.fields[2], line.number)
        else:
            raise line.fail(f"unknown keyword {key!r} (expected MODEL or EFFECT)")
    return scene


def parse_renderer(text: str, name: str = "<renderer>") -> RendererFile:
    """Parses renderer-file text (IBLMODEL lines)."""
    out = RendererFile()
    for line in _lines(text, name):
        if line.fields[0] != "IBLMODEL":
            raise line.fail(f"unknown keyword {line.fields[0]!r} (expected IBLMODEL)")
        line.expect([11], "'modelId effectId px py pz rx ry rz sx sy sz'")
        scale = line.vec3(9, "scale")
        if any(v == 0.0 for v in scale):
            raise line.fail("scale components must be non-zero")
        out.models.append(IblModel(line.int(1, "model id"), line.int(2, "effect id"),
                                   line.vec3(3, "position"), line.vec3(6, "rotation"), scale,
                                   line.number))
    return out


def parse_lights(text: str, name: str = "<lights>") -> LightFile:
    """Parses light-file text (DIRLIGHT / PERSPLIGHT lines)."""
    out = LightFile()
    for line in _lines(text, name):
        key = line.fields[0]
        if key == "DIRLIGHT":
            line.expect([4, 7], "'id dx dy dz [r g b]'")
            lid = line.int(1, "light id")
            d = line.vec3(2, "direction")
            if d == (0.0, 0.0, 0.0):
                raise line.fail("direction must be non-zero")
            colour = line.vec3(5, "colour") if len(line.fields) == 8 else (1.0, 1.0, 1.0)
            if min(colour) < 0.0:
                raise line.fail("colour must be >= 0")
            light: object = DirLight(lid, d, colour, line.number)
        elif key == "PERSPLIGHT":
            line.expect([11], "'id atx aty atz posx posy posz fov aspect near far'")
            lid = line.int(1, "light id")
            at, pos = line.vec3(2, "at"), line.vec3(5, "position")
            fov, aspect = line.float(8, "fov"), line.float(9, "aspect")
            near, far = line.float(10, "near"), line.float(11, "far")
            if not 0.0 < fov <= 180.0:
                raise line.fail(f"fov must be in (0, 180] degrees, got {fov}")
            if aspect <= 0.0:
                raise line.fail(f"aspect must be > 0, got {aspect}")
            if not 0.0 < near < far:
                raise line.fail(f"need 0 < near < far, got near={near}, far={far}")
            if at == pos:
                raise line.fail("at and position must differ")
            light = PerspLight(lid, at, pos, fov, aspect, near, far, line.number)
        else:
            raise line.fail(f"unknown keyword {key!r} (expected DIRLIGHT or PERSPLIGHT)")
        _unique(out.lights, lid, line, "light")
        out.lights[lid] = light
    return out


def _load(parser: Callable[[str, str], object], path: str):
    return parser(_read(path), os.fspath(path))


def load_scene(path: str) -> SceneFile:
    """Reads a scene file (see :func:`parse_scene`)."""
    return _load(parse_scene, path)


def load_renderer(path: str) -> RendererFile:
    """Reads a renderer file (see :func:`parse_renderer`)."""
    return _load(parse_renderer, path)


def load_lights(path: str) -> LightFile:
    """Reads a light file (see :func:`parse_lights`)."""
    return _load(parse_lights, path)


def check_references(scene: SceneFile, renderer: RendererFile) -> None:
    """Raises InvalidArgument when a renderer entry names a model or effect the scene lacks."""
    for m in renderer.models:
        if m.model_id not in scene.models:
            raise InvalidArgument(f"renderer line {m.line}: unknown model id {m.model_id}")
        if m.effect_id not in scene.effects:
            raise InvalidArgument(f"renderer line {m.line}: unknown effect id {m.effect_id}")
