"""Coverage feedback from what the C++ loaders answered (issue 13).

atheris instruments Python only: every input that reaches a compiled decoder follows the same
Python lines, so libFuzzer would keep one seed and learn nothing from the decoder. Here the
outcome -- the error message with its numbers and paths blanked, or the result's shape and type
-- is hashed to 8 bits and walked down a generated, instrumented tree of 255 branches: each new
kind of answer (a new parser state reached in C++) is a new Python edge, so inputs reaching it
are kept in the corpus and mutated further.
"""

from __future__ import annotations

import re
import zlib

_DEPTH = 8


def _tree_source() -> str:
    lines = ["def walk(h):", "    n = 0"]

    def emit(depth: int, indent: str) -> None:
        if depth == _DEPTH:
            lines.append(indent + "n += 1")
            return
        lines.append(indent + f"if h & {1 << depth}:")
        emit(depth + 1, indent + "    ")
        lines.append(indent + "else:")
        emit(depth + 1, indent + "    ")
    emit(0, "    ")
    lines.append("    return n")
    return "\n".join(lines) + "\n"


_namespace: dict = {}
exec(compile(_tree_source(), "<outcome_feedback>", "exec"), _namespace)  # noqa: S102
walk = _namespace["walk"]


def instrument() -> None:
    """Makes the tree visible to atheris (call before atheris.Fuzz)."""
    global walk
    import atheris

    walk = atheris.instrument_func(walk)


def outcome(result=None, error: BaseException | None = None) -> None:
    if error is not None:
        text = re.sub(r"'[^']*'|\"[^\"]*\"|/\S+|\d+", "#", str(error))
        text = type(error).__name__ + text
    else:
        text = repr((getattr(result, "shape", None), getattr(result, "dtype", type(result))))
    walk(zlib.crc32(text.encode("utf-8", "backslashreplace")))


def file_target(load, path: str):
    """A fuzz target that writes each input to `path` and feeds `load(path)`'s answer (result or
    weft error) to :func:`outcome`; any other exception is a finding."""
    import weft

    def one(data: bytes) -> None:
        with open(path, "wb") as f:
            f.write(data)
        try:
            outcome(load(path))
        except weft.Error as e:
            outcome(error=e)
    return one
