"""The catalogue of claims (src/chainchaos/paper/claims/catalogue.py) and the measures its rows call.

The catalogue is data: these tests check that every row can be evaluated (its measure exists and
takes its scenes and arguments, its scenes are the panel table's, its criteria references and
templates resolve, its statements exist), and the measures on small constructed inputs, each built
so that a wrong window, case or comparison fails.
"""

import inspect
import math
import re

import numpy as np
import pytest
import xarray as xr

from chainchaos.paper import panels, statements
from chainchaos.paper.claims import framework as fw
from chainchaos.paper.claims import measures as ms
from chainchaos.paper.claims.catalogue import CATALOGUE, STATEMENT_ROWS, statement_rows
from chainchaos.paper.claims.evidence import REASONS
from chainchaos.paper.criteria import Criteria

ROWS = (*CATALOGUE, *STATEMENT_ROWS)


def times(t_final=1e5, per_decade=20):
    return np.concatenate([[0.0], np.logspace(-1, np.log10(t_final), int(per_decade * (np.log10(t_final) + 1)) + 1)])


def inputs(scenes=None, criteria=None, **kw) -> fw.Inputs:
    return fw.Inputs(dict(scenes or {}), kw.pop("chain", None), kw.pop("ensemble", None), criteria or Criteria(),
                     kw.pop("site", 21), **kw)


# ------------------------------------------------------------------ the catalogue


def test_ids_are_unique():
    ids = [row.id for row in ROWS]
    assert len(set(ids)) == len(ids) >= 50


@pytest.mark.parametrize("row", ROWS, ids=lambda row: row.id)
def test_every_row_names_a_measure_that_takes_its_scenes_and_arguments(row):
    assert row.measure in ms.MEASURES, row.measure
    inspect.signature(ms.MEASURES[row.measure]).bind(None, *row.scenes, **row.args)


@pytest.mark.parametrize("row", ROWS, ids=lambda row: row.id)
def test_every_row_reads_scenes_of_the_panel_table_and_names_existing_statements(row):
    assert set(row.scenes) <= {*panels.scenes(), fw.ENERGY_SCAN}
    assert set(row.statements) <= {st.id for st in statements.STATEMENTS}
    if not isinstance(row.reason, str):
        assert row.reason[0] in REASONS


@pytest.mark.parametrize("row", ROWS, ids=lambda row: row.id)
def test_every_check_and_criterion_resolves_against_the_criteria(row):
    c = Criteria()
    for check in row.checks:
        assert check.comparison in fw.COMPARISONS
        for value in (check.reference, check.tolerance):
            assert value is None or isinstance(fw.resolve(value, c), (int, float, bool, np.bool_))
    t = fw.resolve(row.t_required, c)
    assert t is None or t > 0
    context = {"c": c, "tol": c.tolerance, "target": row.target, "scan_criterion": inputs().scan_criterion(),
               **row.args}
    # a criterion reads only the criteria, the row's arguments and the paper's number: no measurement
    assert not re.search(r"(?<!\\cc)\{(c|tol|target|scan_criterion)\b", fw.render(row.criterion, context))


def test_every_statement_of_the_paper_is_the_subject_of_a_row():
    covered = {i for row in ROWS for i in row.statements}
    assert covered == {st.id for st in statements.STATEMENTS}
    assert not {i for row in STATEMENT_ROWS for i in row.statements} & {i for row in CATALOGUE for i in row.statements}
    assert statement_rows(()) and len(statement_rows(())) == len(statements.STATEMENTS)


# ------------------------------------------------------------------ framework


def test_criteria_references():
    c = Criteria(plateau_end={"fput_H4": 500.0})
    assert fw.resolve("localized_p_max", c) == c.localized_p_max
    assert fw.resolve("tolerance.time_factor", c) == c.tolerance.time_factor
    assert fw.resolve("2e2 * tolerance.time_factor", c) == 2e2 * c.tolerance.time_factor
    assert fw.resolve("1 - tolerance.participation_relative", c) == 1 - c.tolerance.participation_relative
    assert fw.resolve("plateau_end[fput_H4]", c) == 500.0 and math.isnan(fw.resolve("plateau_end[hertz_H3]", c))
    assert fw.resolve(3.5, c) == 3.5 and fw.resolve(None, c) is None
    with pytest.raises(ValueError, match="localized_p_mx"):
        fw.resolve("localized_p_mx", c)
    with pytest.raises(ValueError, match="allowed is"):
        fw.resolve("2 + localized_p_max", c)


def test_checks_compare_every_element_and_read_criteria():
    c = Criteria()
    m = fw.Measurement(1.9, {"levels": np.array([2.05, 1.95]), "off": np.array([2.05, 2.2])})
    assert fw.Check("levels", "near", 2.0, "tolerance.mode_participation").passes(m, c)
    assert not fw.Check("off", "near", 2.0, "tolerance.mode_participation").passes(m, c)
    assert fw.Check("value", "near_relative", 1.8, "tolerance.participation_relative").passes(m, c)
    assert not fw.Check("value", "near_relative", 1.6, "tolerance.participation_relative").passes(m, c)
    assert fw.Check("value", "within_factor", 3.0, 2.0).passes(m, c)
    assert not fw.Check("value", "within_factor", 4.0, 2.0).passes(m, c)
    assert not fw.Check("value", "within_factor", 1.0, 2.0).passes(fw.Measurement(None), c)  # never happened
    assert fw.Check("value", "<", "1 - tolerance.participation_relative").passes(fw.Measurement(0.85), c)
    assert not fw.Check("value", "<", "1 - tolerance.participation_relative").passes(fw.Measurement(0.95), c)


def test_templates_print_numbers_by_spec_and_none_as_dashes():
    c = Criteria()
    text = fw.render("$P = {value:tex}$ within {tol.participation_relative:param%}\\,\\% ({x:math2}, {y:tex}, "
                     "{bonds:bonds}; {none:bonds})", {"value": 26.94, "tol": c.tolerance, "x": 0.1234, "y": None,
                                                     "bonds": [21, 22], "none": []})
    assert text == "$P = 26.9$ within 10\\,\\% ($0.12$, --, 21, 22; none)"
    assert fw.render(fw.literal(r"\cc{crit.x}"), {}) == r"\cc{crit.x}"


# ------------------------------------------------------------------ measures on small inputs


def series(t, name="s", **variables) -> xr.Dataset:
    return xr.Dataset({k: ("time", np.asarray(v, dtype=float)) for k, v in variables.items()}, coords={"time": t})


def test_final_value_uses_the_narrower_window_for_eta():
    t = times(1e5)
    step = np.where(t >= 10**4.5, 0.2, 0.8)  # eta falls at 10^4.5: inside the last decade, outside the last 0.25
    scene = series(t, eta=step, participation=step)
    inp = inputs({"s": scene})
    assert ms.final_value(inp, "s", "eta").value == pytest.approx(0.2)
    assert 0.2 < ms.final_value(inp, "s", "participation").value < 0.8


def test_plateau_measures_read_the_scene_plateau_end():
    t = times(1e5)
    eta = np.where(t < 400, 0.7, 0.1)
    inp = inputs({"fput_H4": series(t, eta=eta, participation=eta)},
                 Criteria(plateau_start=10.0, plateau_end={"fput_H4": 300.0}))
    median = ms.plateau_median(inp, "fput_H4", "eta")
    assert median.value == pytest.approx(0.7) and (median["start"], median["end"]) == (10.0, 300.0)
    assert ms.plateau_average(inp, "fput_H4", "participation").value == pytest.approx(0.7)
    late = inputs(inp.scenes, Criteria(plateau_start=10.0, plateau_end={"fput_H4": 4e4}))
    assert ms.plateau_median(late, "fput_H4", "eta").value == pytest.approx(0.1)


def test_two_scene_measures():
    t = times(1e5)
    early = (t >= 1e2) & (t <= 1e3)
    inp = inputs({"a": series(t, participation=np.full(t.size, 2.0), dvd_participation=np.where(early, 20.0, 10.0)),
                  "b": series(t, participation=np.full(t.size, 3.0), dvd_participation=np.full(t.size, 20.0))})
    diff = ms.relative_difference(inp, "a", "b", "participation")
    assert diff.value == pytest.approx(1 / 2.5) and (diff["first"], diff["second"]) == (2.0, 3.0)
    ratios = ms.early_and_late(inp, "a", "b", "dvd_participation", 1e2, 1e3)
    assert ratios.value == pytest.approx(0.5, rel=0.05) and ratios["second"] == pytest.approx(1.0)


def test_eta_final_gives_the_excess_over_equipartition():
    t = times(1e5)
    scene = xr.Dataset({"eta": ("time", np.full(t.size, 0.3), {"equipartition_value": 0.12})}, coords={"time": t})
    m = ms.eta_final(inputs({"s": scene}), "s")
    assert m.value == pytest.approx(0.3) and m["equipartition"] == 0.12 and m["excess"] == pytest.approx(0.18)


def gap_scene(t, open_bonds, N=40):
    frac = np.zeros((t.size, N + 1))
    for bond, start in open_bonds.items():
        frac[t >= start, bond - 1] = 0.5
    P = np.where(t < 50, 2.0, 20.0)
    return xr.Dataset({"gap_fraction": (("time", "bond"), frac), "participation": ("time", P)},
                      coords={"time": t, "bond": np.arange(1, N + 2)})


def test_gap_measures_and_their_cases():
    t = times(1e4)
    inp = inputs({"beside": gap_scene(t, {21: 1.0, 22: 1.0}), "far": gap_scene(t, {21: 1.0, 30: 300.0}),
                  "none": gap_scene(t, {})})
    beside = ms.gaps_beside_site(inp, "beside")
    assert beside.value == 0.0 and list(beside["bonds"]) == [21, 22] and beside["opened"] == 2
    assert ms.gaps_beside_site(inp, "far").value == 8.0  # bond 30 joins beads 29 and 30
    assert ms.gaps_beside_site(inp, "none").value is None
    far = ms.gap_spread(inp, "far")
    assert far.value == pytest.approx(t[t >= 300][0]) and far.case == "with_onset" and far["onset"] is not None
    assert ms.gap_spread(inp, "beside").case == "never"
    no_p = inputs({"far": inp.scenes["far"].drop_vars("participation")})
    assert ms.gap_spread(no_p, "far").case == "" and ms.gap_spread(no_p, "far")["onset"] is None
    assert ms.bond_coverage(inp, "far").value == pytest.approx(2 / 41)


def scan(hertz: str, fput: str, E=None) -> xr.Dataset:
    E = np.geomspace(0.1, 10, 12) if E is None else E
    flags = np.array([[int(ch) for ch in f] for f in (hertz, fput)], dtype=np.int8)
    return xr.Dataset({"delocalized": (("model", "energy"), flags), "chaotic": (("model", "energy"), flags),
                       "valid": (("model", "energy"), np.ones_like(flags))},
                      coords={"model": ["hertz", "fput"], "energy": E}, attrs={"p_delocalized": 10.0})


def test_scan_measures():
    # grid 0.1 0.152 0.231 0.351 0.534 0.811 1.23 1.87 2.85 4.33 6.58 10
    inp = inputs({fw.ENERGY_SCAN: scan("000000011011", "000000001011")})
    always = ms.scan_always(inp, fw.ENERGY_SCAN, "hertz", "delocalized", 1.8)
    assert always.value == pytest.approx(6.58, abs=0.01) and always.decided and not always["holds_above"]
    assert (always["count"], always["above"]) == (4, 5) and list(np.round(always["failing"], 2)) == [4.33]
    nowhere = ms.scan_always(inputs({fw.ENERGY_SCAN: scan("000000011110", "0" * 12)}), fw.ENERGY_SCAN, "hertz",
                             "delocalized", 1.8)
    assert nowhere.value is None and nowhere.case == "nowhere"
    beyond = ms.scan_always(inp, fw.ENERGY_SCAN, "hertz", "delocalized", 20.0)
    assert not beyond.decided  # no scanned energy reaches H
    alternation = ms.scan_alternation(inp, fw.ENERGY_SCAN, "fput")
    assert alternation.value == pytest.approx(2.85, abs=0.01) and alternation["switches"] == 2
    assert list(np.round(alternation["localized"], 2)) == [4.33]
    never = ms.scan_alternation(inputs({fw.ENERGY_SCAN: scan("0" * 12, "0" * 12)}), fw.ENERGY_SCAN, "fput")
    assert never.value is None and never.case == "never" and never["switches"] == 0


def ensemble(curves: dict) -> xr.Dataset:
    alphas = sorted(curves)
    return xr.Dataset({"mean_participation": (("alpha", "rank"), np.array([curves[a] for a in alphas]))},
                      coords={"alpha": alphas, "rank": np.arange(1, 41)})


def test_ensemble_measures_look_at_the_alphas_from_4_on():
    low = np.linspace(40, 30, 40)
    strong = np.r_[np.linspace(28, 4, 30), np.full(10, 2.1)]
    stronger = np.r_[np.linspace(27, 4, 28), np.full(12, 2.3)]
    chain = xr.Dataset(attrs={"alpha": 5.0})
    inp = inputs(chain=chain, ensemble=ensemble({1.0: low, 4.0: strong, 5.0: stronger}))
    counts = ms.localized_mode_counts(inp, 4.0)
    assert counts.value == 10 and (counts["lowest"], counts["highest"]) == (10, 12)
    assert (counts["alpha_low"], counts["alpha_high"]) == (4.0, 5.0)
    levels = ms.localized_levels(inp, 4.0)
    assert levels.value == pytest.approx(2.1) and levels["period_averaged"] is None
    assert ms.limiting_curve(inp, 4.0).decided
    only_low = inputs(chain=chain, ensemble=ensemble({1.0: low, 2.0: low}))
    assert ms.localized_mode_counts(only_low, 4.0) is None and ms.localized_levels(only_low, 4.0) is None
    assert not ms.limiting_curve(only_low, 4.0).decided


def test_chain_measures():
    from chainchaos import random_chain
    from chainchaos.output.io import chain_dataset

    chain = chain_dataset(random_chain(879, 5.0))
    inp = inputs(chain=chain)
    overlaps = ms.excited_overlaps(inp, 1.06)
    assert overlaps.value == pytest.approx(np.max(np.abs(chain["delta"].values[20:22] - 1.06)))
    assert ms.mode_peak(inp, 34).value == 21
    P = ms.mode_participation(inp, 34)
    assert P.value == chain["mode_participation"].values[33]
    assert P["period_averaged"] == chain["mode_participation_period_averaged"].values[33]


def test_ensemble_statement_counts_orbits_and_takes_the_median():
    verdicts = xr.Dataset({"measured": (("statement", "lane"), [[1.0, 0.0, 1.0, np.nan], [np.nan] * 4])},
                          coords={"statement": ["chaos-x", "onset-x"], "lane": np.arange(4)})
    inp = inputs({"s": xr.Dataset()}, verdicts={"s": verdicts})
    m = ms.ensemble_statement(inp, "s", "chaos-x")
    assert m.value == 1.0 and (m["chaotic"], m["orbits"]) == (2, 3)
    none = ms.ensemble_statement(inp, "s", "onset-x")
    assert none.value is None and math.isnan(none["median"])
