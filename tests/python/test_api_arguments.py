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
