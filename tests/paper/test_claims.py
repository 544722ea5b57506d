"""The claims table (src/chainchaos/paper/claims/) and the manuscript build.

Unit tests run the measurements on small constructed Datasets, each built so that a wrong
criterion fails; the slow tests use the quick-scale results of the `quick` fixture (conftest.py),
whose pipeline run already built the manuscript.
"""

import csv
import itertools
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from conftest import QUICK_MANUSCRIPT

from chainchaos import random_chain
from chainchaos.paper import claims as cl
from chainchaos.paper import panels
from chainchaos.paper.claims import quantities as q
from chainchaos.paper.claims import writers
from chainchaos.paper.criteria import Criteria
from chainchaos.records.io import chain_dataset, ensemble_dataset

ROOT = Path(__file__).resolve().parents[2]


def times(t_final=1e5, per_decade=20):
    return np.concatenate([[0.0], np.logspace(-1, np.log10(t_final), int(per_decade * (np.log10(t_final) + 1)) + 1)])


def series(t, **variables) -> xr.Dataset:
    return xr.Dataset({k: ("time", np.asarray(v, dtype=float)) for k, v in variables.items()}, coords={"time": t})


# ------------------------------------------------------------------ measurements


def test_final_mean_uses_only_the_last_decade():
    t = times(1e5)
    ds = series(t, participation=np.where(t >= 1e4, 26.0, 2.0))
    assert q.final_mean(ds, "participation", 1.0) == pytest.approx(26.0)
    assert 2.0 < q.final_mean(ds, "participation", 2.0) < 26.0


def test_spreading_onset_is_when_the_smoothed_p_doubles_after_the_transient():
    t = times(1e5)
    wiggle = 0.8 * np.sin(7 * np.arange(t.size))  # raw P oscillates between 1.2 and 2.8 before the onset
    step = series(t, participation=np.where(t < 200, 2.0, 20.0))
    assert q.spreading_onset(step, factor=2.0, smoothing_decades=0.01, t_ref=10.0) == pytest.approx(t[t >= 200][0])
    ds = series(t, participation=np.where(t < 200, 2.0 + wiggle, 20.0))
    smoothed = q.spreading_onset(ds, factor=2.0, smoothing_decades=0.5, t_ref=10.0)
    assert 200 / 10**0.25 <= smoothed <= 200
    # an early rise before t_ref is the transient, not the onset
    early = series(t, participation=np.where(t < 5, 1.5, np.where(t < 200, 4.0, 20.0)))
    assert q.spreading_onset(early, 2.0, 0.01, 10.0) == pytest.approx(t[t >= 200][0])
    assert q.spreading_onset(series(t, participation=np.full(t.size, 2.0)), 2.0, 0.5) is None


def test_saturation_time_reaches_the_fraction_of_the_final_value():
    t = times(1e5)
    P = np.clip(2 + 24 * (np.log10(np.maximum(t, 1e-9)) - 2) / 2, 2, 26)  # 2 at 1e2 rising to 26 at 1e4
    ds = series(t, participation=P)
    tsat = q.saturation_time(ds, 0.9, smoothing_decades=0.01)
    assert 3e3 < tsat < 1e4


def test_regular_and_chaotic_orbits_are_told_apart_by_the_paper_reading_of_lambda():
    t = times(1e5)
    c = Criteria()
    with np.errstate(divide="ignore", invalid="ignore"):
        regular = series(t, mlce=np.log(1 + t) / t)                  # |v| ~ t
        slow_regular = series(t, mlce=0.3 * np.log(1 + t) / t)       # |v| ~ t^0.3: slope near -0.7
        late_regular = series(t, mlce=np.log(1 + 0.3 * t / (1 + 1e-4 * t)) / t)  # |v| ~ 1 -> linear growth late
        chaotic = series(t, mlce=1e-3 + np.log(1 + t) / t)           # |v| ~ t e^(1e-3 t)
    assert q.growth_excess(regular) == pytest.approx(0.0, abs=1e-4)
    assert not q.scene_chaotic(regular, c) and not q.scene_chaotic(slow_regular, c)
    assert not q.scene_chaotic(late_regular, c)
    assert q.scene_chaotic(chaotic, c)
    assert q.growth_excess(chaotic) == pytest.approx(90.0, rel=1e-3)  # 1e-3 over 1e4..1e5
    assert q.mlce_slope(regular) < -0.8 and q.mlce_slope(chaotic) > -0.5
    assert q.final_mlce(chaotic) == pytest.approx(1e-3 + np.log(1 + 1e5) / 1e5)


def test_chaos_onset_dates_the_departure_from_the_regular_law():
    t = times(1e5)
    c = Criteria()
    with np.errstate(divide="ignore", invalid="ignore"):
        # regular ~ 1/t until t_c = 1e3, then ln|v| grows linearly: Lambda -> 1e-2
        log_v = np.where(t < 1e3, np.log(1 + t), np.log(1 + 1e3) + 1e-2 * (t - 1e3))
        ds = series(t, mlce=log_v / t)
    onset = q.chaos_onset(ds, c)
    assert 1e3 / 3 < onset < 3e3
    with np.errstate(divide="ignore", invalid="ignore"):
        assert q.chaos_onset(series(t, mlce=np.log(1 + t) / t), c) is None


def gap_scene(t, open_bonds_by_time, N=40):
    """gap_fraction(time, bond): 0.5 on the listed bonds from the given time on."""
    frac = np.zeros((t.size, N + 1))
    for bond, start in open_bonds_by_time.items():
        frac[t >= start, bond - 1] = 0.5
    return xr.Dataset({"gap_fraction": (("time", "bond"), frac),
                       "gap_open": (("time", "bond"), (frac > 0).astype(np.int8)),
                       "n_gaps": ("time", (frac > 0).sum(axis=1)),
                       "n_gaps_max": ("time", np.minimum((frac > 0).sum(axis=1), 1))},
                      coords={"time": t, "bond": np.arange(1, N + 2)})


def test_gap_measurements():
    t = times(1e4)
    ds = gap_scene(t, {21: 1.0, 22: 5.0, 25: 300.0})
    assert list(q.bonds_ever_open(ds)) == [21, 22, 25]
    assert list(q.bond_distance(np.array([19, 20, 21, 22, 23, 24]), 21)) == [2, 1, 0, 0, 1, 2]
    assert q.gap_spread_time(ds, 21, 2) == pytest.approx(t[t >= 300][0])
    assert q.gap_spread_time(gap_scene(t, {21: 1.0, 23: 1.0}), 21, 2) is None
    assert q.max_simultaneous_gaps(ds) == 1  # n_gaps_max (checked every step) wins over n_gaps
    assert q.max_simultaneous_gaps(ds.drop_vars("n_gaps_max")) == 3


def test_dvd_site_fraction_counts_samples_peaked_near_the_site():
    t = times(1e5)
    w = np.full((t.size, 40), 1e-3)
    peaks = np.where(np.arange(t.size) % 4 == 0, 30, 21)  # a quarter of the samples peak at 30
    w[np.arange(t.size), peaks - 1] = 1.0
    ds = xr.Dataset({"dvd": (("time", "site"), w)}, coords={"time": t, "site": np.arange(1, 41)})
    assert q.dvd_site_fraction(ds, 21, 1, 1.0) == pytest.approx(0.75, abs=0.06)


def test_verdicts_follow_the_rules():
    assert cl.decide(True) == cl.REPRODUCED
    assert cl.decide(False) == cl.DIFFERS
    assert cl.decide(None) == cl.UNTESTABLE
    assert cl.decide(True, t_final=1e3, t_required=1e5) == cl.UNTESTABLE
    assert cl.decide(False, t_final=1e3, t_required=1e5) == cl.UNTESTABLE
    assert cl.decide(False, t_final=1e3, t_required=1e5, refutable_early=True) == cl.DIFFERS
    assert cl.decide(True, t_final=1e3, t_required=1e5, refutable_early=True) == cl.UNTESTABLE
    assert cl.decide(True, t_final=1e5, t_required=1e5) == cl.REPRODUCED


def test_ensemble_and_chain_measurements():
    ens = xr.Dataset({"mean_participation": (("alpha", "rank"), np.array([
        np.linspace(40, 30, 40), np.r_[np.linspace(28, 4, 30), np.full(10, 2.1)],
        np.r_[np.linspace(27, 4, 30), np.full(10, 2.2)]]))},
        coords={"alpha": [1.0, 4.0, 5.0], "rank": np.arange(1, 41)})
    assert q.localized_mode_count(ens, 5.0, 3.0) == 10
    assert q.localized_level(ens, 4.0, 10) == pytest.approx(2.1)
    assert q.most_extended(ens, 5.0) == pytest.approx(27.0)
    assert 0 < q.limiting_curve_deviation(ens, 4.0) < 0.1
    chain = chain_dataset(random_chain(879, 5.0))
    h = q.mode_energy_profile(chain, 34)
    assert h.sum() == pytest.approx(1.0)
    assert 1.0 / np.sum(h**2) == pytest.approx(float(chain["mode_participation"].values[33]))
    assert q.mode_peak_site(chain, 34) == 21


def test_interior_mode_participation_is_at_least_two():
    """The bound the manuscript states for the potential convention: no interior bead holds more
    than half of a mode's energy, so P >= 2 (a mode's energy on a wall bond is the exception)."""
    for seed in range(20):
        chain = chain_dataset(random_chain(seed, 5.0))
        for mode in range(1, 41):
            h = q.mode_energy_profile(chain, mode)
            if np.argmax(h) not in (0, 39):
                assert h.max() <= 0.5 + 1e-12


def test_taylor_sign_barrier_blocks_the_high_fput_energies():
    taylor = random_chain(879, 5.0).with_k4_sign(-1.0)
    barrier = q.taylor_sign_barrier(taylor, 21)
    assert 0.5 < barrier < 8.7381
    from chainchaos.errors import ParameterError
    from chainchaos.system.initial import initial_displacement

    initial_displacement("fput", taylor, 0.9 * barrier, 21)
    with pytest.raises(ParameterError):
        initial_displacement("fput", taylor, 1.1 * barrier, 21)


# ------------------------------------------------------------------ the table on synthetic scenes


def synthetic_scenes(t_final=1e5, u0=1.0410, hertz_spreads=True):
    """Every scene of the paper with every variable a claim reads, shaped like the paper's story."""
    t = times(t_final)
    out = {}
    for name, scene in panels.scenes().items():
        spreading = (scene.model == "hertz" and scene.energy >= 1.8 and hertz_spreads) or \
                    (scene.model == "fput" and scene.energy in (2.9, 8.7381))
        chaotic = spreading or (scene.model == "hertz" and scene.energy == 0.5) or (scene.model == "fput"
                                                                                    and scene.energy == 4.0)
        P = np.where(spreading & (t > 2e2), 26.0, 1.8)
        with np.errstate(divide="ignore", invalid="ignore"):
            mlce = np.log(1 + t) / t + (1e-3 if chaotic else 0.0)
        eta = np.where(spreading & (t > 5e3), 0.12, 0.95 if scene.energy < 1 else 0.6)
        w = np.full((t.size, 40), 1e-3)
        w[:, 20] = 1.0
        ds = xr.Dataset({"participation": ("time", P), "mlce": ("time", mlce),
                         "dvd_participation": ("time", np.full(t.size, 20.0)), "dvd": (("time", "site"), w),
                         "eta": ("time", eta, {"equipartition_value": 0.116}),
                         "energy_error": ("time", np.full(t.size, 1e-9))},
                        coords={"time": t, "site": np.arange(1, 41), "bond": np.arange(1, 42),
                                "mode": np.arange(1, 41)})
        if scene.model == "hertz":
            frac = np.zeros((t.size, 41))
            # one gap at a time, on the left (bond 21) and on the right (bond 22) of bead 21 in turn
            frac[0::2, 20] = frac[1::2, 21] = 0.1
            if spreading:
                frac[t > 3e2, :] = 0.1
            ds["gap_fraction"] = (("time", "bond"), frac)
            ds["gap_open"] = (("time", "bond"), (frac > 0).astype(np.int8))
            ds["n_gaps"] = ("time", (frac > 0).sum(axis=1))
            ds["n_gaps_max"] = ("time", (frac > 0).sum(axis=1))
        ds.attrs.update(model=scene.model, energy=scene.energy, u0=u0, dt=5e-4, integrator="SRKN6b",
                        t_final=t_final, max_energy_error=1e-9, final_energy_error=1e-9)
        out[name] = ds
    return out


@pytest.fixture(scope="module")
def chain_and_ensemble():
    return chain_dataset(random_chain(879, 5.0)), ensemble_dataset([1.0, 4.0, 5.0, 6.0], 20)


def by_id(claims):
    return {c.id: c for c in claims}


def test_every_claim_has_a_verdict_and_the_energy_error_of_its_scenes(chain_and_ensemble):
    claims = cl.evaluate_claims(synthetic_scenes(), *chain_and_ensemble,
                                energy_scan=synthetic_scan(*PAPER_STORY, error=1e-9))
    assert len({c.id for c in claims}) == len(claims) >= 40
    for claim in claims:
        assert claim.verdict in cl.VERDICTS, claim.id
        if claim.scenes:
            assert claim.max_energy_error == pytest.approx(1e-9), claim.id
        if claim.verdict != cl.REPRODUCED:
            assert claim.reason, claim.id


def test_the_story_of_the_paper_is_reproduced_on_data_that_tells_it(chain_and_ensemble):
    c = by_id(cl.evaluate_claims(synthetic_scenes(), *chain_and_ensemble))
    for key in ("loc-H0.5-hertz", "chaos-H0.5-hertz", "spread-H1.8-level", "spread-H1.8-onset", "regular-H0.5-fput", "spread-H1.8-saturation",
                "mlce-H1.8", "fput-regular-to-1.8", "fput-H2.9", "loc-H4-fput", "chaos-H4-fput",
                "fput-H8.7381", "gaps-H0.5-site21", "gaps-H1.8-cover", "dvd-H0.5-site21",
                "eta-final-hertz_H1.8", "eta-final-fput_H4", "P-H0.25-hertz", "P-H0.25-overlap"):
        assert c[key].verdict == cl.REPRODUCED, (key, c[key].measured_text, c[key].reason)


def test_u0_differs_with_the_reason_and_is_reproduced_when_it_matches(chain_and_ensemble):
    c = by_id(cl.evaluate_claims(synthetic_scenes(u0=1.041), *chain_and_ensemble))
    assert c["u0"].verdict == cl.DIFFERS and "overlaps" in c["u0"].reason
    c = by_id(cl.evaluate_claims(synthetic_scenes(u0=1.012), *chain_and_ensemble))
    assert c["u0"].verdict == cl.REPRODUCED


def test_a_missing_spreading_differs(chain_and_ensemble):
    c = by_id(cl.evaluate_claims(synthetic_scenes(hertz_spreads=False), *chain_and_ensemble))
    assert c["spread-H1.8-saturation"].verdict == cl.DIFFERS
    assert c["spread-H1.8-onset"].verdict == cl.DIFFERS


def test_short_runs_are_not_testable_unless_already_refuted(chain_and_ensemble):
    c = by_id(cl.evaluate_claims(synthetic_scenes(t_final=1e3), *chain_and_ensemble))
    assert c["chaos-H0.5-hertz"].verdict == cl.UNTESTABLE
    assert "1000" in c["chaos-H0.5-hertz"].reason
    assert c["spread-H1.8-saturation"].verdict == cl.UNTESTABLE
    assert c["u0"].verdict == cl.DIFFERS  # needs no time
    # "a constant value of P ~ 1.8", "the curves almost overlap": about the paper's whole run
    assert c["P-H0.25-hertz"].verdict == c["P-H0.25-overlap"].verdict == cl.UNTESTABLE
    scenes = synthetic_scenes(t_final=1e3)
    scenes["hertz_H0.5"]["n_gaps_max"][:] = 2  # two gaps at once: refuted however short the run
    scenes["hertz_H0.25"]["participation"][:] = 2.5  # P already off 1.8 and off the FPUT curve
    c = by_id(cl.evaluate_claims(scenes, *chain_and_ensemble))
    assert c["gaps-H0.5-one"].verdict == c["P-H0.25-hertz"].verdict == c["P-H0.25-overlap"].verdict == cl.DIFFERS


def test_a_scene_without_a_variable_makes_its_claims_untestable(chain_and_ensemble):
    scenes = synthetic_scenes()
    scenes["hertz_H1.8"] = scenes["hertz_H1.8"].drop_vars("mlce")
    c = by_id(cl.evaluate_claims(scenes, *chain_and_ensemble))
    assert c["mlce-H1.8"].verdict == cl.UNTESTABLE and "mlce" in c["mlce-H1.8"].reason


def synthetic_scan(hertz, fput, t_final=1e5, E=None, error=1e-8):
    """An energy scan on the grid E whose runs are delocalized and chaotic where the flag strings
    say ('1'/'0' per energy; chaos = delocalization unless given as (deloc, chaos))."""
    E = np.geomspace(0.1, 10, 12) if E is None else E
    flags = {}
    for model, spec in (("hertz", hertz), ("fput", fput)):
        deloc, chaos = spec if isinstance(spec, tuple) else (spec, spec)
        flags[model] = [np.array([int(ch) for ch in f], dtype=np.int8) for f in (deloc, chaos)]
    both = lambda i: (("model", "energy"), np.stack([flags["hertz"][i], flags["fput"][i]]))
    t = times(t_final)
    return xr.Dataset({"delocalized": both(0), "chaotic": both(1),
                       "valid": (("model", "energy"), np.ones((2, E.size), dtype=np.int8)),
                       "energy_error_max": (("model", "energy"), np.full((2, E.size), error))},
                      coords={"model": ["hertz", "fput"], "energy": E, "time": t},
                      attrs={"p_delocalized": 10.0, "chaos_margin": 5.0})


#: The 12-point grid 0.1 .. 10: 0.1 0.152 0.231 0.351 0.534 0.811 1.23 1.87 2.85 4.33 6.58 10
PAPER_STORY = ("000000011111",                     # Hertz: delocalized and chaotic from 1.87 on
               ("000000001011", "000000001111"))   # FPUT: from 2.85, localized again at 4.33, always chaotic

SCAN_ROWS = ("scan-hertz-deloc", "scan-hertz-chaos", "scan-hertz-onset", "scan-fput-chaos", "scan-fput-alternation")


def test_the_threshold_statements_are_judged_on_the_energy_scan(chain_and_ensemble):
    def claims(hertz, fput, **kw):
        return by_id(cl.evaluate_claims(synthetic_scenes(), *chain_and_ensemble,
                                        energy_scan=synthetic_scan(hertz, fput, **kw)))

    c = claims(*PAPER_STORY)
    for key in SCAN_ROWS:
        assert c[key].verdict == cl.REPRODUCED, (key, c[key].measured_text)
        assert c[key].max_energy_error == pytest.approx(1e-8) and c[key].scenes == ("energy_scan",)
    assert c["scan-hertz-deloc"].measured == pytest.approx(1.87, abs=0.01)
    # a localized energy above 1.8 breaks "always"; the reason names it
    c = claims("000000011011", PAPER_STORY[1])
    assert c["scan-hertz-deloc"].verdict == cl.DIFFERS and "4.33" in c["scan-hertz-deloc"].reason
    # delocalized and chaotic from 0.534 on: "for H > 1.8 always" says nothing below 1.8, and the
    # onset lies in the paper's region 0.5 <~ H <~ 1.8; the old "H* within a factor 1.5 of 1.8" failed this
    c = claims("000011111111", PAPER_STORY[1])
    for key in ("scan-hertz-deloc", "scan-hertz-chaos", "scan-hertz-onset"):
        assert c[key].verdict == cl.REPRODUCED, (key, c[key].measured_text)
    assert c["scan-hertz-chaos"].measured == pytest.approx(0.534, abs=0.01)
    # delocalized from 0.152: below the paper's H = 0.25, where the packet stays localized
    c = claims("011111111111", PAPER_STORY[1])
    assert c["scan-hertz-deloc"].verdict == cl.REPRODUCED and c["scan-hertz-onset"].verdict == cl.DIFFERS
    assert "outside the paper's region" in c["scan-hertz-onset"].reason
    # delocalization sets in only above 1.8: breaks both the bound and the region
    c = claims("000000001111", PAPER_STORY[1])
    assert c["scan-hertz-deloc"].verdict == c["scan-hertz-onset"].verdict == cl.DIFFERS
    # FPUT regular above 2.8 breaks its bound; chaos below 2.8 does not
    c = claims(PAPER_STORY[0], ("000000001011", "000000011011"))
    assert c["scan-fput-chaos"].verdict == cl.DIFFERS and "4.33" in c["scan-fput-chaos"].reason
    c = claims(PAPER_STORY[0], ("000000001011", "000001111111"))
    assert c["scan-fput-chaos"].verdict == cl.REPRODUCED
    # no return to localization above the first delocalized energy: no alternation
    c = claims(PAPER_STORY[0], "000000001111")
    assert c["scan-fput-alternation"].verdict == cl.DIFFERS
    # a scan that ends before the paper's t = 1e5 cannot judge; without a scan nothing is measured
    c = claims(*PAPER_STORY, t_final=1e4)
    assert all(c[key].verdict == cl.UNTESTABLE for key in SCAN_ROWS)
    c = by_id(cl.evaluate_claims(synthetic_scenes(), *chain_and_ensemble))
    assert all(c[key].verdict == cl.UNTESTABLE and "energy_scan missing" in c[key].reason for key in SCAN_ROWS)


def test_a_scan_claim_on_chaos_is_undecided_where_lambda_and_gali_answer_differently(chain_and_ensemble):
    """With the scan's second indicator (chaotic_gali): "for H > 2.8 always chaotic" holds by both,
    fails by both, or is undecided when only one indicator says it holds; the reason gives both."""
    def claims(gali_fput):
        scan = synthetic_scan(*PAPER_STORY)
        gali = np.stack([scan["chaotic"].values[0], np.array([int(ch) for ch in gali_fput], dtype=np.int8)])
        scan["chaotic_gali"] = (("model", "energy"), gali)
        scan.attrs["gali_order"] = 4
        return by_id(cl.evaluate_claims(synthetic_scenes(), *chain_and_ensemble, energy_scan=scan))

    assert claims("000000001111")["scan-fput-chaos"].verdict == cl.REPRODUCED
    split = claims("000000001011")["scan-fput-chaos"]
    assert split.verdict == cl.UNDECIDED
    assert "GALI" in split.reason and "3 of the 4" in split.reason
    assert "GALI" in split.criterion
    scan = synthetic_scan(PAPER_STORY[0], ("000000001011", "000000001011"))
    scan["chaotic_gali"] = scan["chaotic"].copy()
    c = by_id(cl.evaluate_claims(synthetic_scenes(), *chain_and_ensemble, energy_scan=scan))
    assert c["scan-fput-chaos"].verdict == cl.DIFFERS  # both say it fails


# ------------------------------------------------------------------ the paper against itself

#: The energies the paper simulates (both models share the scan's grid), and two between them.
PAPER_ENERGIES = np.array([0.25, 0.5, 1.0, 1.8, 2.0, 2.9, 3.0, 4.0, 8.7381])


def paper_scans():
    """Every energy scan on PAPER_ENERGIES that each sentence of the paper allows, as (hertz,
    fput) flag strings (delocalized, chaotic): Hertz localized and regular at 0.25 (Sec. III A),
    localized and chaotic at 0.5 (III B 1), delocalized and chaotic for H > 1.8 (III B 2) and at 1.8
    (Fig. 4), free at 1.0, inside the region 0.5 <~ H <~ 1.8 (III C); FPUT localized and regular up
    to 1.8 (III B 3), localized at 2.0 (2.9 is the first delocalized energy), chaotic for H > 2.8,
    delocalized at 2.9 and 8.7381, localized at 4, free at 3.0 and in its chaos at 2.0."""
    for hertz_deloc_1, hertz_chaos_1, fput_chaos_2, fput_deloc_3 in itertools.product("01", repeat=4):
        hertz = (f"00{hertz_deloc_1}111111", f"01{hertz_chaos_1}111111")
        fput = (f"000001{fput_deloc_3}01", f"0000{fput_chaos_2}1111")
        yield hertz, fput


@pytest.mark.parametrize("hertz, fput", list(paper_scans()))
def test_a_scan_that_tells_every_sentence_of_the_paper_passes_every_threshold_claim(hertz, fput,
                                                                                    chain_and_ensemble):
    """The paper's own statements do not contradict each other under the criteria: its Hertz
    orbit chaotic at H = 0.5 and "always [...] a delocalized chaotic state" for H > 1.8, its region
    0.5 <~ H <~ 1.8 and its FPUT bound H > 2.8 with the alternation above 2.9 all hold on one scan,
    whatever the paper leaves free."""
    scan = synthetic_scan(hertz, fput, E=PAPER_ENERGIES)
    c = by_id(cl.evaluate_claims(synthetic_scenes(), *chain_and_ensemble, energy_scan=scan))
    for key in SCAN_ROWS:
        assert c[key].verdict == cl.REPRODUCED, (key, c[key].criterion, c[key].measured_text)
    # the bounds sit at the paper's energies: 1.8 is the scan's threshold for Hertz delocalization
    # when 1.0 is localized, and a failure at the bound itself is not "above" it
    if hertz[0][2] == "0":
        assert c["scan-hertz-deloc"].measured == 1.8
    at_bound = synthetic_scan((hertz[0][:3] + "0" + hertz[0][4:], hertz[1]), fput, E=PAPER_ENERGIES)
    c = by_id(cl.evaluate_claims(synthetic_scenes(), *chain_and_ensemble, energy_scan=at_bound))
    assert c["scan-hertz-deloc"].verdict == cl.REPRODUCED


def test_criteria_come_from_the_config_and_unknown_keys_are_refused():
    block = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())["claims"]
    criteria = Criteria.from_config(block)
    assert criteria.tolerance.time_factor == block["tolerance"]["time_factor"]
    assert criteria.plateau_end["fput_H2.9"] == block["plateau_end"]["fput_H2.9"]
    with pytest.raises(ValueError, match="chaos_slop"):
        Criteria.from_config({"chaos_slop": -0.5})
    with pytest.raises(ValueError, match="tolerance"):
        Criteria.from_config({"tolerance": {"timefactor": 2}})


def test_macros_are_newcommands_read_with_cc():
    text = writers.macros_tex({"scene.hertz_H0.25.u0": "1.041", "count.total": "48"})
    assert r"\expandafter\newcommand\csname cc@scene.hertz_H0.25.u0\endcsname{1.041}" in text
    with pytest.raises(ValueError):
        writers.tex_macro("bad{key}", "1")


@pytest.mark.skipif(shutil.which("pdflatex") is None, reason="needs pdflatex")
def test_macros_compile_and_an_unknown_key_stops_latex(tmp_path):
    (tmp_path / "macros.tex").write_text(writers.macros_tex({"a.b_c": "$1.5$"}) + "\\newif\\ifpaperscale\n")
    doc = "\\documentclass{article}\\begin{document}\\input{macros}%s\\end{document}\n"
    for body, ok in (("\\cc{a.b_c}", True), ("\\cc{a.missing}", False)):
        (tmp_path / "t.tex").write_text(doc % body)
        done = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "t.tex"], cwd=tmp_path,
                              capture_output=True, text=True)
        assert (done.returncode == 0) == ok, done.stdout[-2000:]


# ------------------------------------------------------------------ the build


def figure_objects(pdf: Path) -> list[str]:
    """File names of the PDF figures pdfTeX embedded (its /PTEX.FileName entries)."""
    return re.findall(rb"/PTEX\.FileName \(([^)]*)\)", pdf.read_bytes())


@pytest.mark.pipeline
@pytest.mark.skipif(shutil.which("pdftotext") is None, reason="needs poppler-utils")
def test_quick_manuscript_has_every_figure_and_the_claims(quick):
    pdf = quick / QUICK_MANUSCRIPT
    assert pdf.read_bytes()[:5] == b"%PDF-"
    embedded = {Path(name.decode()).stem for name in figure_objects(pdf)}
    assert {f"fig{n}" for n in panels.LAYOUTS} | {"figscan", "figdisorder"} <= embedded
    if (quick / "figures" / "work_precision.pdf").exists():  # the numerics rules are part of the workflow
        assert {"wpfigure", "stabfigure"} <= embedded  # an optional part's files are named by their key
    images = subprocess.run(["pdfimages", "-list", str(pdf)], capture_output=True, text=True, check=True).stdout
    assert len(images.splitlines()) > 2 + 10  # the density maps are raster images inside the figures
    text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True,
                          check=True).stdout
    for n in panels.LAYOUTS:
        assert re.search(rf"FIG\. {n}\.", text), f"caption of figure {n} missing"
    assert "TABLE I" in text.upper() and "??" not in text
    with open(quick / "claims" / "claims.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert rows and all(r["verdict"] in cl.VERDICTS for r in rows)
    assert sum(r["verdict"] == cl.UNTESTABLE for r in rows) > 0  # quick scale ends at t = 1e3
    scan_rows = [r for r in rows if r["scenes"] == "energy_scan"]
    assert len(scan_rows) == len(SCAN_ROWS) and all(r["measured_text"] != "--" for r in scan_rows)


@pytest.mark.pipeline
def test_every_macro_the_manuscript_uses_is_generated(quick):
    macros = (quick / "claims" / "macros.tex").read_text()
    defined = set(re.findall(r"\\csname cc@([^\\]+)\\endcsname", macros))
    tex = re.sub(r"(?<!\\)%.*", "", (ROOT / "manuscript" / "ms.tex").read_text())  # without comments
    if "\\searcharchivedfalse" in macros:  # the archive's branch is not typeset, its macros not needed
        tex = re.sub(r"\\ifsearcharchived.*?\\else", "", tex, flags=re.S)
    if "\\disordergalifalse" in macros:  # disorder statistics without GALI_k: their sentence is not typeset
        tex = re.sub(r"\\ifdisordergali.*?\\fi", "", tex, flags=re.S)
    used = set(re.findall(r"\\cc\{([^}]+)\}", tex))
    used |= {f"claim.{k}.{f}" for k in re.findall(r"\\(?:claim|verdict)\{([^}]+)\}", tex) for f in ("n", "verdict")}
    used = {u for u in used if "#" not in u}
    assert used and used <= defined, sorted(used - defined)


def test_threshold_sentences_read_correctly_when_no_grid_energy_qualifies():
    """The manuscript's threshold phrases name the energy, or say that the grid has none, in words
    that read as a sentence (no "H = (none on the grid)")."""
    attrs = {"t_final": 1e5, "dt": 5e-3, "integrator": "SRKN6b", "p_delocalized": 10.0, "chaos_slope": -0.5}
    scan = synthetic_scan("000000011111", ("000000000000", "000000001110"))
    scan.attrs.update(attrs)
    E = np.array([0.5, 1.0, 2.0])
    probability = {"hertz": [0.25, 0.5, 1.0], "fput": [0.0, 0.25, 0.25]}
    p = (("model", "energy"), np.array([probability["hertz"], probability["fput"]]))
    disorder = xr.Dataset({f"probability_{key}{band}": p for key in ("delocalized", "chaotic")
                           for band in ("", "_lower", "_upper")},
                          coords={"model": ["hertz", "fput"], "energy": E, "realization": np.arange(4)},
                          attrs={**attrs, "alpha": 5.0})
    disorder["valid"] = (("model", "energy"), np.ones((2, 3), dtype=np.int8))
    m = writers.scan_macros(scan, disorder)
    assert m["scan.hertz.delocalized.always"] == r"delocalized at every scanned $H \ge 1.87$"
    assert m["scan.fput.delocalized.first"] == m["scan.fput.delocalized.always"] == "delocalized at no scanned energy"
    assert m["scan.fput.chaotic.first"] == "first chaotic at $H = 2.85$"
    assert m["scan.fput.chaotic.always"] == "not chaotic at the highest scanned energy, $H = 10$"
    assert m["disorder.hertz.delocalized.half"] == (
        "the lowest energy of the grid at which at least half of the Hertz realizations delocalize is $H = 1.00$")
    assert m["disorder.fput.delocalized.half"] == (
        "at no energy of the grid do at least half of the FPUT realizations delocalize")
    assert not any("none on the grid" in value for value in m.values())
