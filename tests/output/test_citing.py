"""What to cite and which environment variables count, as the docs say them: docs/reference/citing.md
renders the registries' own references (every integration scheme, every chaos indicator and the
tangent map method) and the BibTeX of CITATION.cff, which the README carries unchanged;
docs/reference/environment.md names every environment variable the package reads."""

import re
from pathlib import Path

import pytest

from chainchaos.engine.integrators import SCHEMES
from chainchaos.observe.registry import NEED_REFERENCES, REGISTRY, TANGENT, needing
from chainchaos.output import citing

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "reference" / "citing.md"
ENVIRONMENT = ROOT / "docs" / "reference" / "environment.md"

pytestmark = pytest.mark.docs  # checks pages of docs/


def executed_blocks(path: Path) -> str:
    """The code of the page's blocks that run when the site builds."""
    return "\n".join(re.findall(r'^```python exec="on"[^\n]*\n(.*?)^```', path.read_text(), re.S | re.M))


def test_every_scheme_has_a_reference_and_the_page_renders_them_all():
    references = citing.scheme_references()
    assert list(references) == list(SCHEMES)
    for name, scheme in SCHEMES.items():
        assert scheme.reference.strip(), f"scheme {name} has no reference"
        assert references[name] == scheme.reference
    assert "citing.scheme_references()" in executed_blocks(PAGE)


def test_every_chaos_indicator_has_its_paper_and_the_tangent_map_method():
    """The indicators are the observables that follow deviation vectors (they need the tangent map)."""
    indicators = sorted(needing(TANGENT))
    assert {"mlce", "lyapunov_spectrum", "sali", "log_gali", "dvd"} <= set(indicators), indicators
    references, methods = citing.indicator_references(), citing.method_references()
    for name in indicators:
        assert REGISTRY[name].reference.strip(), f"indicator {name} has no reference"
        assert references[name] == REGISTRY[name].reference, name
        assert name in methods[NEED_REFERENCES[TANGENT]], name
        assert REGISTRY[name].references == (REGISTRY[name].reference, NEED_REFERENCES[TANGENT]), name
    code = executed_blocks(PAGE)
    assert "citing.indicator_references()" in code and "citing.method_references()" in code


def test_the_bibtex_is_the_citation_files_and_the_readme_carries_it():
    citation = citing.read_citation(ROOT / "CITATION.cff")
    text = citing.bibtex(citation)
    assert f"note   = {{Version {citation['version']}}}" in text
    assert f"year   = {{{str(citation['date-released'])[:4]}}}" in text
    for author in citation["references"][0]["authors"]:
        assert f"{author['family-names']}, {author['given-names']}" in text
    assert not re.search(r"^\s*(journal|volume|doi)\s*=", text, re.M)  # none that could not be checked
    assert text.rstrip() in (ROOT / "README.md").read_text(), "README's BibTeX differs: paste citing.bibtex()"
    assert "citing.bibtex(" in executed_blocks(PAGE)


def package_environment_variables() -> set[str]:
    """Every environment variable a module of the package reads or sets by name."""
    found = set()
    for path in (ROOT / "src" / "chainchaos").rglob("*.py"):
        text = path.read_text()
        found |= set(re.findall(r'environ(?:\.get|\.setdefault)?\(\s*"([A-Z_]+)"', text))
        found |= set(re.findall(r'environ\[\s*"([A-Z_]+)"\s*\]', text))
        found |= set(re.findall(r'^[A-Z_]*VARIABLE\s*=\s*"([A-Z_]+)"', text, re.M))
    return found


def test_the_environment_page_names_every_variable_the_package_reads():
    names = package_environment_variables()
    assert {"NUMBA_DISABLE_INTEL_SVML", "NUMBA_CACHE_DIR", "CHAINCHAOS_SIMD_LANES",
            "SOURCE_DATE_EPOCH"} <= names, names
    page = ENVIRONMENT.read_text()
    missing = sorted(name for name in names if f"`{name}`" not in page)
    assert not missing, f"docs/reference/environment.md lacks {missing}"
