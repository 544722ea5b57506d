"""Tasks of workflow/rules/manuscript.smk: the paper's claims measured on the results, and the
manuscript built from them (chainchaos.output.manuscript)."""

import sys

import xarray as xr

from chainchaos.output import manuscript
from chainchaos.paper.claims.evaluation import evaluate_claims as measure_claims
from chainchaos.paper.claims.quantities import taylor_sign_barrier
from chainchaos.paper.claims.writers import (
    claim_macros,
    claims_notes_tex,
    claims_table_tex,
    macros_tex,
    run_macros,
    scan_macros,
    scene_macros,
    scenes_table_tex,
    write_csv,
)
from chainchaos.paper.criteria import Criteria
from chainchaos.records import kept
from chainchaos.records.atomic import atomic_output
from chainchaos.records.io import read_chain, write_text
from chainchaos.studies.indicators.report import spectra_macros
from chainchaos.studies.search import report as search_report

#: The inputs of evaluate_claims that are not scene files (and the prefix of the ensemble verdicts).
#: ``search_population``: the search whose candidates are counted (the archived full search when
#: ``all`` pins its chain, else ``search`` itself).
PRODUCTS = ("chain", "ensemble", "energy_scan", "disorder", "search", "search_population")
VERDICT_PREFIX = "verdict_"
SPECTRUM_PREFIX = "spectrum_"


def evaluate_claims(inputs, outputs, params, wildcards) -> None:
    """Measure the paper's claims on the results and write claims.csv, claims_table.tex,
    claims_notes.tex, scenes_table.tex, search_table.tex and macros.tex (every number the
    manuscript prints, as \\cc{key}). Inputs: the products named in :data:`PRODUCTS`, the
    ensemble verdicts ``verdict_<scene>`` and the scene files by scene name (``code`` only triggers
    reruns, ``kept`` orders the job after the kept search's check); params: the config blocks
    ``claims`` and ``simulation``."""
    files = {k: v for k, v in inputs.items() if k not in ("code", "kept")}
    # the kept full search when `all` uses it: a damaged one stops this job, naming it
    kept.check_data(files["search_population"], "snakemake --cores 2 keep --config keep=search_full")
    products = {name: xr.load_dataset(files.pop(name)) for name in PRODUCTS}
    chain, ensemble, energy_scan, disorder, search, population = (products[name] for name in PRODUCTS)
    verdicts = {name[len(VERDICT_PREFIX):]: xr.load_dataset(files.pop(name))
                for name in sorted(files) if name.startswith(VERDICT_PREFIX)}
    spectra = {name[len(SPECTRUM_PREFIX):]: xr.load_dataset(files.pop(name))
               for name in sorted(files) if name.startswith(SPECTRUM_PREFIX)}
    scenes = {name: xr.load_dataset(path) for name, path in files.items()}
    criteria = Criteria.from_config(params.get("claims"))
    simulation = params.get("simulation", {})
    site = int(simulation.get("excited_site", 21))
    claims = measure_claims(scenes, chain, ensemble, criteria, excited_site=site, energy_scan=energy_scan,
                            verdicts=verdicts, search=population, disorder=disorder)

    barrier = taylor_sign_barrier(read_chain(inputs["chain"], k4_sign=-1.0), site)
    macros = run_macros(scenes, chain, ensemble, simulation, criteria, barrier)
    macros.update(scan_macros(energy_scan, disorder))
    for name, ds in scenes.items():
        macros.update(scene_macros(name, ds, criteria))
    macros.update(claim_macros(claims))
    macros.update(search_report.search_macros(population, search, verdicts, energy_scan, disorder, criteria))
    macros.update(spectra_macros(spectra))
    paper_scale = macros["run.scale"] == "paper"

    with atomic_output(outputs["csv"]) as tmp:
        write_csv(claims, tmp)
    write_text(claims_table_tex(claims), outputs["table"])
    write_text(claims_notes_tex(claims), outputs["notes"])
    write_text(scenes_table_tex(scenes), outputs["scenes"])
    write_text(search_report.search_table_tex(population, search, verdicts), outputs["search"])
    write_text(macros_tex(macros)
               + "\\newif\\ifpaperscale\n" + ("\\paperscaletrue\n" if paper_scale else "\\paperscalefalse\n")
               + "\\newif\\ifsearchpinned\n"
               + ("\\searchpinnedtrue\n" if int(search.attrs["pinned"]) else "\\searchpinnedfalse\n")
               + "\\newif\\ifsearcharchived\n"
               + ("\\searcharchivedtrue\n" if macros["search.archived"] == "yes" else "\\searcharchivedfalse\n")
               + "\\newif\\ifdisordergali\n"
               + ("\\disordergalitrue\n" if "probability_chaotic_gali" in disorder else "\\disordergalifalse\n"),
               outputs["macros"])
    for claim in claims:
        print(f"{claim.id:28s} {claim.verdict:28s} {claim.measured}", file=sys.stderr)


def build_manuscript(inputs, outputs, params, wildcards) -> None:
    """latexmk in the build directory on a copy of manuscript/ms.tex and of its inputs; a
    :class:`~chainchaos.errors.BuildError` (TeX missing, a LaTeX error) names what to do."""
    figures = {k: v for k, v in inputs.items() if k.startswith("fig")}
    parts = {part: {k[len(part) + 1:]: v for k, v in inputs.items() if k.startswith(f"{part}_")}
             for part in manuscript.PARTS}
    manuscript.build(inputs["tex"], {k: inputs[k] for k in manuscript.GENERATED}, figures, parts, outputs["pdf"],
                     params["build_dir"])


def beyond_the_paper(inputs, outputs, params, wildcards) -> None:
    """The section Beyond the paper's table of laws and figures, from the kept studies' laws files."""
    from chainchaos.output.beyond import body

    named = {name: xr.load_dataset(path) for name, path in zip(params["studies"], inputs["laws"])}
    write_text(body(named, dict(params["figures"])), outputs["body"])


def run_summary(inputs, outputs, params, wildcards) -> None:
    """What this run did, from its files (``output.run_summary``), as the report's table; with the
    optional input ``lock``, whether the running environment is the locked one."""
    from chainchaos.output.run_summary import summary_csv, summary_rows
    from chainchaos.records.environment import lock_status

    lock = inputs.get("lock")
    environment = lock_status(lock) if lock else None
    with (xr.open_dataset(inputs["chain"]) as chain, xr.open_dataset(inputs["scene"]) as scene,
          xr.open_dataset(inputs["energy_scan"]) as energy_scan, xr.open_dataset(inputs["disorder"]) as disorder):
        rows = summary_rows(chain, scene, energy_scan, disorder, inputs["claims"], environment)
    write_text(summary_csv(rows), outputs["csv"])
