"""The HTML report (snakemake --report) of the quick run, and the captions of the paper's figures."""

import json
import re
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest
import xarray as xr
from docutils.core import publish_parts
from jinja2 import Environment

from chainchaos.output import report_captions
from chainchaos.paper import panels, statements

ROOT = Path(__file__).resolve().parents[2]

# Every figure of the workflow besides the paper's panels and composites, and the tables.
OTHER_RESULTS = ["run_summary.csv", "energy_scan.png", "disorder_statistics.png", "lyapunov_spectra.png", "search.png", "search_joint.png",
                 "work_precision.png", "stability.png", "claims.csv", "thresholds.csv", "work_precision.csv",
                 "work_precision_runs.csv", "stability.csv", "step_advice.csv"]


def _render(figure_id: str) -> str:
    """The caption of a panel or composite as Snakemake renders it: its rule's caption template
    (Jinja, given the job's params), then docutils, here stopping at the first warning (Snakemake
    would print it into the report)."""
    panel = not figure_id.isdigit()
    template = (ROOT / "workflow/report" / ("panel.rst" if panel else "figure.rst")).read_text()
    caption = report_captions.panel_caption(figure_id) if panel else report_captions.figure_caption(int(figure_id))
    env = Environment(trim_blocks=True, lstrip_blocks=True)  # as snakemake.report
    text = env.from_string(template).render(snakemake=SimpleNamespace(params=SimpleNamespace(caption=caption)))
    assert caption.strip() in text  # inserted as it is: no Jinja in it is evaluated
    return publish_parts(text, writer="html", settings_overrides={"halt_level": 2, "report_level": 2})["body"]


def test_every_panel_and_figure_has_a_caption_that_renders_cleanly():
    for p in panels.PANELS:
        html = _render(p)
        assert f"Fig. {p[:-1]}({p[-1]})" in html and "Shows" in html and "The paper reports" in html, p
        for s in statements.statements_of_panel(p):
            assert s.text.split("$")[0].strip() in html, (p, s.id)
    for n in panels.LAYOUTS:
        html = _render(str(n))
        kinds = {panels.PANELS[p].kind for p in panels.panels_of_figure(n)}
        assert f"Fig. {n}</strong>" in html and html.count("<li>") >= len(kinds), n
        for p in panels.panels_of_figure(n):
            assert re.search(rf"<em>\([a-z, ]*{p[-1]}[a-z, ]*\)</em>", html), p


def test_every_statement_is_about_a_panel_of_the_figure_it_cites():
    for s in statements.STATEMENTS:
        ids = statements.statement_panels(s)
        assert ids and all(s.scene in panels.PANELS[p].scenes for p in ids), s.id
        assert all(f"(Fig. {p[:-1]}" in s.text for p in ids), s.id


def test_labels_tell_the_panels_of_a_figure_apart():
    for n in panels.LAYOUTS:
        rows = [report_captions.figure_labels(n)] + [report_captions.panel_labels(p)
                                                    for p in panels.panels_of_figure(n)]
        assert len({tuple(r.values()) for r in rows}) == len(rows)
        assert all(list(r) == list(rows[0]) for r in rows)
    assert report_captions.panel_labels("4c")["model"] == "Hertz, FPUT"
    assert report_captions.panel_labels("4c")["energy H"] == "0.5, 1.8"


def _embedded(html: str, name: str):
    """The JSON the report embeds as ``var name = {...};``."""
    match = re.search(rf"^\s*var {name} = (\{{.*\}});\s*$", html, re.M)
    assert match, name
    return json.loads(match.group(1))


@pytest.mark.pipeline
@pytest.mark.browser
def test_report_of_the_quick_run_holds_every_figure_with_caption_and_labels(quick, tmp_path):
    out = tmp_path / "report.html"
    done = subprocess.run([sys.executable, "-m", "snakemake", "--nolock", "--report", str(out),
                           "--configfile", "config/quick.yaml", "--config", f"results={quick}"],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, (done.stdout + done.stderr)[-4000:]
    assert "Unknown command" not in done.stderr  # LaTeX that docutils' math cannot render
    html = out.read_text()
    assert "system-message" not in html  # a docutils warning printed into a caption
    embedded = _embedded(html, "results")
    # the figures of the studies shown in the manuscript's Beyond the paper (kept studies), apart
    studies = {path: entry for path, entry in embedded.items() if "/studies/" in path}
    results = {Path(path).name: entry for path, entry in embedded.items() if path not in studies}
    categories = _embedded(html, "categories")
    for path, entry in studies.items():
        assert entry["caption"].strip() and entry["labels"].get("study") in path, path

    for p in panels.PANELS:
        entry = results[f"fig{p}.png"]
        assert entry["labels"] == report_captions.panel_labels(p)
        assert f"Fig. {p[:-1]}({p[-1]})" in entry["caption"], p
    for n in panels.LAYOUTS:
        entry = results[f"fig{n}.png"]
        assert entry["labels"] == report_captions.figure_labels(n)
        assert f"Fig. {n}</strong>" in entry["caption"]
    for name in OTHER_RESULTS:
        assert results[name]["caption"].strip() and results[name]["labels"], name
    assert set(categories["Paper figures"]) == {report_captions.figure_subcategory(n) for n in panels.LAYOUTS}
    expected = len(panels.PANELS) + len(panels.LAYOUTS) + len(OTHER_RESULTS)
    assert len(results) == expected
    # the start page (workflow/report/workflow.rst) links every category by its name
    for category in categories:
        assert f"showCategory('{category.replace(' ', '%20')}')" in html, category
    from browser import console_errors

    assert console_errors([out]) == {str(out): []}  # it loads in Chromium without errors


@pytest.mark.pipeline
def test_the_run_summary_says_what_the_quick_run_did_from_its_files(quick):
    """The quick run pins the archived full search's chain: the summary says so with that search's
    counts, and the quick scale's times as the project writes them, none of it from the config."""
    import csv

    with open(quick / "report" / "run_summary.csv", newline="") as f:
        rows = {row["what"]: row["this run"] for row in csv.DictReader(f)}
    with xr.open_dataset(ROOT / "data" / "search" / "search_full.nc") as archive:
        counts = (f"{int(archive.attrs['seeds_scanned'])} seeds scanned, {int(archive.attrs['n_qualifying'])} "
                  f"candidates passed the linear rule, {int(archive.attrs['n_scored'])} scored")
        seed = int(archive.attrs["chosen_seed"])
    assert rows["chain"].startswith(f"seed {seed}, N = 40")
    assert rows["chain chosen by"].startswith("the archived full search data/search/search_full.nc") and \
        counts in rows["chain chosen by"]
    assert rows["scenes"].endswith("to t = 10^3") and "to t = 10^3" in rows["energy scan"]
    assert rows["disorder statistics"].endswith("this run's own disorder statistics")
    assert "reproduced" in rows["claims"]


def test_the_run_summary_names_the_archived_disorder_statistics_it_read(tmp_path):
    from chainchaos.output.run_summary import summary_rows

    with xr.open_dataset(ROOT / "data" / "disorder" / "disorder_full.nc") as archive:
        disorder = archive.copy()
    disorder.attrs["kept_file"] = "data/disorder/disorder_full.nc (the archived full disorder statistics)"
    scan = xr.Dataset(coords={"energy": [0.1, 10.0]}, attrs={"t_final": 1e5, "dt": 0.01})
    chain = xr.Dataset(coords={"site": range(40)}, attrs={
        "seed": 879, "alpha": 5.0, "selection_source": "data/search/search_full.nc", "selection_pinned": 0,
        "selection_seeds_scanned": 200000, "selection_candidates": 2392, "selection_search_scored": 64,
        "selection_search_score": 23.625, "selection_site": 21, "selection_mode": 34})
    scene = xr.Dataset(attrs={"integrator": "SRKN6b", "dt": 5e-4, "t_final": 1e5})
    claims = tmp_path / "claims.csv"
    claims.write_text("id,verdict\na,reproduced\nb,differs\nc,reproduced\n")
    rows = dict(summary_rows(chain, scene, scan, disorder, str(claims)))
    assert rows["disorder statistics"] == ("100 realizations x 20 energies, to t = 10^4: "
                                           "data/disorder/disorder_full.nc (the archived full disorder statistics)")
    assert rows["scenes"] == "SRKN6b at dt = 0.0005, to t = 10^5" and rows["claims"] == "1 differs, 2 reproduced"
    assert "200000 seeds scanned, 2392 candidates passed the linear rule, 64 scored" in rows["chain chosen by"]
    # the environment's row only when the task was given the lock (its optional input)
    assert "environment" not in rows
    status = "equals requirements/lock.txt (122 packages)"
    assert summary_rows(chain, scene, scan, disorder, str(claims), status)[-1] == ("environment", status)
