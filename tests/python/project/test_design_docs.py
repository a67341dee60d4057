"""The design the sources cite is in the repository: every `SPEC §N` or `SPEC §N.M` in the C++,
GLSL, Python and test sources names a section heading of docs/design/SPEC.md (issue 15: the
comments used to point to a file outside the repository)."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
CITE = re.compile(r"SPEC §(\d+(?:\.\d+)*)")
HEADING = re.compile(r"^#{2,3} (\d+(?:\.\d+)*)\.? ", re.M)
SOURCES = ("cpp", "glsl", "python", "tests", "scripts")
SUFFIXES = {".h", ".cpp", ".glsl", ".vert", ".frag", ".comp", ".geom", ".py", ".sh", ".txt"}


def _cited():
    cited = {}
    for top in SOURCES:
        for path in (ROOT / top).rglob("*"):
            if path.suffix in SUFFIXES and path.is_file():
                for m in CITE.finditer(path.read_text(errors="replace")):
                    cited.setdefault(m.group(1), path.relative_to(ROOT))
    return cited


def test_every_cited_section_exists():
    spec = (ROOT / "docs" / "design" / "SPEC.md").read_text()
    sections = set(HEADING.findall(spec))
    assert {"1", "1.3", "4.5", "5.4"} <= sections, sorted(sections)  # the parser reads headings
    cited = _cited()
    assert len(cited) > 20, cited  # the sources do cite it
    missing = {k: str(v) for k, v in cited.items() if k not in sections}
    assert not missing, missing


def test_the_formats_are_in_the_repository():
    for name in ("hair.md", "bonn-btf.md"):
        text = (ROOT / "docs" / "design" / "formats" / name).read_text()
        assert len(text) > 500, name
