"""The claims table: every row of the catalogue measured on the stored results, with its verdict."""

import xarray as xr

from chainchaos.paper.claims.catalogue import CATALOGUE, STATEMENT_ROWS
from chainchaos.paper.claims.evidence import (
    REASONS,
    ensemble_verdict,
    indicators_disagree,
    search_evidence,
    statement_result,
)
from chainchaos.paper.claims.framework import (
    DIFFERS,
    ENERGY_SCAN,
    REPRODUCED,
    UNDECIDED,
    UNTESTABLE,
    Claim,
    ClaimRow,
    Inputs,
    decide,
    render,
    resolve,
)
from chainchaos.paper.claims.measures import MEASURES
from chainchaos.paper.criteria import Criteria
from chainchaos.records.formatting import tex_number, tex_parameter


def _context(row: ClaimRow, inputs: Inputs, measurement=None) -> dict:
    c = inputs.criteria
    context = {"c": c, "tol": c.tolerance, "target": row.target, "scan_criterion": inputs.scan_criterion(),
               **row.args}
    if measurement is not None:
        context.update(measurement.details, value=measurement.value)
    return context


def _measured_text(row: ClaimRow, measurement, context: dict) -> str:
    if measurement is None:
        return "--"
    template = row.measured if isinstance(row.measured, str) else row.measured[measurement.case]
    return render(template, context)


def _reason_differs(row: ClaimRow, inputs: Inputs, measurement) -> str:
    if isinstance(row.reason, str):
        return row.reason
    name, *args = row.reason
    return REASONS[name](inputs, measurement, *args)


def evaluate_row(row: ClaimRow, inputs: Inputs) -> Claim:
    """One row of the catalogue measured on ``inputs``: its :class:`Claim`.

    A row whose scenes or variables are missing is not testable. Otherwise its measure reads the
    results; the verdict is the ensemble verdict of its statements where there is one, else it
    follows from the checks (:func:`framework.decide`, with the time the statement needs)."""
    c = inputs.criteria
    scenes = row.scenes
    t_required = resolve(row.t_required, c)
    criterion = render(row.criterion, _context(row, inputs))
    if scenes and not inputs.has(scenes, *row.variables):
        missing = [n for n in scenes if n not in inputs.scenes]
        what = (f"scene(s) {', '.join(missing)} missing" if missing
                else f"the scenes lack {', '.join(row.variables)}")
        return Claim(id=row.id, where=row.where, statement=row.statement, paper=row.paper, measured=None,
                     measured_text="--", unit=row.unit, criterion=criterion, verdict=UNTESTABLE,
                     reason=what, scenes=scenes, max_energy_error=inputs.max_energy_error(scenes),
                     t_final=inputs.t_final(scenes), t_required=t_required)
    measurement = MEASURES[row.measure](inputs, *scenes, **row.args)
    context = _context(row, inputs, measurement)
    measured = None if measurement is None else measurement.value
    t_final = inputs.t_final(scenes) if scenes else None
    ensemble = ensemble_verdict(inputs, row.statements) if row.statements else None
    fraction = ""
    if ensemble is not None:
        verdict, fraction = ensemble
        criterion = (f"{criterion}; decided on the ensemble of perturbed orbits: each statement on at "
                     f"least {tex_parameter(100 * c.agreement)}\\,\\% of them")
    else:
        decidable = measurement is not None and measurement.decided and row.checks
        passed = all(check.passes(measurement, c) for check in row.checks) if decidable else None
        verdict = decide(passed, t_final, t_required, row.refutable_early)
        if verdict in (REPRODUCED, DIFFERS) and measurement.split:
            verdict = UNDECIDED
    reason = ""
    if verdict == UNDECIDED and measurement is not None and measurement.split:
        reason = measurement.split
    elif verdict == UNTESTABLE:
        reason = (f"needs the run to reach $t = {tex_parameter(t_required)}$; it ends at $t = {tex_number(t_final)}$"
                  if t_final is not None and t_required is not None and t_final < t_required
                  else "nothing to measure")
    elif verdict == UNDECIDED:
        split = ", ".join(f"\\texttt{{{i}}}" for i in indicators_disagree(inputs, row.statements))
        reason = (f"the two chaos indicators disagree on {split} "
                  f"({fraction} of the orbits say it holds): whether the orbits are chaotic by $t_\\mathrm{{end}}$ "
                  f"depends on the indicator" if split else
                  f"the perturbed orbits disagree ({fraction} satisfy it): the answer depends on the orbit, "
                  f"not only on the scene")
    elif verdict == DIFFERS:
        evidence = search_evidence(inputs, row.statements)
        reason = "; ".join(x for x in (_reason_differs(row, inputs, measurement), evidence) if x) or \
            "the measured value lies outside the tolerance"
    return Claim(id=row.id, where=row.where, statement=row.statement, paper=row.paper, measured=measured,
                 measured_text=_measured_text(row, measurement, context), unit=row.unit, criterion=criterion,
                 verdict=verdict, reason=reason, scenes=scenes,
                 max_energy_error=inputs.max_energy_error(scenes), t_final=t_final, t_required=t_required,
                 fraction=fraction, statements=tuple(row.statements))


def evaluate_claims(scenes: dict, chain: xr.Dataset, ensemble: xr.Dataset,
                    criteria: Criteria | None = None, excited_site: int = 21,
                    energy_scan: xr.Dataset | None = None, verdicts: dict | None = None,
                    search: xr.Dataset | None = None, disorder: xr.Dataset | None = None) -> list[Claim]:
    """Every claim of the catalogue, measured on ``scenes`` (scene name -> Dataset), the chain file,
    the ensemble file and the energy scan (the threshold statements; without it they are not
    testable), with the qualitative verdicts decided on the ensemble verdicts (scene name ->
    Dataset of ``verdicts.verdict_dataset``) where given, and the search (``stages.merge``) to
    name what no candidate avoids; then a row for every other statement of ``statements.STATEMENTS``
    that has an ensemble verdict."""
    if energy_scan is not None:
        scenes = {**scenes, ENERGY_SCAN: energy_scan}
    inputs = Inputs(scenes=scenes, chain=chain, ensemble=ensemble, criteria=criteria or Criteria(), site=excited_site,
                    verdicts=dict(verdicts or {}), search=search, disorder=disorder)
    rows = [*CATALOGUE, *(row for row in STATEMENT_ROWS if statement_result(inputs, row.statements[0]) is not None)]
    return [evaluate_row(row, inputs) for row in rows]
