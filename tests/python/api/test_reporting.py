"""The shared report helpers (weft.reporting): the progress bar shows on a terminal or when
asked and stays out of captured output otherwise; Markdown tables; the figure tail."""

from __future__ import annotations

import argparse
import io

import numpy as np
from weft.reporting import Progress, add_progress_arguments, markdown_table, pyplot, save_figure


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def _run(stream: io.StringIO, enabled=None) -> str:
    p = Progress(3, stream=stream, enabled=enabled)
    p.update("fit Blinn-Phong")
    p.step("fit Blinn-Phong")
    p.step("Lafortune")
    p.close()
    return stream.getvalue()


def test_progress_is_quiet_on_a_pipe_unless_asked():
    assert _run(io.StringIO()) == ""
    assert _run(_Terminal(), enabled=False) == ""
    shown = _run(io.StringIO(), enabled=True)
    assert "fit Blinn-Phong" in shown and "Lafortune" in shown
    assert "2/3" in shown


def test_progress_shows_on_a_terminal_by_default():
    text = _run(_Terminal())
    # tqdm redraws at most every 0.1 s; the labels and the final count are always drawn
    assert "fit Blinn-Phong" in text and "Lafortune" in text and "2/3" in text


def test_progress_flags():
    parser = argparse.ArgumentParser()
    add_progress_arguments(parser)
    assert parser.parse_args([]).progress is None
    assert parser.parse_args(["--progress"]).progress is True
    assert parser.parse_args(["--no-progress"]).progress is False


def test_markdown_table_escapes_pipes():
    text = markdown_table(["a", "b"], [[1, "x|y"], ["2", None]])
    assert text.splitlines() == ["| a | b |", "|---|---|", "| 1 | x\\|y |", "| 2 | None |"]


def test_save_figure_writes_a_png_and_closes_the_figure(tmp_path):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(2, 2))
    ax.plot([0, 1], [0, 1])
    path = save_figure(fig, str(tmp_path / "sub" / "f.png"), dpi=50)
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert fig.number not in plt.get_fignums()
    import weft
    image = weft.load_png(path)
    assert image.shape[:2] == (100, 100)
    assert np.ptp(image[..., :3]) > 0
