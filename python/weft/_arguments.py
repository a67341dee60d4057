"""Friendlier calls into the compiled module (issues 13 and 14).

pybind11 answers a call whose arguments do not convert -- a mistyped keyword, a negative count
for an unsigned parameter, a string for a number -- with a ``TypeError`` that dumps every
signature of the function. :func:`install` wraps the compiled functions, constructors and
methods so that such a call raises :class:`ArgumentError` (a :class:`weft.InvalidArgument` and
a ``TypeError``) that names the function, the unknown keyword (with the closest known one) or
the values it was given, and the one signature that applies. It also gives every compiled
callable an ``inspect.signature`` parsed from pybind11's docstring, so that help(), IDEs and
``inspect`` see the parameters.
"""

from __future__ import annotations

import ast
import difflib
import functools
import inspect
import re
from typing import Any, Callable, Dict, List, Optional, Tuple

_INCOMPATIBLE = ("incompatible function arguments", "incompatible constructor arguments")
_SIGNATURE_LINE = re.compile(r"^\s*\d+\.\s*(?P<sig>.*)$")


def _split_top_level(text: str) -> List[str]:
    """Splits a parameter list on commas outside brackets and quotes."""
    parts, depth, quote, start = [], 0, "", 0
    for i, ch in enumerate(text):
        if quote:
            if ch == quote and text[i - 1] != "\\":
                quote = ""
        elif ch in "'\"":
            quote = ch
        elif ch in "([{<":
            depth += 1
        elif ch in ")]}>":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(text[start:i].strip())
            start = i + 1
    tail = text[start:].strip()
    if tail:
        parts.append(tail)
    return parts


def _clean_annotation(text: str) -> str:
    """pybind11's annotations as a user writes them: ``int`` for ``typing.SupportsInt |
    typing.SupportsIndex``, ``weft.Mesh`` for ``weft._core.Mesh``."""
    text = re.sub(r"typing\.Supports(Int|Float) \| typing\.SupportsIndex",
                  lambda m: m.group(1).lower(), text)
    return text.replace("typing.", "").replace("weft._core.", "weft.")


def _clean_default(value: Any) -> Any:
    """A float32 default printed with float64 digits (0.009999999776482582) as written (0.01)."""
    if isinstance(value, float):
        short = float(format(value, ".7g"))
        if abs(short - value) <= 1e-7 * max(abs(value), 1e-30):
            return short
    if isinstance(value, tuple):
        return tuple(_clean_default(v) for v in value)
    return value


class _Text:
    """Shown as its text: a default pybind11 printed as something that is not a Python literal,
    or an annotation (so that inspect does not quote it)."""

    def __init__(self, text: str) -> None:
        self.text = text

    def __repr__(self) -> str:
        return self.text


def _parameters(signature: str) -> Optional[Tuple[List[inspect.Parameter], Optional[str]]]:
    """Parameters and return annotation of one pybind11 signature ``name(a: T = d, ...) -> R``."""
    match = re.match(r"^[\w.]*\((?P<params>.*)\)(?:\s*->\s*(?P<ret>.+))?$", signature.strip())
    if not match:
        return None
    params: List[inspect.Parameter] = []
    kind = inspect.Parameter.POSITIONAL_OR_KEYWORD
    for part in _split_top_level(match.group("params")):
        if part in ("*", "/"):
            if part == "*":
                kind = inspect.Parameter.KEYWORD_ONLY
            continue
        if part.startswith("**"):
            params.append(inspect.Parameter(part[2:].split(":")[0].strip(),
                                            inspect.Parameter.VAR_KEYWORD))
            continue
        if part.startswith("*"):
            params.append(inspect.Parameter(part[1:].split(":")[0].strip(),
                                            inspect.Parameter.VAR_POSITIONAL))
            kind = inspect.Parameter.KEYWORD_ONLY
            continue
        name_annotation, _, default_text = part.partition("=")
        name, _, annotation = name_annotation.partition(":")
        name = name.strip()
        if not name.isidentifier():
            return None
        default: Any = inspect.Parameter.empty
        if default_text.strip():
            try:
                default = _clean_default(ast.literal_eval(default_text.strip()))
            except (ValueError, SyntaxError):
                default = _Text(_clean_annotation(default_text.strip()))
        annotation = _clean_annotation(annotation.strip())
        params.append(inspect.Parameter(name, kind, default=default,
                                        annotation=_Text(annotation) if annotation
                                        else inspect.Parameter.empty))
    ret = match.group("ret")
    return params, _Text(_clean_annotation(ret)) if ret else None


def _signatures(doc: Optional[str], name: str) -> List[str]:
    """The signature lines of a pybind11 docstring (one, or one per overload)."""
    if not doc:
        return []
    lines = doc.splitlines()
    if len(lines) > 1 and lines[1].strip() == "Overloaded function.":
        return [re.sub(r"^\d+\.\s*", "", l.strip()) for l in lines[2:]
                if re.match(r"^\d+\.\s*" + re.escape(name) + r"\(", l.strip())]
    return [lines[0]] if lines[0].startswith(name + "(") else []


def _signature_object(func: Callable, name: str, method: bool) -> Optional[inspect.Signature]:
    sigs = _signatures(getattr(func, "__doc__", None), name)
    if len(sigs) != 1:
        return None
    parsed = _parameters(sigs[0])
    if parsed is None:
        return None
    params, ret = parsed
    try:
        return inspect.Signature(params, return_annotation=ret or inspect.Signature.empty)
    except ValueError:  # e.g. a default before a non-default parameter
        return None


def _known_names(message: str) -> Tuple[List[str], List[str]]:
    """The signatures pybind11 lists in its error, and every parameter name they accept."""
    sigs = []
    for line in message.splitlines():
        m = _SIGNATURE_LINE.match(line)
        if m:
            sigs.append(m.group("sig"))
    names: List[str] = []
    for sig in sigs:
        inner = sig[sig.find("(") + 1: sig.rfind(")")] if "(" in sig else ""
        for part in _split_top_level(inner):
            n = part.split(":")[0].split("=")[0].strip().lstrip("*")
            if n.isidentifier() and n != "self" and n not in names:
                names.append(n)
    return sigs, names


def _describe(values: Tuple[Any, ...], kwargs: Dict[str, Any]) -> str:
    def short(v: Any) -> str:
        text = repr(v)
        return text if len(text) <= 60 else text[:57] + "..."

    parts = [short(v) for v in values] + [f"{k}={short(v)}" for k, v in kwargs.items()]
    return ", ".join(parts)


def _translate(error: TypeError, qualname: str, args: Tuple[Any, ...],
               kwargs: Dict[str, Any], error_type: type) -> Optional[Exception]:
    message = str(error)
    if not any(marker in message for marker in _INCOMPATIBLE):
        return None
    sigs, names = _known_names(message)
    unknown = [k for k in kwargs if k not in names]
    if unknown:
        hints = []
        for k in unknown:
            close = difflib.get_close_matches(k, names, n=1)
            hints.append(f"'{k}'" + (f" (did you mean '{close[0]}'?)" if close else ""))
        text = (f"{qualname}: unknown keyword argument{'s' if len(unknown) > 1 else ''} "
                f"{', '.join(hints)}; it takes {', '.join(names) or 'no arguments'}")
    else:
        shown = []
        for sig in sigs:
            parsed = _parameters(sig[sig.find("("):] if "(" in sig else sig)
            try:
                shown.append(str(inspect.Signature([p for p in parsed[0] if p.name != "self"]))
                             if parsed else _clean_annotation(sig))
            except ValueError:
                shown.append(_clean_annotation(sig))
        negative = any(isinstance(v, int) and not isinstance(v, bool) and v < 0
                       for v in (*args, *kwargs.values()))
        text = (f"{qualname}: the arguments ({_describe(args, kwargs)}) do not fit "
                f"{' or '.join(shown)}" + (" (a count or size cannot be negative)"
                                           if negative else ""))
    return error_type(text)


def _wrap(func: Callable, qualname: str, error_type: type, skip_self: bool) -> Callable:
    @functools.wraps(func)
    def call(*args: Any, **kwargs: Any) -> Any:
        try:
            return func(*args, **kwargs)
        except TypeError as e:
            shown = args[1:] if skip_self else args
            translated = _translate(e, qualname, shown, kwargs, error_type)
            if translated is None:
                raise
            raise translated from None

    sig = _signature_object(func, func.__name__, skip_self)
    if sig is not None:
        if skip_self:
            sig = sig.replace(parameters=[inspect.Parameter("self",
                                                            inspect.Parameter.POSITIONAL_ONLY),
                                          *[p for p in sig.parameters.values()
                                            if p.name != "self"]])
        call.__signature__ = sig  # type: ignore[attr-defined]
    else:
        call.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
            [inspect.Parameter("args", inspect.Parameter.VAR_POSITIONAL),
             inspect.Parameter("kwargs", inspect.Parameter.VAR_KEYWORD)])
    call.__weft_wrapped__ = True  # type: ignore[attr-defined]
    return call


def _wrap_setter(fset: Callable, qualname: str, error_type: type) -> Callable:
    """A property setter whose conversion failures (a wrong type, an int out of range, an
    unsigned given a negative) raise ``error_type`` naming the property and the value."""
    @functools.wraps(fset)
    def set_value(obj: Any, value: Any) -> None:
        try:
            fset(obj, value)
        except TypeError as e:
            if not any(marker in str(e) for marker in _INCOMPATIBLE):
                # the setter's own type check ("ka must be numeric, got str"): same class
                raise error_type(f"{qualname}: {e}") from None
            expects = re.findall(r"arg1: ([^)]*)\)", str(e))
            hint = f" (expects {_clean_annotation(expects[0])})" if expects else ""
            negative = isinstance(value, int) and not isinstance(value, bool) and value < 0
            raise error_type(f"{qualname} cannot be set to {_describe((value,), {})}{hint}"
                             + ("; a count or size cannot be negative" if negative else "")
                             ) from None
        except RuntimeError as e:
            if not str(e).startswith("Unable to cast"):
                raise
            raise error_type(f"{qualname} cannot be set to {_describe((value,), {})} "
                             "(wrong type)") from None
    return set_value


def install(core: Any, error_type: type) -> None:
    """Wraps every compiled function, constructor and method of ``core`` in place."""
    for name in dir(core):
        obj = getattr(core, name)
        if type(obj).__name__ == "builtin_function_or_method" and not name.startswith("_"):
            setattr(core, name, _wrap(obj, f"weft.{name}()", error_type, False))
        elif isinstance(obj, type) and getattr(obj, "__module__", "").startswith("weft"):
            if issubclass(obj, BaseException):
                continue
            for attr, value in list(vars(obj).items()):
                if attr.startswith("__") and attr != "__init__":
                    continue
                if attr.startswith("_") and attr != "__init__":
                    continue
                kind = type(value).__name__
                label = f"weft.{name}()" if attr == "__init__" else f"weft.{name}.{attr}()"
                if type(value) is property and value.fset is not None:
                    setattr(obj, attr, property(value.fget,
                                                _wrap_setter(value.fset, f"weft.{name}.{attr}",
                                                             error_type),
                                                value.fdel, value.__doc__))
                elif kind == "instancemethod":
                    setattr(obj, attr, _wrap(value.__func__, label, error_type, True))
                elif isinstance(value, staticmethod):
                    setattr(obj, attr, staticmethod(_wrap(value.__func__, label, error_type,
                                                          False)))
