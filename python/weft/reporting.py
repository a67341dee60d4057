"""What weft's reports and long runs share: a progress bar (tqdm), Markdown tables and the
matplotlib figure tail (Agg backend, save, close).

Progress is shown when stderr is a terminal, or when asked (``--progress``, ``enabled=True``);
a run whose output goes to a file or a pipe stays quiet unless asked. matplotlib and tqdm are
required dependencies of the package (pyproject.toml).
"""

from __future__ import annotations

import argparse
import os
import sys
from typing import Any, Optional, Sequence, TextIO

from tqdm import tqdm


def _is_terminal(stream: Any) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):  # no isatty, or a closed stream
        return False


class Progress:
    """A progress bar on stderr over ``total`` steps, labelled with the step now running.

    ``enabled``: True shows it, False hides it, None (the default) shows it only when ``stream``
    is a terminal, so that logs and captured output do not fill with bars."""

    def __init__(self, total: int, stream: Optional[TextIO] = None,
                 enabled: Optional[bool] = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = _is_terminal(self.stream) if enabled is None else bool(enabled)
        self.total = max(int(total), 1)
        self._bar = tqdm(total=self.total, file=self.stream, disable=not self.enabled,
                         dynamic_ncols=True, unit="step", leave=True,
                         bar_format="{l_bar}{bar}| {n_fmt}/{total_fmt} [{elapsed}<{remaining}]")

    @property
    def done(self) -> int:
        return int(self._bar.n)

    def update(self, label: str) -> None:
        """Shows ``label`` for the step now running."""
        self._bar.set_description_str(label, refresh=True)

    def step(self, label: str = "") -> None:
        """Marks one step finished (and shows ``label`` when given)."""
        if label:
            self._bar.set_description_str(label, refresh=False)
        self._bar.update(1)

    def close(self) -> None:
        self._bar.close()

    def __enter__(self) -> "Progress":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


def add_progress_arguments(parser: argparse.ArgumentParser) -> None:
    """``--progress`` / ``--no-progress`` (dest ``progress``: True, False, or None = only on a
    terminal)."""
    parser.add_argument("--progress", dest="progress", action=argparse.BooleanOptionalAction,
                        default=None,
                        help="show a progress bar on stderr (default: only when stderr is a "
                             "terminal)")


def markdown_table(header: Sequence[Any], rows: Sequence[Sequence[Any]]) -> str:
    """A GitHub-flavoured Markdown table; a ``|`` inside a cell is escaped."""
    def cell(value: Any) -> str:
        return str(value).replace("|", "\\|").replace("\n", " ")

    lines = ["| " + " | ".join(cell(h) for h in header) + " |",
             "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(cell(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def pyplot() -> Any:
    """matplotlib.pyplot on the Agg backend (files only: no display needed)."""
    import matplotlib  # noqa: PLC0415 - imported on first figure, not with weft

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: PLC0415

    return plt


def save_figure(fig: Any, path: str, dpi: int = 100) -> str:
    """Writes ``fig`` to ``path`` (folders made as needed) and closes it; returns ``path``."""
    plt = pyplot()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    try:
        fig.savefig(path, dpi=dpi)
    finally:
        plt.close(fig)
    return path
