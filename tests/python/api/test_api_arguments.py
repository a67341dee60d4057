"""Arguments that do not fit a compiled signature (issues 13 and 14): a mistyped keyword, a
negative count or a wrong type raises weft.ArgumentError -- a weft.InvalidArgument that names the
function and the bad keyword or values, not a dump of every pybind11 overload -- and every
compiled callable has an inspect.signature."""

from __future__ import annotations

import inspect
import math

import pytest
import weft
import weft._core as core

#: classes with a constructor (Collider has factories only)
CLASSES = [c for c in vars(core).values()
           if isinstance(c, type) and not issubclass(c, BaseException)
           and c.__module__.startswith("weft") and "__init__(" in (c.__init__.__doc__ or "")]


def test_the_error_is_an_invalid_argument_and_a_type_error():
    assert issubclass(weft.ArgumentError, weft.InvalidArgument)
    assert issubclass(weft.ArgumentError, ValueError)
    assert issubclass(weft.ArgumentError, TypeError)


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_a_mistyped_keyword_is_named(cls):
    with pytest.raises(weft.InvalidArgument) as info:
        cls(no_such_keyword_xyz=1)
    text = str(info.value)
    assert f"weft.{cls.__name__}()" in text and "'no_such_keyword_xyz'" in text
    assert "incompatible" not in text and "following argument types" not in text


def test_the_closest_keyword_is_suggested():
    with pytest.raises(weft.ArgumentError, match=r"'shinyness' \(did you mean 'shininess'\?\)"):
        weft.Material(shinyness=3.0)
    with pytest.raises(weft.ArgumentError, match=r"did you mean 'msaa'"):
        weft.Renderer(8, 8, msa=4)


def test_a_negative_count_names_the_value():
    with pytest.raises(weft.ArgumentError, match=r"weft.generate_hair\(\): the arguments \(-1\).*"
                                                 r"cannot be negative"):
        weft.generate_hair(-1)


def test_a_bad_index_or_shape_is_named():
    """Issue 13's cases: Cloth.pin([-1]) named no index, btf.deviation(s, zeros(5)) raised
    NumPy's IndexError."""
    cloth = weft.Cloth(nx=4, ny=3)
    with pytest.raises(weft.InvalidArgument, match=r"pin: particle index -1 \(entry 1\)"):
        cloth.pin([0, -1])
    with pytest.raises(weft.InvalidArgument,
                       match=r"pin: particle index 12 out of range \[0, 12\)"):
        cloth.pin([12])
    from weft import btf

    samples, _ = btf.synthesize("corduroy", size=4)
    with pytest.raises(weft.InvalidArgument, match=r"shape \(81,\).*got shape \(5,\)"):
        btf.deviation(samples, [0.0] * 5)
    with pytest.raises(weft.InvalidArgument, match="finite"):
        btf.deviation(samples, [math.nan] * 81)
    assert btf.deviation(samples, [0.01] * 81)["total"] == pytest.approx(1.0)


def test_a_wrong_type_names_the_method():
    scene = weft.Scene()
    with pytest.raises(weft.ArgumentError, match=r"weft.Scene.add_mesh\(\): the arguments \(3\)"):
        scene.add_mesh(3)
    with pytest.raises(weft.ArgumentError, match=r"weft.Mesh.plane\(\)"):
        weft.Mesh.plane("wide")


def test_errors_from_inside_still_pass_through():
    """Only pybind11's conversion failures are translated; weft's own errors keep their text."""
    with pytest.raises(weft.InvalidArgument, match="1..65535 pixels") as info:
        weft.Renderer(100000, 100000)
    assert not isinstance(info.value, weft.ArgumentError)


def _compiled_callables():
    out = []
    for name, obj in vars(core).items():
        if getattr(obj, "__weft_wrapped__", False):
            out.append((name, obj))
        elif isinstance(obj, type):
            for attr, value in vars(obj).items():
                fn = value.__func__ if isinstance(value, staticmethod) else value
                if getattr(fn, "__weft_wrapped__", False):
                    out.append((f"{name}.{attr}", fn))
    return out


def test_compiled_callables_have_signatures():
    callables = _compiled_callables()
    assert len(callables) > 150
    generic = [n for n, f in callables
               if [p.kind for p in inspect.signature(f).parameters.values()]
               == [inspect.Parameter.VAR_POSITIONAL, inspect.Parameter.VAR_KEYWORD]]
    # only overloaded functions keep (*args, **kwargs)
    assert len(generic) <= 0.1 * len(callables), generic
    sig = inspect.signature(weft.generate_hair)
    assert list(sig.parameters)[:2] == ["strands", "points"]
    assert sig.parameters["strands"].default == 1000
    assert math.isclose(sig.parameters["curl_radius"].default, 0.01)  # not 0.00999999977...
    assert str(sig.parameters["strands"].annotation) == "int"
    assert list(inspect.signature(weft.Renderer.render).parameters) == ["self", "scene", "camera"]


def _sweep_cases():
    """Every keyword of every constructor with a value no parameter may take: NaN, +-inf and
    -1e30 for floats; -1 and 2**40 for ints (counts and sizes)."""
    cases = []
    for cls in CLASSES:
        try:
            params = list(inspect.signature(cls.__init__).parameters.values())[1:]
        except (TypeError, ValueError):
            continue
        if any(p.default is inspect.Parameter.empty for p in params):
            continue  # needs arguments this sweep cannot invent
        for p in params:
            ann = str(p.annotation)
            values = {"float": (math.nan, math.inf, -math.inf, -1e30),
                      "int": (-1, 2 ** 40)}.get(ann, ())
            cases += [(cls, p.name, v) for v in values]
    return cases


SWEEP = _sweep_cases()


def test_the_sweep_covers_the_constructors():
    assert len(SWEEP) > 40 and len({c for c, _, _ in SWEEP}) >= 5


@pytest.mark.parametrize("cls,name,value", SWEEP,
                         ids=[f"{c.__name__}.{n}={v}" for c, n, v in SWEEP])
def test_impossible_values_are_refused(cls, name, value):
    """weft.InvalidArgument (ArgumentError included), never acceptance or another error."""
    with pytest.raises(weft.InvalidArgument):
        cls(**{name: value})
