"""Energy scans and disorder statistics (chainchaos.studies.scan.runs): reductions, criteria, the
scans as studies, merge."""

import numpy as np
import pytest
import xarray as xr

from chainchaos import random_chain
from chainchaos.records.io import chain_dataset, write_netcdf
from chainchaos.studies.scan.merge import merge_disorder, merge_energy_scan, scan_groups
from chainchaos.studies.study.statistics import wilson_interval
from chainchaos.run.orbits import Orbit
from chainchaos.studies.scan.runs import scan_study, settings_for
from chainchaos.paper.thresholds import (
    PAPER_THRESHOLDS,
    thresholds_csv,
    thresholds_table,
    thresholds_tex,
)
from chainchaos.studies.study.orbits import (
    StudySettings,
    energy_grid,
    select_excitation,
)
from chainchaos.studies.study.runs import run_group
from chainchaos.studies.study.spec import load_study
from chainchaos.system.models import get_model
from reduced import reduced_orbits

CFG = {
    "settings": {"dt": 0.02, "samples_per_decade": 8, "p_delocalized": 10.0, "chaos_slope": -0.5,
                 "batch_size": 8, "engine": "batch"},
    "energy_scan": {"n_energies": 4, "energy_min": 0.2, "energy_max": 8.0, "t_final": 300.0,
                    "trajectories_per_job": 3, "site": 21},
    "disorder": {"n_energies": 2, "energy_min": 0.5, "energy_max": 8.0, "realizations": 3, "t_final": 200.0,
                 "trajectories_per_job": 5, "alpha": 5.0, "first_seed": 100,
                 "selection": {"high_frequency_modes": 14, "centre_window": 5}},
}


@pytest.fixture(scope="module")
def chain():
    return random_chain(5346, 5.0)


@pytest.fixture(scope="module")
def chain_file(chain, tmp_path_factory):
    return str(write_netcdf(chain_dataset(chain), tmp_path_factory.mktemp("chain") / "chain.nc"))


def scan_as_study(kind, chain_file=None):
    """The study a scan kind of CFG is, and its group files (each job's orbits)."""
    study = load_study(scan_study(kind, CFG, 40, chain_file))
    return study, [run_group(study, g) for g in range(study.n_groups)]


def test_a_scan_is_the_study_of_its_settings(chain_file):
    study = load_study(scan_study("energy_scan", CFG, 40, chain_file))
    assert study.settings == StudySettings(**{**settings_for("energy_scan", CFG).__dict__, "batch_size": 32})
    assert study.energies.tolist() == energy_grid(CFG["energy_scan"]).tolist()
    assert study.excitation().site == 21 and study.models == ["hertz", "fput"] and study.realizations == 1
    assert study.n_groups == 3  # 8 trajectories, 3 per job
    disorder = load_study(scan_study("disorder", CFG))
    assert disorder.n_groups == 3 and disorder.seeds == [100, 101, 102]  # 12 trajectories, 5 per job
    for r, chain in enumerate(disorder.chains):
        assert disorder.excitation(r).site == select_excitation(chain, 14, 5)["site"]
    items = [it for g in range(disorder.n_groups) for it in disorder.group_items(g)]
    assert items == disorder.items() and len(set(items)) == len(items)


def test_energy_grid_is_log_spaced_and_rounded():
    grid = energy_grid({"n_energies": 100, "energy_min": 0.1, "energy_max": 10})
    assert grid[0] == 0.1 and grid[-1] == 10.0 and grid.size == 100
    assert np.allclose(np.diff(np.log(grid)), np.log(100) / 99, rtol=0, atol=1e-5)


def test_selection_rule_picks_a_localized_high_mode_near_the_centre(chain):
    pick = select_excitation(chain, high_frequency_modes=14, centre_window=5)
    assert pick["mode"] > chain.N - 14 and abs(pick["site"] - (chain.N + 1) / 2) <= 5 and not pick["fallback"]
    from chainchaos.system.linear import (
        mode_energy_density,
        normal_modes,
        participation_number,
    )

    omega, U = normal_modes(chain)
    h = mode_energy_density(chain, omega, U)
    P = participation_number(h)
    near = [k for k in range(chain.N - 14, chain.N) if abs(np.argmax(h[:, k]) + 1 - 20.5) <= 5]
    assert pick["participation"] == pytest.approx(min(P[near]))
    # with no candidate near the centre the most localized high mode is taken, flagged
    assert select_excitation(chain, high_frequency_modes=1, centre_window=0)["fallback"] in (True, False)


def test_engines_agree_and_criteria_follow_their_definitions(chain):
    settings = StudySettings(t_final=400.0, dt=0.02, samples_per_decade=8, p_delocalized=6.0,
                                 chaos_growth_margin=2.0, final_samples=20)
    trajs = [Orbit(model=m, energy=E, chain=chain, site=21) for m in ("hertz", "fput", "toda") for E in (0.2, 3.0)]
    a = reduced_orbits(trajs, settings)
    b = reduced_orbits(trajs, StudySettings(**{**settings.__dict__, "engine": "single"}))
    for ra, rb in zip(a, b):
        for key in ("participation_final", "mlce_final", "eta_final", "max_gaps", "chaotic"):
            assert ra[key] == rb[key]  # the engines are bit-identical
    for t, r in zip(trajs, a):
        assert r["valid"] and r["energy_error_max"] < 1e-3
        tt, P = r["times"], r["participation"]
        last = tt >= tt[-1] / 10
        assert np.count_nonzero(last) >= 20  # the dense final samples
        # the final value is the trapezoidal time average over the last decade
        assert r["participation_final"] == pytest.approx(np.trapezoid(P[last], tt[last]) / (tt[-1] - tt[last][0]))
        assert r["delocalized"] == (r["participation_final"] > 6.0)
        assert r["mlce_final"] == pytest.approx(r["log_growth"][-1] / r["times"][-1])
        assert (r["max_gaps"] >= 0) == get_model(t.model).has_gaps
        if np.isfinite(r["delocalization_onset"]):  # a sustained crossing: above for half a decade
            i = np.searchsorted(tt, r["delocalization_onset"])
            hold = (tt >= tt[i]) & (tt <= min(tt[i] * 10**0.5, tt[-1]))
            assert (P[hold] > 6.0).all()
    low, high = a[0], a[1]  # Hertz: the low energy stays localized, the high one spreads with gaps
    assert low["participation_final"] < 4 and high["participation_final"] > low["participation_final"]
    assert high["max_gaps"] > low["max_gaps"]


def test_energy_scan_groups_merge_onto_the_grid(chain, chain_file):
    ds = merge_energy_scan(scan_groups(scan_as_study("energy_scan", chain_file)[1]), CFG, chain)
    assert ds.participation_final.dims == ("model", "energy")
    assert ds.participation.dims == ("model", "energy", "time")
    assert list(ds.model.values) == ["hertz", "fput"] and ds.sizes["energy"] == 4
    assert np.isfinite(ds.participation_final).all() and (ds.valid == 1).all()
    assert (ds.max_gaps.sel(model="fput") == -1).all() and (ds.max_gaps.sel(model="hertz") >= 0).all()
    for key in ("git_commit", "parameters", "chainchaos_version", "delocalization_criterion", "chaos_criterion"):
        assert key in ds.attrs
    rows = thresholds_table(ds)
    assert {(r["model"], r["criterion"]) for r in rows} == set(PAPER_THRESHOLDS)
    csv = thresholds_csv(rows, ds)
    assert "model,criterion,first_energy,always_above" in csv and "p_delocalized = 10" in csv
    assert "\\begin{tabular}" in thresholds_tex(rows, ds)


def test_thresholds_table_reads_first_and_always_above():
    E = np.array([0.1, 0.2, 0.5, 1.0, 2.0])
    flags = np.array([[0, 1, 0, 1, 1], [0, 0, 0, 0, 0]], dtype=np.int8)
    ds = xr.Dataset({"delocalized": (("model", "energy"), flags), "chaotic": (("model", "energy"), flags[::-1]),
                     "valid": (("model", "energy"), np.ones_like(flags))},
                    coords={"model": ["hertz", "fput"], "energy": E})
    rows = {(r["model"], r["criterion"]): r for r in thresholds_table(ds)}
    assert rows["hertz", "delocalization"]["first_energy"] == 0.2
    assert rows["hertz", "delocalization"]["always_above"] == 1.0
    assert np.isnan(rows["hertz", "chaos"]["first_energy"])
    assert rows["fput", "chaos"]["fraction"] == pytest.approx(0.6)


def test_disorder_statistics_with_binomial_bands():
    ds = merge_disorder(scan_groups(scan_as_study("disorder")[1]), CFG)
    assert ds.participation_final.dims == ("model", "energy", "realization")
    assert ds.sizes["realization"] == 3 and (ds.count_valid == 3).all()
    for what in ("delocalized", "chaotic"):
        p, lo, hi = (ds[f"probability_{what}{s}"].values for s in ("", "_lower", "_upper"))
        assert ((lo <= p + 1e-12) & (p <= hi + 1e-12)).all() and (lo >= 0).all() and (hi <= 1).all()
        k = ((ds[what] == 1) & (ds.valid == 1)).sum("realization").values
        np.testing.assert_allclose(p, k / 3)
    # the excited bead of each realization follows the selection rule
    for r in range(3):
        pick = select_excitation(random_chain(100 + r, 5.0), 14, 5)
        assert int(ds.excited_site[r]) == pick["site"] and int(ds.excited_mode[r]) == pick["mode"]
    assert ds.delocalization_onset_quantiles.dims == ("model", "energy", "quantile")
    assert "selection_rule" in ds.attrs and ds.attrs["confidence_interval"].startswith("Wilson")


def test_wilson_interval_known_values():
    lo, hi = wilson_interval(0, 10)
    assert lo == 0 and hi == pytest.approx(0.2775, abs=1e-3)
    lo, hi = wilson_interval(5, 10)
    assert lo == pytest.approx(0.2366, abs=1e-3) and hi == pytest.approx(0.7634, abs=1e-3)
    lo, hi = wilson_interval(0, 0)
    assert np.isnan(lo) and np.isnan(hi)


def test_scan_figures_are_byte_stable(tmp_path, chain, chain_file):
    from chainchaos.output.plotting.style import save_figure
    from chainchaos.output.plotting import scan as scan_plots

    ds = merge_energy_scan(scan_groups(scan_as_study("energy_scan", chain_file)[1]), CFG, chain)
    dis = merge_disorder(scan_groups(scan_as_study("disorder")[1]), CFG)
    for name, fig_fn, data in (("e", scan_plots.energy_scan_figure, ds), ("d", scan_plots.disorder_figure, dis)):
        save_figure(fig_fn(data), tmp_path / f"{name}1")
        save_figure(fig_fn(data), tmp_path / f"{name}2")
        a, b = (tmp_path / f"{name}1.pdf").read_bytes(), (tmp_path / f"{name}2.pdf").read_bytes()
        assert a[:5] == b"%PDF-" and a == b and b"CreationDate" not in a
        assert (tmp_path / f"{name}1.png").read_bytes() == (tmp_path / f"{name}2.png").read_bytes()


def test_a_scan_orbit_of_the_study_is_the_scans_trajectory(chain, chain_file):
    """The study path and the orbits integrated alone give the same numbers, orbit by orbit, to the bit."""
    study, groups = scan_as_study("energy_scan", chain_file)
    g = groups[0]
    trajs = [Orbit(model=str(m), energy=float(study.energies[e]), chain=chain, site=21)
             for m, e in zip(g["model"].values, g["energy_index"].values)]
    for i, r in enumerate(reduced_orbits(trajs, settings_for("energy_scan", CFG))):
        for key in ("participation_final", "mlce_final", "eta_final", "chaos_onset", "max_gaps", "u0"):
            np.testing.assert_array_equal(g[key].values[i], r[key], err_msg=key)
        np.testing.assert_array_equal(g["participation"].values[i], r["participation"])
