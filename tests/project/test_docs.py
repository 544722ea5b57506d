"""The documentation site (mkdocs.yml, docs/) builds with --strict: every link and anchor resolves,
every docstring of the API reference parses, every generated page renders and every executed
example runs; an example that raises fails the build. Needs the docs extra."""

import html
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

pytestmark = pytest.mark.docs  # every test here builds the site or its hook

pytest.importorskip("mkdocs", reason="the docs extra is not installed: pip install -e '.[docs]'")
pytest.importorskip("markdown_exec", reason="the docs extra is not installed: pip install -e '.[docs]'")
pytest.importorskip("mkdocstrings", reason="the docs extra is not installed: pip install -e '.[docs]'")


def build(config: Path, site: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1"}
    return subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(config), "-d", str(site)],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=900, check=False)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The site built once, strict: (the build's result, its folder, its seconds)."""
    site = tmp_path_factory.mktemp("docs") / "site"
    start = time.perf_counter()
    result = build(ROOT / "mkdocs.yml", site)
    return result, site, time.perf_counter() - start


def test_the_site_builds_strict(built):
    result, site, seconds = built
    assert result.returncode == 0, result.stderr[-5000:]
    warnings = [line for line in result.stderr.splitlines() if line.startswith(("WARNING", "ERROR"))]
    assert not warnings, warnings
    for page in ("tutorials/first-orbit", "tutorials/ensemble", "reference/config", "reference/study-keys",
                 "reference/cli", "reference/api", "explanation/performance", "conventions"):
        assert (site / page / "index.html").is_file(), page
    # the generated pages hold what they are generated from
    assert "simulation.dt" in (site / "reference/config/index.html").read_text()
    assert "excitation.site" in (site / "reference/study-keys/index.html").read_text()
    assert "chainchaos simulate" in (site / "reference/cli/index.html").read_text()
    performance = (site / "explanation/performance/index.html").read_text()
    for record in sorted((ROOT / "benchmarks" / "results").glob("*.json")):
        assert record.name in performance, record.name
    # the executed examples ran and printed
    assert "Data variables" in (site / "tutorials/first-orbit/index.html").read_text()
    # the figures are drawn, and the code shown is what a user pastes, without the build's scaffolding
    for page in ("index.html", "tutorials/first-orbit/index.html", "tutorials/ensemble/index.html"):
        text = (site / page).read_text()
        assert "https://matplotlib.org" in text, f"{page}: no figure"  # a matplotlib SVG's metadata
        shown = html.unescape(re.sub(r"<[^>]+>", "", text))  # the text of the page, code included
        assert "plt.show()" in shown, page
        assert not [s for s in ("StringIO", "getvalue", "markdown-exec: hide") if s in shown], page
    # what to cite: every scheme's reference and every indicator's, from the registries
    from chainchaos.output import citing

    citing_page = html.unescape(re.sub(r"<[^>]+>", "", (site / "reference/citing/index.html").read_text()))
    for reference in [*citing.scheme_references().values(), *citing.indicator_references().values(),
                      *citing.method_references()]:
        assert reference in citing_page, reference
    assert "@misc{chainchaos," in citing_page
    assert "CHAINCHAOS_SIMD_LANES" in (site / "reference/environment/index.html").read_text()
    print(f"mkdocs build --strict: {seconds:.1f} s")


def test_the_api_page_shows_the_parameters_of_every_function_and_class(built):
    """Each function and class of docs/reference/api.md shows its parameter table (from its numpydoc
    Parameters section) before its members, and no Sphinx role is left as text (docs/hooks.py)."""
    result, site, _ = built
    assert result.returncode == 0, result.stderr[-5000:]
    page = (site / "reference/api/index.html").read_text()
    blocks = re.split(r'(?=<h3 id="chainchaos\.)', page)[1:]
    objects = [block for block in blocks if "module-attribute" not in block.split("</h3>", 1)[0]]
    assert len(objects) >= 30, len(objects)
    for block in objects:
        name = re.match(r'<h3 id="([^"]+)"', block)[1]
        own = block.split("<h4", 1)[0]  # before its members' headings
        assert 'doc-section-title">Parameters:<' in own and "<table>" in own, f"{name}: no parameter table"
    assert not re.search(r":(func|class|meth|attr|data|exc|mod):<code>", page), "a Sphinx role shown as text"


@pytest.mark.browser
def test_every_page_of_the_site_loads_in_chromium_without_console_errors(built):
    from browser import console_errors

    result, site, _ = built
    assert result.returncode == 0, result.stderr[-5000:]
    pages = sorted(site.rglob("index.html"))
    assert len(pages) > 10
    errors = {page: found for page, found in console_errors(pages, root=site).items() if found}
    assert not errors, errors


def test_a_failing_example_fails_the_build(tmp_path):
    """A copy of the site's configuration on a docs folder of one page whose example raises."""
    docs = tmp_path / "docs"
    docs.mkdir()
    shutil.copy(ROOT / "docs" / "hooks.py", docs / "hooks.py")
    (docs / "index.md").write_text('# A page\n\n```python exec="on" source="above"\n'
                                   'raise ValueError("this example fails")\n```\n')
    config = (ROOT / "mkdocs.yml").read_text()
    config = config[:config.index("\nnav:")] + "\nnav:\n  - Home: index.md\n"
    config = config.replace("paths: [src]", f"paths: [{ROOT / 'src'}]")
    (tmp_path / "mkdocs.yml").write_text(config)
    result = build(tmp_path / "mkdocs.yml", tmp_path / "site")
    assert result.returncode != 0
    assert "this example fails" in result.stderr and "index.md" in result.stderr


def test_the_hook_fails_a_build_without_strict(tmp_path):
    """The hook itself raises after a build in which an example raised, strict or not."""
    sys.path.insert(0, str(ROOT / "docs"))
    try:
        import hooks
    finally:
        sys.path.remove(str(ROOT / "docs"))
    from mkdocs.exceptions import PluginError

    hooks.on_pre_build(None)
    hooks.on_post_build(None)  # nothing failed: no error
    import logging

    logging.getLogger("mkdocs.plugins.markdown_exec").warning("markdown_exec: Execution of python code block "
                                                              "exited with errors")
    with pytest.raises(PluginError, match="1 executed example"):
        hooks.on_post_build(None)
    hooks.on_pre_build(None)
