"""The realization search in the manuscript: its numbers as macros, and a table per statement.

Reads results/search/search.nc (``stages.merge``), the ensemble verdicts of the chosen chain
(``verdicts.verdict_dataset``, one file per scene), the energy scan and the disorder statistics.
"""

import numpy as np
import xarray as xr

from chainchaos.output.formatting import tex_number, tex_parameter
from chainchaos.paper import statements
from chainchaos.paper.verdicts import HOLDS, VERDICT_NAMES, verdict_code
from chainchaos.studies.scan.merge import probability_at
from chainchaos.studies.scan.thresholds import criterion_holds, first_energy
from chainchaos.system.models import model_label


def _statement_rows(search: xr.Dataset, verdicts: dict) -> list[dict]:
    scored = search["scored"].values == 1
    chosen = int(search.attrs["chosen_candidate"])
    rows = []
    for st in statements.STATEMENTS:
        i = st.id
        v = verdicts.get(st.scene.name)
        row = {
            "id": i,
            "not_broken": int((search["filter_outcome"].sel(statement=i).values != 0).sum()),
            "held": int((search["verdict"].sel(statement=i).values[scored] == HOLDS).sum()),
            "search_fraction": float(search["fraction"].sel(statement=i).values[chosen]),
            "fraction": float(v["fraction"].sel(statement=i)) if v is not None else float("nan"),
            "lanes": int(v["n_decided"].sel(statement=i)) if v is not None else 0,
            "verdict": VERDICT_NAMES[int(v["verdict"].sel(statement=i))] if v is not None else "--",
        }
        rows.append(row)
    return rows


def step_agreement(search: xr.Dataset, verdicts: dict, agreement: float) -> tuple[int, int]:
    """(statements whose verdict on the chosen chain is the same at the search's step and at the
    verdicts' step, statements decided at both): the check that the coarser search step does not
    change the verdicts."""
    same = total = 0
    for r in _statement_rows(search, verdicts):
        a, b = r["search_fraction"], r["fraction"]
        if not (np.isfinite(a) and np.isfinite(b)):
            continue
        total += 1
        same += verdict_code(a, agreement) == verdict_code(b, agreement)
    return same, total


def search_table_tex(search: xr.Dataset, verdicts: dict) -> str:
    """Per statement: candidates whose short run leaves it unbroken, scored candidates on whose
    ensemble it holds, the chosen chain's fraction at the search step and at the verdict step."""
    n_c, n_s = search.sizes["candidate"], int((search["scored"].values == 1).sum())
    lines = [
        r"\begingroup\footnotesize",
        r"\begin{longtable}{@{}lcccc@{}}",
        (r"\caption{\label{tab:search}The realization search, statement by statement: of the "
         f"{n_c} candidates, how many short runs (to $t = {tex_parameter(search.attrs['filter_t_final'])}$) leave the "
         f"statement unbroken; of the {n_s} candidates scored on ensembles, on how many it holds; on the "
         r"chosen chain, the fraction of perturbed orbits satisfying it at the search's step "
         f"($\\Delta t = {tex_parameter(search.attrs['dt'])}$) and at the verdicts' step, with that verdict.}}\\\\"),
        r"\hline\hline",
        r"Statement & unbroken & holds & chosen (search) & chosen (verdict)\\ \hline",
        r"\endfirsthead",
        r"\hline Statement & unbroken & holds & chosen (search) & chosen (verdict)\\ \hline",
        r"\endhead",
        r"\hline\hline",
        r"\endlastfoot",
    ]
    for r in _statement_rows(search, verdicts):
        verdict_cell = (f"${tex_number(r['fraction'], 2)}$ of {r['lanes']}, {r['verdict']}" if r["lanes"]
                        else r["verdict"])
        lines.append(f"\\texttt{{{r['id']}}} & {r['not_broken']}/{n_c} & {r['held']}/{n_s} & "
                     f"${tex_number(r['search_fraction'], 2)}$ & {verdict_cell}\\\\")
    lines += [r"\end{longtable}", r"\endgroup", ""]
    return "\n".join(lines)


def threshold_quantiles(energy_scan: xr.Dataset, disorder: xr.Dataset) -> dict:
    """Where the chosen chain's thresholds sit among the realizations: per model and criterion, its
    lowest scanned energy H* that satisfies the criterion, and the fraction of the disorder
    statistics' realizations that already satisfy it at H* (log-linear interpolation on their
    grid; NaN outside it). A typical chain sits near one half."""
    out = {}
    for model in energy_scan.model.values:
        for key in ("delocalized", "chaotic"):
            H = first_energy(energy_scan.energy.values, criterion_holds(energy_scan, str(model), key))
            out[(str(model), key)] = (H, probability_at(disorder, str(model), key, H))
    return out


def search_macros(search: xr.Dataset, verdicts: dict, energy_scan: xr.Dataset, disorder: xr.Dataset,
                  agreement: float) -> dict[str, str]:
    a = search.attrs
    scored = search["scored"].values == 1
    held = search["statements_held"].values[scored]
    out = {
        "search.pinned": "yes" if int(a["pinned"]) else "no",
        "search.candidates": str(search.sizes["candidate"]),
        "search.scored": str(int(scored.sum())),
        "search.statements": str(int(a["n_statements"])),
        "search.seed": str(int(a["chosen_seed"])),
        "search.score": tex_number(float(a["chosen_score"])),
        "search.held": str(int(search["statements_held"].values[int(a["chosen_candidate"])])),
        "search.heldmax": str(int(held.max())) if held.size else "0",
        "search.heldmin": str(int(held.min())) if held.size else "0",
        "search.filtert": tex_parameter(a["filter_t_final"]),
        "search.tfinal": tex_parameter(a["t_final"]),
        "search.dt": tex_parameter(a["dt"]),
        "search.lanes": str(int(a["lanes"])),
        "search.seedsscanned": str(int(a["seeds_scanned"])),
        "search.perturbation": tex_parameter(a["perturbation"]),
        "search.allheld": str(int((held == int(a["n_statements"])).sum())),
    }
    same, total = step_agreement(search, verdicts, agreement)
    out["search.stepsame"], out["search.steptotal"] = str(same), str(total)
    any_v = next(iter(verdicts.values()), None)
    if any_v is not None:
        out.update({"verdicts.lanes": str(int(any_v.attrs["lanes"])), "verdicts.dt": tex_parameter(any_v.attrs["dt"]),
                    "verdicts.tfinal": tex_parameter(any_v.attrs["t_final"])})
    names = {"delocalized": "deloc", "chaotic": "chaos"}
    for (model, key), (H, frac) in threshold_quantiles(energy_scan, disorder).items():
        label = model_label(model)
        if not np.isfinite(H):
            sentence = f"the chosen {label} chain is never {key} on the scanned grid."
        elif not np.isfinite(frac):
            sentence = (f"the chosen {label} chain is first {key} at $H = {tex_number(H)}$, outside the grid of the "
                        f"disorder statistics.")
        else:
            sentence = (f"at $H = {tex_number(H)}$, where the chosen {label} chain is first {key}, "
                        f"{tex_number(100 * frac, 2)}\\,\\% of the realizations are.")
        out[f"search.{model}.{names[key]}.sentence"] = sentence[0].upper() + sentence[1:]
    return out
