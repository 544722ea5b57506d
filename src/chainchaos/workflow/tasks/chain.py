"""Tasks of workflow/rules/chain.smk: the disorder statistics (Fig. 1a) and the chosen chain."""

import sys

import xarray as xr

from chainchaos.records import kept
from chainchaos.records.io import chain_dataset, ensemble_dataset, write_netcdf
from chainchaos.studies.search import stages as search
from chainchaos.studies.search.selection import SelectionCriteria, candidate_row
from chainchaos.system.chain import random_chain


def selection_criteria(params: dict) -> SelectionCriteria:
    """The linear selection rule of the config's `chain` block (its `selection` sub-block)."""
    chain = params["chain"]
    return SelectionCriteria(alpha=float(chain["alpha"]), N=int(chain["N"]), **chain.get("selection", {}))


def compute_ensemble(inputs, outputs, params, wildcards) -> None:
    """Participation-number statistics of the linear modes over disorder realizations."""
    e = params["ensemble"]
    ds = ensemble_dataset(e["alphas"], e["realizations"], params["N"], e.get("first_seed", 0),
                          e.get("convention", "potential"))
    write_netcdf(ds, outputs["stats"])


def select_chain(inputs, outputs, params, wildcards) -> None:
    """The chain file of the realization a search chose (the archived full search's, this run's
    or the pinned seed), with that search's record of the choice."""
    selection = selection_criteria(params)
    # the kept full search when `all` pins its choice: a damaged one stops this job, naming it
    kept.check_data(inputs["search"], "snakemake --cores 2 keep --config keep=search_full")
    found = xr.load_dataset(inputs["search"])
    seed = int(found.attrs["chosen_seed"])
    chain = random_chain(seed, selection.alpha, selection.N, float(params["chain"].get("wall_radius", 1.0)))
    row = search.candidate_rows(found)[int(found.attrs["chosen_candidate"])]
    passes = bool(candidate_row(seed, selection)["qualifies"])
    record = {
        "selection_seed": seed,
        "selection_candidates": int(found.attrs["n_qualifying"]),
        "selection_seeds_scanned": int(found.attrs.get("seeds_scanned", selection.n_seeds)),
        "selection_mode": selection.mode,
        "selection_site": selection.site,
        "selection_linear_rule": int(passes),
        "selection_pinned": int(found.attrs["pinned"]),
        "selection_search_score": float(found.attrs["chosen_score"]),
        "selection_search_candidates": int(found.attrs["n_candidates"]),
        "selection_search_scored": int(found.attrs.get("n_scored", -1)),
        "selection_source": str(inputs["search"]),  # the archived full search, or this run's
        "selection_rule": ("the linear rule (selection module) as a first filter, then the chain whose orbits "
                           "satisfy the most of the paper's qualitative statements (search module)"),
    }
    record.update(selection_score=row["score"], selection_mode_participation=row["mode_participation"],
                  selection_overlap_left=row["overlap_left"], selection_overlap_right=row["overlap_right"])
    print(f"chose seed {seed}", file=sys.stderr)
    write_netcdf(chain_dataset(chain, record), outputs["chain"])
