"""docs/conventions.md is what the code cites by section: every citation names a heading that exists."""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "conventions.md"
CITING = ("src", "workflow", "config", "tests", "README.md", "docs")
CITATION = re.compile(r"conventions\.md#([A-Za-z0-9_-]+)")

pytestmark = pytest.mark.docs  # checks pages of docs/


def anchors(markdown: str) -> set[str]:
    """The anchors GitHub gives the headings: lower case, punctuation dropped, spaces to hyphens,
    a repeated heading numbered -1, -2, ..."""
    seen: dict[str, int] = {}
    out = set()
    fenced = False
    for line in markdown.splitlines():
        if line.startswith("```"):
            fenced = not fenced
        heading = None if fenced else re.match(r"#{1,6}\s+(.*)", line)
        if heading:
            slug = re.sub(r"[^\w\- ]", "", heading.group(1).strip().lower()).replace(" ", "-")
            out.add(f"{slug}-{seen[slug]}" if slug in seen else slug)
            seen[slug] = seen.get(slug, 0) + 1
    return out


def citations() -> list[tuple[str, int, str]]:
    found = []
    for top in CITING:
        paths = [ROOT / top] if (ROOT / top).is_file() else sorted((ROOT / top).rglob("*"))
        for path in paths:
            if not path.is_file() or path.suffix not in (".py", ".smk", ".yaml", ".md", ".rst", ""):
                continue
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                found += [(str(path.relative_to(ROOT)), number, a) for a in CITATION.findall(line)]
    return found


def test_every_cited_section_exists():
    known = anchors(DOC.read_text())
    cited = citations()
    assert cited, "no citation of docs/conventions.md found"
    missing = [f"{path}:{number}: #{anchor}" for path, number, anchor in cited if anchor not in known]
    assert not missing, f"citations of sections docs/conventions.md lacks: {missing}"


def test_the_contents_list_links_to_headings():
    text = DOC.read_text()
    links = re.findall(r"\]\(#([^)]+)\)", text)
    assert links and set(links) <= anchors(text)


def test_anchors_follow_the_headings():
    assert anchors("# A title\n## Bond laws\n```\n# not a heading\n```\n### Finite-time mLCE\n## Bond laws\n") == {
        "a-title", "bond-laws", "finite-time-mlce", "bond-laws-1"}
