"""The catalogue of claims (src/chainchaos/paper/claims/catalogue.py) and the measures its rows call.

The catalogue is data: these tests check that every row can be evaluated (its measure exists and
takes its scenes and arguments, its scenes are the panel table's, its criteria references and
templates resolve, its statements exist), and the measures on small constructed inputs, each built
so that a wrong window, case or comparison fails.
"""

import inspect
import math
import os
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from chainchaos.paper import panels, statements
from chainchaos.paper.claims import framework as fw
from chainchaos.paper.claims import measures as ms
from chainchaos.paper.claims import quantities as q
from chainchaos.paper.claims.catalogue import CATALOGUE, STATEMENT_ROWS, statement_rows
from chainchaos.paper.claims.evidence import REASONS
from chainchaos.paper.criteria import Criteria

ROWS = (*CATALOGUE, *STATEMENT_ROWS)


def times(t_final=1e5, per_decade=20):
    return np.concatenate([[0.0], np.logspace(-1, np.log10(t_final), int(per_decade * (np.log10(t_final) + 1)) + 1)])


def inputs(scenes=None, criteria=None, **kw) -> fw.Inputs:
    return fw.Inputs(scenes=dict(scenes or {}), chain=kw.pop("chain", None), ensemble=kw.pop("ensemble", None),
                     criteria=criteria or Criteria(), site=kw.pop("site", 21), **kw)


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
    assert ms.plateau_largest(inp, "fput_H4", "participation").value == pytest.approx(0.7)
    late = inputs(inp.scenes, Criteria(plateau_start=10.0, plateau_end={"fput_H4": 4e4}))
    assert ms.plateau_median(late, "fput_H4", "eta").value == pytest.approx(0.1)


def test_the_largest_plateau_value_sees_one_sample_above_a_low_mean():
    """"P < 3 up to t ~ 2e2" holds at every sample: a short excursion above 3 breaks it, although
    the window's mean stays below 3."""
    t = times(1e5)
    p = np.where((t > 50) & (t < 70), 6.0, 2.0)
    inp = inputs({"hertz_H1.8": series(t, participation=p)},
                 Criteria(plateau_start=10.0, plateau_end={"hertz_H1.8": 200.0}, smoothing_decades=0.05))
    assert ms.plateau_largest(inp, "hertz_H1.8", "participation").value > 3.0
    assert q.window_mean(inp.scenes["hertz_H1.8"], "participation", 10.0, 200.0) < 3.0


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


def test_gaps_at_site_21_need_both_of_its_bonds_and_no_other():
    """"on the left and right side of site n=21 a gap often opens": bond 21 (beads 20, 21) and
    bond 22 (beads 21, 22) both open, and no bond farther away."""
    row = next(r for r in CATALOGUE if r.id == "gaps-H0.5-site21")
    t = times(1e5)
    cases = {"both": ({21: 1.0, 22: 10.0}, True), "left only": ({21: 1.0}, False),
             "right only": ({22: 1.0}, False), "one side and a neighbour": ({20: 1.0, 21: 1.0}, False),
             "both and farther": ({21: 1.0, 22: 1.0, 24: 1e3}, False), "none": ({}, False)}
    inp = inputs({name: gap_scene(t, bonds) for name, (bonds, _) in cases.items()})
    for name, (_, holds) in cases.items():
        m = ms.gaps_beside_site(inp, name)
        assert all(check.passes(m, inp.criteria) for check in row.checks) == holds, name
    both = ms.gaps_beside_site(inp, "both")
    assert (both["left_bond"], both["right_bond"]) == (21, 22) and both["left"] and both["right"]
    # gap_fraction 0.5 from t = 1 (bond 21) and from t = 10 (bond 22) on, over a run from 0 to 1e5
    assert both["left_time"] == pytest.approx(0.5 * (1e5 - 1) / 1e5, rel=1e-3)
    assert both["right_time"] == pytest.approx(0.5 * (1e5 - 10) / 1e5, rel=1e-3)
    assert not ms.gaps_beside_site(inp, "left only")["right"]


def test_gaps_cover_the_whole_lattice_only_when_every_bond_opens():
    """"covering eventually the whole lattice": every bond 1..N+1, the two wall bonds included,
    opens at some time; one bond that never opens (a wall bond or one inside) breaks it."""
    row = next(r for r in CATALOGUE if r.id == "gaps-H1.8-cover")
    t = times(1e5)
    every = {b: 1.0 + b for b in range(1, 42)}
    cases = {"every": (every, True), "all but bond 30": ({b: s for b, s in every.items() if b != 30}, False),
             "all but the right wall bond": ({b: s for b, s in every.items() if b != 41}, False),
             "all but the left wall bond": ({b: s for b, s in every.items() if b != 1}, False)}
    inp = inputs({name: gap_scene(t, bonds) for name, (bonds, _) in cases.items()})
    for name, (_, holds) in cases.items():
        m = ms.bond_coverage(inp, name)
        assert all(check.passes(m, inp.criteria) for check in row.checks) == holds, name
    assert ms.bond_coverage(inp, "every").value == 1.0 and ms.bond_coverage(inp, "every")["bonds"] == 41
    short = ms.bond_coverage(inp, "all but bond 30")
    assert short.value == pytest.approx(40 / 41) and short["never"] == 1 and list(short["never_bonds"]) == [30]
    assert not any(isinstance(v, str) and "gap_coverage" in v for c in row.checks for v in (c.reference, c.tolerance))


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


def test_scan_always_is_a_bound_strictly_above_the_papers_energy():
    E = np.array([0.5, 1.0, 1.8, 2.5, 4.0])
    inp = inputs({fw.ENERGY_SCAN: scan("00011", "00000", E)})
    at = ms.scan_always(inp, fw.ENERGY_SCAN, "hertz", "delocalized", 1.8)
    assert at["holds_above"] and (at["count"], at["above"]) == (2, 2) and at.value == 2.5  # 1.8 is not above 1.8
    above = ms.scan_always(inp, fw.ENERGY_SCAN, "hertz", "delocalized", 1.0)
    assert not above["holds_above"] and list(above["failing"]) == [1.8]
    # an invalid run (energy error above the bound) is neither: not a failure, and not a success
    ds = scan("00001", "00000", E)
    ds["valid"][0, 3] = 0
    invalid = ms.scan_always(inputs({fw.ENERGY_SCAN: ds}), fw.ENERGY_SCAN, "hertz", "delocalized", 1.8)
    assert invalid["holds_above"] and (invalid["count"], invalid["above"]) == (1, 1) and invalid.value == 4.0
    ds["valid"][0, 4] = 0
    assert not ms.scan_always(inputs({fw.ENERGY_SCAN: ds}), fw.ENERGY_SCAN, "hertz", "delocalized", 1.8).decided


def test_scan_onset_brackets_the_first_energy():
    E = np.array([0.25, 0.5, 1.0, 1.8, 2.5])
    onset = ms.scan_onset(inputs({fw.ENERGY_SCAN: scan("00101", "00000", E)}), fw.ENERGY_SCAN, "hertz",
                          "delocalized", 1.8)
    assert (onset.value, onset["first"], onset["before"], onset.case) == (1.0, 1.0, 0.5, "")
    lowest = ms.scan_onset(inputs({fw.ENERGY_SCAN: scan("11111", "00000", E)}), fw.ENERGY_SCAN, "hertz",
                           "delocalized", 1.8)
    assert (lowest.value, lowest["before"], lowest.case) == (0.25, 0.0, "lowest")
    never = ms.scan_onset(inputs({fw.ENERGY_SCAN: scan("00000", "00000", E)}), fw.ENERGY_SCAN, "hertz",
                          "delocalized", 1.8)
    assert never.value is None and never.case == "never" and never.decided  # 2.5 lies above the range
    short = ms.scan_onset(inputs({fw.ENERGY_SCAN: scan("0000", "0000", E[:4])}), fw.ENERGY_SCAN, "hertz",
                          "delocalized", 1.8)
    assert not short.decided  # nothing scanned above the range: it may set in higher up


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
    from chainchaos.records.io import chain_dataset

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


def test_an_ensemble_verdict_where_lambda_and_gali_disagree_is_undecided():
    """Hertz H = 3's ensemble: every orbit chaotic by Λ; by GALI_4 all (agree), or none (the
    statement is undecided, the claim too, and the text names both indicators' counts)."""
    from chainchaos.paper import verdicts as vd
    from chainchaos.paper.claims import evidence

    c = Criteria()
    t = np.concatenate([[0.0], np.logspace(0, 5, 101)])
    with np.errstate(divide="ignore", invalid="ignore"):
        chaotic_growth = 1e-3 * t + np.log1p(t)

    def ensemble(gali_crosses: bool):
        runs = [{"participation": np.full(t.size, 20.0), "log_growth": chaotic_growth, "eta": np.ones(t.size),
                 "energy_error": np.zeros(t.size), "u0": 1.0, "valid": True, "max_gaps": 3,
                 "log_gali": np.where(t > 1e3, -30.0, -1.0) if gali_crosses else np.full(t.size, -1.0)}
                for _ in range(8)]
        ds = vd.verdict_dataset("hertz_H3", t, runs, c, {"gali_order": 4})
        return inputs({"s": xr.Dataset()}, verdicts={"hertz_H3": ds})

    agree = ensemble(True)
    assert evidence.ensemble_verdict(agree, ["chaos-H3-hertz"]) == (fw.REPRODUCED, "$\\Lambda$ 8/8, $\\mathrm{GALI}_{4}$ 8/8")
    assert evidence.ensemble_verdict(agree, ["deloc-H3-hertz"]) == (fw.REPRODUCED, "8/8")  # P: one reading
    split = ensemble(False)
    verdict, text = evidence.ensemble_verdict(split, ["chaos-H3-hertz"])
    assert verdict == fw.UNDECIDED and text == "$\\Lambda$ 8/8, $\\mathrm{GALI}_{4}$ 0/8"
    assert evidence.indicators_disagree(split, ["chaos-H3-hertz", "deloc-H3-hertz"]) == ["chaos-H3-hertz"]
    # an onset is judged by Λ; GALI_4's crossing time is reported beside it (the first sample after 1e3)
    runs = [{"participation": np.full(t.size, 20.0), "log_growth": chaotic_growth, "eta": np.ones(t.size),
             "energy_error": np.zeros(t.size), "u0": 1.0, "valid": True, "max_gaps": 3,
             "log_gali": np.where(t > 1e3, -30.0, -1.0)} for _ in range(8)]
    onset = inputs({"s": xr.Dataset()}, verdicts={"hertz_H1.8": vd.verdict_dataset("hertz_H1.8", t, runs, c, {"gali_order": 4})})
    text = evidence.indicator_text(onset, "chaos-onset-H1.8-hertz")
    assert f"$\\mathrm{{GALI}}_{{4}}$ below its threshold from $t \\approx {t[t > 1e3][0]:.0f}$, median" in text


# ------------------------------------------------------------------ the paper's words

#: The paper's LaTeX source (a directory with a .tex file, or a text file holding it): by default
#: ../shared/paper beside the checkout, where CI puts it.
PAPER_DIR = Path(os.environ.get("CHAINCHAOS_PAPER_DIR", Path(__file__).resolve().parents[3] / "shared" / "paper"))
ROMAN = ("I", "II", "III", "IV", "V", "VI")


def normalise(tex: str) -> str:
    """LaTeX compared as words: without comments, whitespace, $, braces, ~ and thin spaces."""
    tex = re.sub(r"(?<!\\)%.*", "", tex).replace(r"\,", "")
    return re.sub(r"[\s${}~]", "", tex)


def paper_sections() -> dict[str, str]:
    """The paper's body by section ("II A", "III B 2", "IV"; before the first, "abstract"), figure
    environments left out (their captions float away from the text they sit in), normalised."""
    sources = [p.read_text() for p in sorted(PAPER_DIR.glob("*")) if p.suffix in (".tex", ".txt")]
    sources = [s for s in sources if r"\begin{document}" in s]
    if not sources:
        pytest.skip(f"the paper's LaTeX source is not in {PAPER_DIR} (set CHAINCHAOS_PAPER_DIR)")
    body = re.sub(r"(?<!\\)%.*", "", sources[0])
    body = re.sub(r"\\begin\{figure\*?\}.*?\\end\{figure\*?\}", "", body[body.index(r"\begin{document}"):],
                  flags=re.S)
    heads = list(re.finditer(r"\\(section|subsection|subsubsection)(\*?)\{[^}]*\}", body))
    sections, counters = {"abstract": normalise(body[:heads[0].start()])}, [0, 0, 0]
    for head, after in zip(heads, [*heads[1:], None]):
        level = ("section", "subsection", "subsubsection").index(head.group(1))
        counters[level] += 1
        counters[level + 1:] = [0] * (2 - level)
        label = "*" if head.group(2) else " ".join(
            [ROMAN[counters[0] - 1], "ABCDEFG"[counters[1] - 1] if level >= 1 else "",
             str(counters[2]) if level >= 2 else ""]).split()
        text = body[head.end():after.start() if after else len(body)]
        sections[label if isinstance(label, str) else " ".join(label)] = normalise(text)
    return sections


def cited_sections(where: str) -> list[str]:
    """The sections a row's ``where`` names: "Fig. 4(d), Sec. III B, IV" -> ["III B", "IV"]."""
    found = re.search(r"Sec\. ([IVX]+(?: [A-Z])?(?:, [IVX]+(?: [A-Z])?)*)", where)
    return found.group(1).split(", ") if found else []


def test_the_paper_is_read_by_section():
    sections = paper_sections()
    assert {"I", "II", "II A", "III", "III A", "III B", "III B 1", "III B 2", "III B 3", "III C", "IV"} <= set(sections)
    assert normalise(r"For energies $H > 1.8$ we have found") in sections["III B 2"]
    assert normalise(r"For energies $H > 1.8$ we have found") not in sections["III C"]
    assert cited_sections("Fig. 4(d), Sec. III B, IV") == ["III B", "IV"] and cited_sections("Fig. 1(a)") == []


@pytest.mark.parametrize("row", ROWS, ids=lambda row: row.id)
def test_every_row_quotes_the_paper_in_the_section_it_names(row):
    sections = paper_sections()
    cited = cited_sections(row.where)
    assert row.quote and cited, "a row quotes the paper's words and names their section"
    for passage in row.quote:
        inside = [label for label, text in sections.items() if normalise(passage) in text]
        assert inside, f"not in the paper: {passage!r}"
        assert any(label.split()[:len(c.split())] == c.split() for label in inside for c in cited), \
            f"{passage!r} is in section(s) {inside}, the row names {cited}"


def test_every_statement_of_the_paper_has_its_quote():
    from chainchaos.paper.claims.catalogue import STATEMENT_QUOTES

    assert set(STATEMENT_QUOTES) == {st.id for st in statements.STATEMENTS}
    text = "".join(paper_sections().values())
    for i, passages in STATEMENT_QUOTES.items():
        assert passages and all(normalise(p) in text for p in passages), i


# ------------------------------------------------------------------ the paper against itself

#: What the paper itself reports for each row, as the fields of the row's measurement (typed from
#: its text, independently of the catalogue); None where it prints no number a check could read
#: (the scan rows are fed the paper's energies in tests/paper/test_claims.py).
PAPER_VALUES = {
    "fig1-count": {"counts": [10]},                              # "about 10 strongly localized modes"
    "fig1-level": {"levels": [2.0]},                             # "<P> ~ 2"
    "fig1-limit": {"value": 0.0},                                # "reaches a limiting curve"
    "fig1-extended": {"value": 26.0},                            # "P ~ 26 [...] most extended mode"
    "mode34-P": {"value": 2.5},
    "mode34-site": {"value": 21},
    "overlaps": {"overlaps": [1.06, 1.06]},                      # "delta_{21,22} ~ 1.06"
    "u0": {"value": 1.01},
    "P-H0.25-hertz": {"value": 1.8},                             # "a constant value of P ~ 1.8"
    "P-H0.25-fput": {"value": 1.8},
    "P-H0.25-overlap": {"value": 0.0},                           # "almost overlap"
    "regular-H0.25-hertz": {"chaotic": False},
    "regular-H0.25-fput": {"chaotic": False},
    "PD-H0.25-hertz": {"value": 20.0},
    "PD-H0.25-fput": {"value": 20.0},
    "PD-H0.25-drop": {"second": 1.0},                            # FPUT's does not drop; Hertz's drop has no size
    "eta-H0.25-hertz": {"value": 1.0},                           # "eta = 1 and only slightly decreases"
    "eta-H0.25-fput": {"value": 1.0},
    "loc-H0.5-hertz": None,
    "chaos-H0.5-hertz": {"chaotic": True},
    "loc-H0.5-fput": None,
    "regular-H0.5-fput": {"chaotic": False},
    "dvd-H0.5-site21": {"value": 1.0},                           # "for the rest of the simulation"
    "gaps-H0.5-one": {"value": 1},                               # "no more than one gap"
    "gaps-H0.5-site21": {"left": True, "right": True, "distances": [0, 0]},  # "on the left and right side of site n=21"
    "spread-H1.8-level": None,                                   # "P < 3": a bound, no value
    "spread-H1.8-onset": {"value": 2e2},
    "spread-H1.8-saturation": {"value": 26.0},
    "spread-H1.8-until": {"value": 4e3},
    "mlce-H1.8": {"value": 1e-3},
    "chaos-H1.8-onset": {"value": 2e2},
    "gaps-H1.8-spread": {"value": 3e2},
    "gaps-H1.8-cover": {"value": 1.0, "never": 0},               # "covering eventually the whole lattice"
    "fput-regular-to-1.8": {"chaotic": [False, False, False]},
    "fput-H2.9": {"chaotic": True},
    "chaos-H2.9-onset": {"value": 4e3},
    "loc-H4-fput": None,
    "chaos-H4-fput": {"chaotic": True},
    "fput-H8.7381": {"chaotic": True},
    "eta-plateau-hertz_H1.8": {"value": 0.5},
    "eta-plateau-hertz_H3": {"value": 0.5},
    "eta-plateau-fput_H2.9": {"value": 0.7},
    "eta-plateau-fput_H4": {"value": 0.82},
    "eta-plateau-fput_H8.7381": {"value": 0.8},
    "eta-final-hertz_H1.8": {"excess": 0.0},                     # "approaches [...] <eta>"
    "eta-final-hertz_H3": {"excess": 0.0},
    "eta-final-fput_H2.9": {"excess": 0.0},
    "eta-final-fput_H8.7381": {"excess": 0.0},
    "eta-final-fput_H4": None,                                   # not at equipartition: no value
    "scan-hertz-deloc": None,
    "scan-hertz-chaos": None,
    "scan-hertz-onset": None,
    "scan-fput-chaos": None,
    "scan-fput-alternation": {"first": 2.9, "switches": 2},       # 2.9 delocalized, 4 localized, 8.7381 delocalized
}


def test_every_row_says_what_the_paper_reports_for_it():
    assert set(PAPER_VALUES) == {row.id for row in CATALOGUE}


@pytest.mark.parametrize("row", [row for row in CATALOGUE if PAPER_VALUES[row.id] is not None],
                         ids=lambda row: row.id)
def test_the_papers_own_values_pass_the_rows_checks(row):
    """A row checked against the paper's value passes at that value: the paper's numbers are
    the references of the checks and its tolerances contain them."""
    values = {k: np.asarray(v) if isinstance(v, list) else v for k, v in PAPER_VALUES[row.id].items()}
    measurement = fw.Measurement(values.get("value"), values)
    checked = [check for check in row.checks if check.field in values]
    assert checked, "the paper's values reach none of the row's checks"
    for check in checked:
        assert check.passes(measurement, Criteria()), (check, values)


def test_the_papers_two_times_for_the_hertz_onset_agree_under_the_tolerance():
    """Sec. III B has P start to grow after t ~ 2e2, Sec. III C at t ~ 3e2, together with the
    gaps: each of the paper's times passes the other's check."""
    rows = {row.id: row for row in CATALOGUE}
    c = Criteria()
    for row, other in (("spread-H1.8-onset", 3e2), ("gaps-H1.8-spread", 2e2), ("chaos-H1.8-onset", 3e2)):
        assert all(check.passes(fw.Measurement(other), c) for check in rows[row].checks), row


def test_the_windows_before_an_onset_end_before_the_earliest_onset_the_tolerance_accepts():
    """A level the paper reads before something happens at time T ("P < 3 up to t ~ 2e2", "eta
    has a plateau [...] then falls at t ~ 5e3") is measured up to plateau_end <= T / time_factor,
    so an onset the time tolerance still calls "at T" cannot fall inside the window."""
    c = Criteria()
    paper_times = {"hertz_H1.8": 2e2, "fput_H2.9": 5e3, "fput_H4": 1e3, "fput_H8.7381": 1e4}
    for scene, T in paper_times.items():
        assert c.plateau_end[scene] * c.tolerance.time_factor <= T * (1 + 1e-12), scene
