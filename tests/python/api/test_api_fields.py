"""One declaration per bound field (issue 15): a value type's constructor takes exactly its
settable properties as keywords, and each keyword's default is what a default-made object holds
(the bindings read the defaults from the C++ structs instead of repeating them)."""

from __future__ import annotations

import inspect

import pytest
import weft

VALUE_TYPES = [weft.Material, weft.DirectionalLight, weft.PointLight, weft.SpotLight,
               weft.Camera, weft.Wind, weft.HairMaterial]


def _settable(cls: type) -> set:
    return {name for name, value in vars(cls).items()
            if isinstance(value, property) and value.fset is not None}


def _same(a: object, b: object) -> bool:
    if isinstance(a, tuple) or isinstance(b, tuple):
        return len(a) == len(b) and all(x == pytest.approx(y) for x, y in zip(a, b))
    return a == pytest.approx(b) if isinstance(a, float) else a == b


@pytest.mark.parametrize("cls", VALUE_TYPES, ids=lambda c: c.__name__)
def test_keywords_are_the_properties_and_defaults_what_an_object_holds(cls):
    params = inspect.signature(cls).parameters
    assert set(params) == _settable(cls)
    made = cls()
    for name, p in params.items():
        assert _same(getattr(made, name), p.default), name


@pytest.mark.parametrize("make,owner", [
    (lambda: weft.Cloth(), weft.Cloth),
    (lambda: weft.Renderer(8, 8), weft.Renderer),
], ids=["Cloth", "Renderer"])
def test_owner_settings_default_to_what_the_owner_holds(make, owner):
    """Every constructor keyword that is also a property reads back as its default."""
    params = inspect.signature(owner).parameters
    made = make()
    shared = set(params) & _settable(owner)
    assert len(shared) >= 14
    for name in shared:
        assert _same(getattr(made, name), params[name].default), name


def test_a_refused_keyword_value_leaves_no_half_made_object():
    with pytest.raises(weft.InvalidArgument, match="inner"):
        weft.SpotLight(inner_angle=0.6, outer_angle=0.5)
    light = weft.SpotLight(inner_angle=0.6, outer_angle=0.7)  # validated as a whole, any order
    assert light.inner_angle == pytest.approx(0.6)
    with pytest.raises(weft.InvalidArgument):
        light.outer_angle = 0.55
    assert light.outer_angle == pytest.approx(0.7)
