"""What the ensemble verdicts, the realization search and the disorder statistics say about a claim:
its verdict when it rests on statements of ``statements.STATEMENTS``, and the reasons a row gives when it
differs (:data:`REASONS`, named by the catalogue's ``reason=(name, *args)``).
"""

import numpy as np

from chainchaos.observe.reductions import within_factor
from chainchaos.paper import statements
from chainchaos.paper import verdicts as _verdicts
from chainchaos.paper.claims.framework import (
    DIFFERS,
    FORMATS,
    REPRODUCED,
    UNDECIDED,
    UNTESTABLE,
    Inputs,
    Measurement,
)
from chainchaos.records.formatting import tex_math, tex_number, tex_parameter
from chainchaos.paper.thresholds import probability_at


def statement_result(inputs: Inputs, statement_id: str):
    """(fraction, lanes decided, verdict code) of a statement on its scene's ensemble, or None."""
    for ds in inputs.verdicts.values():
        if statement_id in ds["statement"].values:
            row = ds.sel(statement=statement_id)
            return float(row["fraction"]), int(row["n_decided"]), int(row["verdict"])
    return None


def indicator_text(inputs: Inputs, statement_id: str) -> str:
    """The orbits that satisfy a statement, as text: "7/8", or for one that Λ and GALI_k both
    decide "Λ 7/8, GALI_4 8/8" (each over the orbits it decides)."""
    for ds in inputs.verdicts.values():
        if statement_id not in ds["statement"].values:
            continue
        row = ds.sel(statement=statement_id)
        n = int(row["n_decided"])
        gali = f"\\mathrm{{GALI}}_{{{ds.attrs.get('gali_order', 'k')}}}"
        if "verdict_gali" not in row or int(row["verdict_gali"]) == _verdicts.NOT_READ:
            text = f"{round(float(row['fraction']) * n)}/{n}" if n else "--"
            crossing = row["measured_gali"].values if "measured_gali" in row else np.array([np.nan])
            if np.isfinite(crossing).any():  # an onset: GALI_k's crossing time, reported beside
                text += (f" (${gali}$ below its threshold from $t \\approx "
                         f"{tex_number(float(np.nanmedian(crossing)), 2)}$, median)")
            return text
        if not (np.isfinite(row["outcome"].values).any() or np.isfinite(row["outcome_gali"].values).any()):
            return "--"
        parts = []
        for name, key in (("\\Lambda", "outcome"), (gali, "outcome_gali")):
            x = row[key].values
            decided = np.isfinite(x)
            parts.append(f"${name}$ {int(np.nansum(x))}/{int(decided.sum())}")
        return ", ".join(parts)
    return "--"


def indicators_disagree(inputs: Inputs, ids) -> list[str]:
    """The statements among ``ids`` whose verdicts by Λ and by GALI_k differ."""
    out = []
    for ds in inputs.verdicts.values():
        for i in ids:
            if i in ds["statement"].values and "verdict_gali" in ds:
                row = ds.sel(statement=i)
                if int(row["verdict_gali"]) != _verdicts.NOT_READ and int(row["verdict_gali"]) != int(row["verdict_lambda"]):
                    out.append(i)
    return out


def ensemble_verdict(inputs: Inputs, ids) -> tuple[str, str] | None:
    """The claim's verdict from the ensemble verdicts of its statements: reproduced when all
    hold, differs when one fails, undecided when none fails and one is undecided (the orbits
    disagree, or the two chaos indicators do), not testable otherwise; and the fractions as text
    (e.g. "8/8; $\\Lambda$ 7/8, $\\mathrm{GALI}_4$ 8/8"). None when a statement has no ensemble verdict."""
    rows = [statement_result(inputs, i) for i in ids]
    if not rows or any(r is None for r in rows):
        return None
    codes = [r[2] for r in rows]
    text = "; ".join(indicator_text(inputs, i) for i in ids)
    if any(code == _verdicts.FAILS for code in codes):
        return DIFFERS, text
    if any(code == _verdicts.UNDECIDED for code in codes):
        return UNDECIDED, text
    if any(code == _verdicts.UNTESTABLE for code in codes):
        return UNTESTABLE, text
    return REPRODUCED, text


def search_evidence(inputs: Inputs, ids) -> str:
    """How many scored candidates of the realization search satisfy the failed statements."""
    ds = inputs.search
    if ds is None:
        return ""
    scored = ds["scored"].values == 1
    parts = []
    for i in ids:
        row = statement_result(inputs, i)
        if row is None or row[2] != _verdicts.FAILS or i not in ds["statement"].values:
            continue
        v = ds["verdict"].sel(statement=i).values[scored]
        held = int((v == _verdicts.HOLDS).sum())
        kept = int((ds["filter_outcome"].sel(statement=i).values != 0).sum())
        parts.append(f"\\texttt{{{i}}} holds on the ensembles of {held} of the {int(scored.sum())} scored "
                     f"candidates (and is not broken by the short runs of {kept} of the "
                     f"{ds.sizes['candidate']} candidates)")
    if not parts:
        return ""
    seeds = ds.attrs.get("seeds_scanned")
    searched = f"the search over {int(seeds)} seeds" if seeds else "the search"
    return (f"a property of the chosen chain, which satisfies the most statements of {searched}: "
            + "; ".join(parts))


# ---- reasons a row names -------------------------------------------------------------------------


def follows(inputs: Inputs, measurement: Measurement, statement_id: str, consequence: str) -> str:
    """A claim that follows from a statement: names the statement, its ensemble verdict and the
    search's evidence when it fails on the chosen chain (empty otherwise)."""
    row = statement_result(inputs, statement_id)
    if row is None or row[2] != _verdicts.FAILS:
        return ""
    evidence = search_evidence(inputs, (statement_id,))
    return (f"{consequence}: \\texttt{{{statement_id}}} fails on the chosen chain's ensemble "
            f"({round(row[0] * row[1])}/{row[1]} orbits satisfy it)" + (f"; {evidence}" if evidence else ""))


def spread_of_values(inputs: Inputs, measurement: Measurement, statement_id: str, what: str) -> str:
    """A value outside the tolerance: the range of the statement's measured value over the chosen
    chain's perturbed orbits and over the medians of the scored candidates of the search."""
    scene = next((st.scene.name for st in statements.STATEMENTS if st.id == statement_id), None)
    ds = inputs.verdicts.get(scene)
    if ds is None:
        return ""
    v = ds["measured"].sel(statement=statement_id).values
    v = v[np.isfinite(v)]
    if not v.size:
        return ""
    text = (f"{what} lies between {tex_math(v.min())} and {tex_math(v.max())} over the {v.size} perturbed "
            f"orbits of the chosen chain")
    if inputs.search is not None and "measured_median" in inputs.search:
        scored = inputs.search["scored"].values == 1
        c = inputs.search["measured_median"].sel(statement=statement_id).values[scored]
        c = c[np.isfinite(c)]
        if c.size:
            text += (f", and its median between {tex_math(c.min())} and {tex_math(c.max())} over the {c.size} "
                     f"scored candidates of the search: a property of the spread state of these chains")
    return text


def realization_threshold(inputs: Inputs, model: str, key: str, H_chain: float, H_paper: float) -> str:
    """A threshold of the chosen chain that differs from the paper's: where both sit in the
    disorder statistics (fraction of realizations that satisfy the criterion at each)."""
    text = f"the chosen chain's threshold $H^* = {tex_number(H_chain)}$ is a property of this realization"
    d = inputs.disorder
    if d is None or model not in d.model.values:
        return text

    def at(H):
        p = probability_at(d, model, key, H)
        return f"{tex_number(100 * p, 2)}\\,\\%" if np.isfinite(p) else "(outside the grid)"

    return (f"{text}: over {d.sizes['realization']} realizations (Sec.~\\ref{{sec:scan}}) "
            f"{at(H_chain)} are {key} at $H^*$ and {at(H_paper)} at the paper's $H = {tex_parameter(H_paper)}$")


def scan_always_reason(inputs: Inputs, measurement: Measurement, model: str, key: str, H: float) -> str:
    """Why "always ``key`` above H" differs: the energies >= H where it fails, or, where it holds,
    the realization's threshold in the disorder statistics."""
    if measurement["holds_above"]:
        return realization_threshold(inputs, model, key, measurement["star"], H)
    return f"not {key} at the scanned $H = $ {FORMATS['energies'](measurement['failing'])}"


def scan_alternation_reason(inputs: Inputs, measurement: Measurement, model: str, H: float) -> str:
    """Why the alternation above H differs: the realization's first delocalized energy, or too few
    changes of state above it."""
    first = measurement["first"]
    if np.isfinite(first) and not within_factor(first, H, inputs.criteria.tolerance.threshold_factor):
        return realization_threshold(inputs, model, "delocalized", first, H)
    return f"the state changes only {measurement['switches']} times above the first delocalized energy"


REASONS = {f.__name__: f for f in (follows, spread_of_values, scan_always_reason, scan_alternation_reason)}
