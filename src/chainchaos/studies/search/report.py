"""The realization search in the manuscript: its numbers as macros, and a table per statement.

Reads two merged searches (``stages.merge``): the *population*, whose candidates are counted (the
archived full search, ``archive``, when the build pins its chain; else the build's own search), and
the build's *search* (results/search/search.nc: the chosen chain re-scored when pinned); the
ensemble verdicts of the chosen chain (``verdicts.verdict_dataset``, one file per scene), the
energy scan and the disorder statistics.
"""

import numpy as np
import xarray as xr

from chainchaos.paper import statements
from chainchaos.paper.criteria import Criteria
from chainchaos.paper.verdicts import HOLDS, NOT_READ, VERDICT_NAMES, verdict_code
from chainchaos.records.formatting import tex_number, tex_parameter
from chainchaos.paper.thresholds import probability_at
from chainchaos.paper.thresholds import criterion_holds, first_energy
from chainchaos.studies.search.joint import (
    held_counts,
    joint_statements,
    onset_level_consistency,
    unbroken_counts,
)
from chainchaos.system.models import model_label


def _statement_rows(population: xr.Dataset, search: xr.Dataset, verdicts: dict) -> list[dict]:
    ids = [str(s) for s in population.statement.values]
    not_broken = dict(zip(ids, unbroken_counts(population)))
    held = dict(zip(ids, held_counts(population)))
    chosen = int(search.attrs["chosen_candidate"])
    by_indicator = indicator_held_counts(population)
    rows = []
    for st in statements.STATEMENTS:
        i = st.id
        v = verdicts.get(st.scene.name)
        row = {
            "id": i,
            "not_broken": int(not_broken[i]),
            "held": int(held[i]),
            "held_by": by_indicator.get(i),
            "search_fraction": float(search["fraction"].sel(statement=i).values[chosen]),
            "fraction": float(v["fraction"].sel(statement=i)) if v is not None else float("nan"),
            "lanes": int(v["n_decided"].sel(statement=i)) if v is not None else 0,
            "verdict": VERDICT_NAMES[int(v["verdict"].sel(statement=i))] if v is not None else "--",
        }
        rows.append(row)
    return rows


def _scored_verdicts(population: xr.Dataset):
    """The scored candidates' ensemble verdicts (candidate, statement) by Λ and by GALI_k, or None
    for a population scored by Λ alone (an archive written before GALI_k joined)."""
    scored = population["scored"].values == 1
    if "verdict_gali" not in population or (population["verdict_gali"].values[scored] == NOT_READ).all():
        return None
    return tuple(population[key].values[scored] for key in ("verdict_lambda", "verdict_gali"))


def indicator_held_counts(population: xr.Dataset) -> dict[str, tuple[int, int]]:
    """Per statement that GALI_k judges on some scored candidate: on how many scored candidates it
    holds by Λ and by GALI_k (empty for a population scored by Λ alone)."""
    verdicts = _scored_verdicts(population)
    if verdicts is None:
        return {}
    lam, gali = verdicts
    return {str(i): (int((lam[:, s] == HOLDS).sum()), int((gali[:, s] == HOLDS).sum()))
            for s, i in enumerate(population.statement.values) if (gali[:, s] != NOT_READ).any()}


def step_agreement(search: xr.Dataset, verdicts: dict, agreement: float) -> tuple[int, int]:
    """(statements whose verdict on the chosen chain is the same at the search's step and at the
    verdicts' step, statements decided at both): the check that the coarser search step does not
    change the verdicts."""
    same = total = 0
    for r in _statement_rows(search, search, verdicts):
        a, b = r["search_fraction"], r["fraction"]
        if not (np.isfinite(a) and np.isfinite(b)):
            continue
        total += 1
        same += verdict_code(a, agreement) == verdict_code(b, agreement)
    return same, total


def search_table_tex(population: xr.Dataset, search: xr.Dataset, verdicts: dict) -> str:
    """Per statement: candidates of the population whose short run leaves it unbroken, scored
    candidates on whose ensemble it holds, the chosen chain's fraction at the build's search step
    and at the verdict step."""
    n_c, n_s = population.sizes["candidate"], int((population["scored"].values == 1).sum())
    lines = [
        r"\begingroup\footnotesize",
        r"\begin{longtable}{@{}lcccc@{}}",
        (r"\caption{\label{tab:search}The realization search, statement by statement: of the "
         f"{n_c} candidates, how many short runs (to "
         f"$t = {tex_parameter(population.attrs['filter_t_final'])}$) leave the "
         f"statement unbroken; of the {n_s} candidates scored on ensembles, on how many it holds (for chaos "
         r"by $\Lambda$ and GALI together; in brackets, by each alone); on the "
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
    for r in _statement_rows(population, search, verdicts):
        verdict_cell = (f"${tex_number(r['fraction'], 2)}$ of {r['lanes']}, {r['verdict']}" if r["lanes"]
                        else r["verdict"])
        by = f" ({r['held_by'][0]}, {r['held_by'][1]})" if r["held_by"] else ""
        lines.append(f"\\texttt{{{r['id']}}} & {r['not_broken']}/{n_c} & {r['held']}/{n_s}{by} & "
                     f"${tex_number(r['search_fraction'], 2)}$ & {verdict_cell}\\\\")
    lines += [r"\end{longtable}", r"\endgroup", ""]
    return "\n".join(lines)


def _joint_macros(population: xr.Dataset, criteria: Criteria) -> dict[str, str]:
    """The joint analysis in words: statements that exclude each other, how many candidates score
    at least as well as the chosen one, and Hertz H = 1.8's onset against its level."""
    joint = joint_statements(population)
    pairs = joint.exclusive_pairs()
    tol = criteria.tolerance
    c = onset_level_consistency(population, tol.time_factor, tol.mlce_factor)
    listed = "; ".join(f"\\texttt{{{a}}} and \\texttt{{{b}}}" for a, b in pairs) or "none"
    return {
        "search.exclusive": str(len(pairs)),
        "search.exclusivelist": listed,
        "search.asgood": str(joint.at_least_as_good()),
        "search.asgoodfraction": tex_number(joint.at_least_as_good() / float(population.attrs["seeds_scanned"]), 2),
        "search.allheldtestable": str(joint.all_held()),
        "search.onsetnear": str(c["onset_near"]),
        "search.levelnear": str(c["level_near"]),
        "search.onsetlevelboth": str(c["both"]),
        "search.onsetleveldecided": str(c["decided"]),
        "search.lowestlevel": tex_number(c["lowest_level_with_onset"]) if np.isfinite(c["lowest_level_with_onset"])
        else "\\mbox{--}",
    }


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


def indicator_sentence(population: xr.Dataset) -> str:
    """How often Λ and GALI_k give the scored candidates different ensemble verdicts (each such
    verdict is undecided), or that the population was scored by Λ alone (an archive written before
    GALI_k joined)."""
    verdicts = _scored_verdicts(population)
    if verdicts is None:
        return "The scores were decided by $\\Lambda$ alone."
    lam, gali = verdicts
    read = gali != NOT_READ
    differ = read & (lam != gali)
    k, n = population.attrs.get("gali_order", "k"), int(differ.any(axis=1).sum())
    return (f"On the {len(lam)} scored candidates, $\\Lambda$ and GALI$_{{{k}}}$ give different "
            f"ensemble verdicts on {int(differ.sum())} of the {int(read.sum())} (candidate, statement) pairs "
            f"that GALI$_{{{k}}}$ judges, on {n} candidate{'' if n == 1 else 's'}: each such verdict is "
            f"undecided, and an orbit counts towards a score only where both say the statement holds.")


def _commits(stage_commits: str) -> str:
    """The commits of an archive's stage files in words: 'commit X' or 'commits X, Y' (short hashes)."""
    commits = [c.strip()[:7] for c in stage_commits.split(";") if c.strip()]
    return ("commit " if len(commits) == 1 else "commits ") + ", ".join(f"\\texttt{{{c}}}" for c in commits)


def search_macros(population: xr.Dataset, search: xr.Dataset, verdicts: dict, energy_scan: xr.Dataset,
                  disorder: xr.Dataset, criteria: Criteria) -> dict[str, str]:
    """The search's numbers in the text: the population's counts and choice, this build's re-score,
    the joint analysis (``joint``) and, for an archived search, its cost and machine."""
    agreement = criteria.agreement
    a = population.attrs
    archived = "cost_total_cpu_seconds" in a  # only search_full writes its cost
    scored = population["scored"].values == 1
    held = population["statements_held"].values[scored]
    out = {
        "search.pinned": "yes" if int(search.attrs["pinned"]) else "no",
        "search.archived": "yes" if archived else "no",
        "search.candidates": str(population.sizes["candidate"]),
        "search.scored": str(int(scored.sum())),
        "search.statements": str(int(a["n_statements"])),
        "search.seed": str(int(a["chosen_seed"])),
        "search.score": tex_number(float(a["chosen_score"])),
        "search.rescore": tex_number(float(search.attrs["chosen_score"])),
        "search.held": str(int(population["statements_held"].values[int(a["chosen_candidate"])])),
        "search.heldmax": str(int(held.max())) if held.size else "0",
        "search.heldmin": str(int(held.min())) if held.size else "0",
        "search.filtert": tex_parameter(a["filter_t_final"]),
        "search.tfinal": tex_parameter(a["t_final"]),
        "search.dt": tex_parameter(a["dt"]),
        "search.lanes": str(int(a["lanes"])),
        "search.seedsscanned": str(int(a["seeds_scanned"])),
        "search.qualifying": str(int(a["n_qualifying"])),
        "search.perturbation": tex_parameter(a["perturbation"]),
        "search.allheld": str(int((held == int(a["n_statements"])).sum())),
        "search.rescoretfinal": tex_parameter(search.attrs["t_final"]),
        "search.rescorelanes": str(int(search.attrs["lanes"])),
        "search.indicators.sentence": indicator_sentence(population),
    }
    out.update(_joint_macros(population, criteria))
    if archived:
        out.update({"search.cost.cpuhours": tex_number(a["cost_total_cpu_seconds"] / 3600, 2),
                    "search.cost.jobs": str(int(a["cost_total_jobs"])),
                    "search.cost.cpu": str(a["stage_cpus"]).replace("_", "\\_"),
                    "search.cost.commit": _commits(str(a["stage_commits"]))})
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
