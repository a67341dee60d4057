"""Method-level argument sweep (issue 13): every compiled function, method and property setter of
the Python API whose numeric parameters can be read from its signature is called with NaN, +-inf,
+-1e30, negative and huge integers, and values of the wrong type. Each call must either raise a
weft error (weft.InvalidArgument / weft.IoError) or be accepted -- and then leave no NaN or inf
in its result or in the object it was called on. A crash ends the run, a hang trips the alarm.

The cases are generated from inspect.signature (weft._arguments gives every compiled callable
one), not listed by hand; only the fillers for parameters that are not swept are chosen here."""

from __future__ import annotations

import inspect
import math
import signal

import numpy as np
import pytest
import weft
import weft._core as core

BAD = {
    "float": (math.nan, math.inf, -math.inf, -1e30, 1e30, "x", None),
    "int": (-1, -2 ** 31, 2 ** 31 - 1, 2 ** 40, 1.5, "x", None),
}
#: not swept: they write files, start windows or long runs, or change process-wide settings
SKIP = {"run_demo", "set_shader_directory", "btf_write", "save_png", "save_exr", "save_hdr",
        "save_hair", "Renderer.render_to_file", "Renderer.screenshot", "clear_validation_messages"}
SECONDS = 30


def _cube(size=4):
    return core.CubeMap(np.ones((6, size, size, 3), np.float32))


FACTORIES = {
    "Mesh": lambda: core.Mesh.plane(1.0, 1.0, 2, 2),
    "Texture": lambda: core.Texture(np.full((4, 4, 4), 128, np.uint8)),
    "Renderer": lambda: core.Renderer(16, 16, shadow_map_size=64, msaa=1),
    "Cloth": lambda: core.Cloth(4, 4),
    "HairStrands": lambda: weft.generate_hair(3, 4),
    "BtfSamples": lambda: weft.btf.synthesize("wool", 4)[0],
    "SkyModel": lambda: core.SkyModel((0.0, 1.0, 0.3)),
    "CubeMap": _cube,
    "ShadowDome": lambda: core.ShadowDome(_cube(8), 8),
    "Environment": lambda: core.Environment(_cube(8)),
}


def _instance(cls_name):
    if cls_name in FACTORIES:
        return FACTORIES[cls_name]()
    return getattr(core, cls_name)()


def _filler(annotation):
    """A valid value for a parameter that is not swept, or None when none can be invented."""
    a = str(annotation)
    if a == "int":
        return 2
    if a == "float":
        return 0.5
    if a == "bool":
        return False
    if a.startswith("weft.") and "|" not in a and a[5:] in vars(core):
        try:
            return _instance(a[5:])
        except Exception:  # noqa: BLE001 (no default instance: the method is not swept)
            return None
    return None


def _finite(value, seen=0) -> bool:
    if isinstance(value, (float, np.floating)):
        return math.isfinite(value)
    if isinstance(value, np.ndarray) and value.dtype.kind == "f":
        return bool(np.all(np.isfinite(value)))
    if isinstance(value, (tuple, list)) and seen < 2:
        return all(_finite(v, seen + 1) for v in value)
    return True


def _state_is_finite(obj) -> bool:
    """Every readable float / vector / array property of `obj` is finite."""
    for name, attr in vars(type(obj)).items():
        if isinstance(attr, property) and not name.startswith("_"):
            try:
                value = getattr(obj, name)
            except weft.Error:
                continue
            if not _finite(value):
                return False
    return True


def _method_cases():
    cases = []
    for name, fn in _compiled_callables():
        if name in SKIP or name.split(".")[-1] in SKIP or name.split(".")[-1].startswith("_"):
            continue
        try:
            params = list(inspect.signature(fn).parameters.values())
        except (TypeError, ValueError):
            continue
        owner = name.split(".")[0] if "." in name else None
        if owner and params and params[0].name == "self":
            params = params[1:]
        elif owner:
            owner = None  # a static factory: called on the class
        required = [p for p in params if p.default is inspect.Parameter.empty]
        if any(p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD) for p in params):
            continue
        if any(_filler(p.annotation) is None for p in required):
            continue
        for p in params:
            for bad in BAD.get(str(p.annotation), ()):
                cases.append((name, owner, p.name, bad))
    return cases


def _compiled_callables():
    out = []
    for name, obj in vars(core).items():
        if name.startswith("_"):
            continue  # private helpers (the cloth peer solver for benchmarks)
        if getattr(obj, "__weft_wrapped__", False):
            out.append((name, obj))
        elif isinstance(obj, type):
            for attr, value in vars(obj).items():
                fn = value.__func__ if isinstance(value, staticmethod) else value
                if getattr(fn, "__weft_wrapped__", False) and attr != "__init__":
                    out.append((f"{name}.{attr}", fn))
    return out


METHOD_CASES = _method_cases()


def _property_cases():
    cases = []
    for cls_name, cls in sorted(vars(core).items()):
        if not isinstance(cls, type) or issubclass(cls, BaseException) or cls_name[0] == "_":
            continue
        for attr, prop in sorted(vars(cls).items()):
            if not (isinstance(prop, property) and prop.fset) or attr.startswith("_"):
                continue
            try:
                value = getattr(_instance(cls_name), attr)
            except Exception:  # noqa: BLE001 (no default instance to read the type from)
                continue
            if isinstance(value, bool):
                kinds = ("x",)
            elif isinstance(value, int):
                kinds = BAD["int"]
            elif isinstance(value, float):
                kinds = BAD["float"]
            elif isinstance(value, tuple) and len(value) in (2, 3, 4):
                n = len(value)
                kinds = tuple(tuple([v] + [0.5] * (n - 1)) for v in (math.nan, math.inf, -1e30)) + (
                    "x", (0.5,) * (n + 1))
            else:
                continue
            cases += [(cls_name, attr, bad) for bad in kinds]
    return cases


PROPERTY_CASES = _property_cases()


@pytest.fixture(autouse=True)
def _alarm():
    def hang(*_):
        raise TimeoutError(f"call did not return within {SECONDS} s")
    old = signal.signal(signal.SIGALRM, hang)
    signal.alarm(SECONDS)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, old)


def test_the_sweep_reaches_most_of_the_api():
    names = {c[0] for c in METHOD_CASES}
    assert len(names) >= 30, sorted(names)
    assert len(METHOD_CASES) >= 400
    assert len({c[0] for c in PROPERTY_CASES}) >= 8 and len(PROPERTY_CASES) >= 300


def _accepted_or_refused(call, obj=None):
    try:
        result = call()
    except weft.Error:
        return
    assert _finite(result), f"accepted, but the result holds NaN/inf: {result!r}"[:300]
    if obj is not None:
        assert _state_is_finite(obj), "accepted, but the object now holds NaN/inf"


@pytest.mark.parametrize("name,owner,param,bad", METHOD_CASES,
                         ids=[f"{n}:{p}={b!r}" for n, _, p, b in METHOD_CASES])
def test_method_refuses_or_survives(name, owner, param, bad):
    fn = getattr(core, name) if "." not in name else getattr(getattr(core, name.split(".")[0]),
                                                             name.split(".")[1])
    params = list(inspect.signature(fn).parameters.values())
    obj = _instance(owner) if owner else None
    if owner:
        params = params[1:]
    kwargs = {p.name: _filler(p.annotation) for p in params
              if p.default is inspect.Parameter.empty and p.name != param}
    kwargs[param] = bad
    call = (lambda: getattr(obj, name.split(".")[1])(**kwargs)) if owner else (lambda: fn(**kwargs))
    _accepted_or_refused(call, obj)


@pytest.mark.parametrize("cls_name,attr,bad", PROPERTY_CASES,
                         ids=[f"{c}.{a}={b!r}" for c, a, b in PROPERTY_CASES])
def test_setter_refuses_or_survives(cls_name, attr, bad):
    obj = _instance(cls_name)
    _accepted_or_refused(lambda: setattr(obj, attr, bad), obj)


def test_a_setter_given_the_wrong_type_names_the_property():
    cloth = core.Cloth(4, 4)
    with pytest.raises(weft.ArgumentError, match=r"weft.Cloth.iterations cannot be set to 'x' "
                                                 r"\(expects int\)"):
        cloth.iterations = "x"
    renderer = FACTORIES["Renderer"]()
    with pytest.raises(weft.ArgumentError, match="probe_size cannot be set to -1.*negative"):
        renderer.probe_size = -1
    assert cloth.iterations == 1  # unchanged
