"""Studies from one file (chainchaos.studies.study): the excitations and spreading observables
against exact results, the file's checks, the statistics' rules, and numbers that do not depend
on how the orbits are cut into jobs."""

import numpy as np
import pytest
import xarray as xr

from chainchaos import run_study
from chainchaos.errors import StudyError
from chainchaos.observe import formulas
from chainchaos.studies.study import statistics as st
from chainchaos.studies.study.spec import FIGURE_OBSERVABLES, load_study, study_names
from chainchaos.system.initial import Excitation, initial_displacement
from chainchaos.system.linear import modal_energies, normal_modes, participation_number
from chainchaos.system.models import get_model, total_energy

TINY = {"lattice": {"model": "fput", "N": 16, "realizations": 3},
        "excitation": {"energies": [0.5, 2.0]},
        "integration": {"dt": 0.05, "t_final": 50.0}}


# ---- excitations ----------------------------------------------------------------------------

@pytest.mark.parametrize("model", ["hertz", "fput"])
def test_a_single_displaced_bead_is_the_papers_initial_state_to_the_bit(chain, model):
    u, p, a = Excitation(site=21).state(get_model(model), chain, 1.8)
    assert a == initial_displacement(get_model(model), chain, 1.8, 21)
    assert u[20] == a and np.count_nonzero(u) == 1 and not p.any()


@pytest.mark.parametrize("kind,width", [("site", 1), ("block", 4), ("mode", 1)])
def test_a_momentum_excitation_has_the_energy_exactly(chain, kind, width):
    exc = Excitation(kind=kind, variable="momentum", site=20, mode=30, width=width)
    u, p, _ = exc.state(get_model("hertz"), chain, 0.7)
    assert not u.any()
    assert float(total_energy(get_model("hertz"), chain, u, p)) == pytest.approx(0.7, rel=1e-14)
    if kind == "block":  # every bead of the block gets the same kinetic energy, signs alternating
        kinetic = p**2 / (2 * chain.mass)
        assert np.flatnonzero(p).tolist() == [18, 19, 20, 21]
        assert kinetic[18:22] == pytest.approx(np.full(4, 0.7 / 4), rel=1e-14)
        assert np.sign(p[18:22]).tolist() == [1, -1, 1, -1]


def test_a_displaced_mode_of_the_harmonic_chain_holds_all_its_energy_in_that_mode(chain):
    harmonic = get_model("harmonic")
    u, p, _ = Excitation(kind="mode", mode=34).state(harmonic, chain, 0.3)
    omega, U = normal_modes(chain)
    E = modal_energies(chain, omega, U, u[None, :], p[None, :])[0]
    assert E.sum() == pytest.approx(0.3, rel=1e-12)
    assert E[33] == pytest.approx(0.3, rel=1e-12)


@pytest.mark.parametrize("exc,message", [
    (Excitation(site=41), "excitation site = 41"),
    (Excitation(kind="mode", mode=41), "excitation mode = 41"),
    (Excitation(kind="block", site=39, width=5), "excitation block"),
])
def test_an_excitation_beyond_the_chain_is_named(chain, exc, message):
    with pytest.raises(ValueError, match=message):
        exc.state(get_model("fput"), chain, 1.0)


def test_the_linear_limit_keeps_a_mode_a_mode():
    """Integrable limit through the whole study path: a mode of the harmonic chain stays a mode,
    its spectral entropy zero to the integrator's error at every sample."""
    ds = run_study({"lattice": {"model": "harmonic", "N": 24, "alpha": 3.0, "realizations": 2},
                    "excitation": {"kind": "mode", "mode": 20, "energies": [1.0]},
                    "integration": {"dt": 0.01, "t_final": 100.0},
                    "observables": ["spectral_entropy", "participation"]})
    assert np.nanmax(np.abs(ds["spectral_entropy"].values)) < 1e-8
    assert (ds["valid"] == 1).all()


# ---- spreading observables ------------------------------------------------------------------

def test_second_moment_and_compactness_of_exact_distributions():
    N, L = 40, 9
    point = np.zeros(N)
    point[12] = 1.0
    even = np.zeros(N)
    even[10:10 + L] = 1.0 / L
    two = np.zeros(N)
    two[[4, 24]] = 0.5  # two peaks 20 sites apart: m2 = 100
    h = np.stack([point, even, two])
    m2 = formulas.second_moment(h)
    assert m2[0] == 0.0
    assert m2[1] == pytest.approx((L**2 - 1) / 12, rel=1e-14)
    assert m2[2] == pytest.approx(100.0, rel=1e-14)
    zeta = formulas.compactness(participation_number(h, axis=-1), m2)
    assert zeta[1] == pytest.approx(12 * L**2 / (L**2 - 1), rel=1e-13)
    assert zeta[2] == pytest.approx(0.04, rel=1e-13)  # sparse: P = 2, m2 = 100


# ---- the study file -------------------------------------------------------------------------

def test_the_worked_studies_are_valid_and_fput_extends_hertz():
    assert {"hertz100", "fput100"} <= set(study_names())
    hertz, fput = load_study("hertz100"), load_study("fput100")
    assert hertz.models == ["hertz"] and fput.models == ["fput"]
    assert fput.spec["lattice"] == {**hertz.spec["lattice"], "model": "fput"}
    assert fput.spec["integration"] == hertz.spec["integration"]
    assert len(hertz.seeds) == 16 and hertz.energies.tolist() == [0.5, 1.8, 3.0]
    assert hertz.excitation().site == 50 and hertz.settings.alignment and hertz.settings.gali_order == 4


@pytest.mark.parametrize("change,message", [
    ({"excitation": {"energies": [1.0], "site": 17}}, "study key excitation.site = 17: allowed is beads within 1..N = 16"),
    ({"excitation": {"energies": [1.0], "kind": "mode", "mode": 20}}, "study key excitation.mode = 20"),
    ({"integration": {"dt": 60.0, "t_final": 50.0}}, "study key integration.dt = 60.0"),
    ({"lattice": {"model": "fpu", "N": 16}}, "study key lattice.model = 'fpu': allowed is a model of the registry"),
    ({"observables": ["dvd"]}, "study key observables[0] = 'dvd'"),
    ({"lattice": {"model": "fput", "N": 1}}, "study key lattice.N = 1"),
    ({"excitation": {"energies": [-1.0]}}, "study key excitation.energies[0] = -1.0"),
    ({"ensemble": {"lanes": 0}}, "study key ensemble.lanes = 0"),
    ({"extends": "no_such_study"}, "study 'no_such_study': no file"),
    ({"typo": 1}, "unknown key(s) ['typo']"),
    ({"laws": {"walls": {"edge_energy": 1e-6}}},
     "study key laws.walls.edge_energy = 1e-06: allowed is a bound only with edge_energy among the observables"),
])
def test_a_wrong_key_is_named_with_what_is_allowed(change, message):
    with pytest.raises(StudyError) as err:
        load_study({**TINY, **change})
    assert message in str(err.value)


@pytest.mark.parametrize("figure", sorted(FIGURE_OBSERVABLES))
def test_a_study_whose_figure_lacks_an_observable_is_refused_before_it_runs(figure):
    """Each figure a study draws needs its series: without one, the study is refused at once,
    naming the figure and the observable (the figure job would fail after all the work)."""
    figures = {"compare_with": ["hertz100"], "figures": []} if figure == "comparison" else {"figures": [figure]}
    if figure == "maps":  # maps draw the density at map times, not a series
        figures["integration"] = {**TINY["integration"], "map_times": [float(TINY["integration"]["t_final"])]}
    load_study({**TINY, **figures})  # the default observables draw every figure
    for missing in FIGURE_OBSERVABLES[figure]:
        observables = [o for o in ("participation", "second_moment", "mlce") if o != missing]
        with pytest.raises(StudyError) as err:
            load_study({**TINY, **figures, "observables": observables})
        assert f"study key figures = '{figure}'" in str(err.value) and f"draws {missing}" in str(err.value)


def test_the_default_figures_follow_the_observables():
    """The issue's study, P and Lambda only with the default figures, draws chaos and fractions
    (spreading needs m2); naming spreading with those observables is refused."""
    assert load_study({**TINY, "observables": ["participation", "mlce"]}).spec["figures"] == ["chaos", "fractions"]
    assert load_study(TINY).spec["figures"] == ["spreading", "chaos", "fractions"]
    with pytest.raises(StudyError, match="spreading draws second_moment"):
        load_study({**TINY, "observables": ["participation", "mlce"], "figures": ["spreading", "chaos"]})


def test_a_study_extending_itself_is_named(tmp_path):
    (tmp_path / "a.yaml").write_text("extends: b\n")
    (tmp_path / "b.yaml").write_text("extends: a\n")
    with pytest.raises(StudyError, match="extend each other"):
        load_study("a", root=tmp_path)


# ---- numbers ----------------------------------------------------------------------------------

def test_results_do_not_depend_on_how_orbits_are_cut_into_jobs():
    """Bit for bit: one job against one orbit per job (lanes of other batches never mix)."""
    one = run_study({**TINY, "ensemble": {"lanes": 2}, "jobs": {"orbits_per_job": 64}})
    many = run_study({**TINY, "ensemble": {"lanes": 2}, "jobs": {"orbits_per_job": 1}})
    for name in one.data_vars:
        np.testing.assert_array_equal(one[name].values, many[name].values, err_msg=name)


def test_run_study_returns_every_orbit_and_the_statistics():
    ds = run_study({**TINY, "observables": ["participation", "second_moment", "mlce", "log_gali"]})
    assert dict(ds["second_moment"].sizes) == {"model": 1, "energy": 2, "realization": 3, "lane": 1,
                                                 "time": ds.sizes["time"]}
    assert ds["mean_log10_second_moment"].dims == ("model", "energy", "time")
    assert ds["quantile_log10_mlce"].dims == ("model", "energy", "quantile", "time")
    assert (ds["valid"] == 1).all() and float(ds["energy_error_max"].max()) < 1e-3
    assert set(np.unique(ds["chaotic_gali"])) <= {0, 1}
    # the mean is the mean of the logarithms over the realizations
    expected = np.log10(ds["second_moment"].isel(lane=0)).mean("realization")
    np.testing.assert_allclose(ds["mean_log10_second_moment"].values[..., 1:], expected.values[..., 1:], rtol=1e-14)


def test_running_slope_recovers_a_power_law_and_needs_three_samples():
    t = 10.0 ** np.linspace(0, 4, 41)
    slope = st.running_slope(np.log10(t), 0.33 * np.log10(t) + 2.0, 1.0)
    np.testing.assert_allclose(slope, 0.33, rtol=1e-12)
    sparse = st.running_slope(np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 2.0]), 2.0)
    assert np.isnan(sparse[0]) and np.isnan(sparse[2]) and sparse[1] == pytest.approx(1.0)


def test_a_realization_whose_lanes_split_is_undecided():
    flag = xr.DataArray(np.array([[[[1, 1], [0, 0], [1, 0], [1, 1]]]]), dims=("model", "energy", "realization", "lane"))
    valid = xr.DataArray(np.array([[[[1, 1], [1, 1], [1, 1], [0, 0]]]]), dims=flag.dims)
    assert st.realization_verdicts(flag, valid).tolist() == [[[1, 0, -1, -2]]]


def test_ordered_mean_skips_missing_values():
    x = np.array([[1.0, np.nan], [3.0, 2.0], [np.nan, np.nan]])
    mean, count = st.ordered_mean(x, axis=0)
    assert mean.tolist() == [2.0, 2.0] and count.tolist() == [2, 1]


def test_ordered_mean_adds_the_terms_in_index_order():
    # 1e16 + 1 + 1 + ... in index order loses every 1 (half an ulp of 1e16 is 1); a pairwise or
    # reordered sum keeps some of them
    column = np.array([1e16] + [1.0] * 15 + [-1e16])
    x = np.stack([column, column[::-1]], axis=1)
    mean, count = st.ordered_mean(x, axis=0)
    expected = []
    for values in x.T:
        total = 0.0
        for v in values:
            total += v
        expected.append(total / values.size)
    assert mean.tolist() == expected and expected == [0.0, 0.0] and count.tolist() == [17, 17]


def test_every_study_key_is_described_and_the_committed_readme_is_generated():
    from pathlib import Path

    from chainchaos.workflow import config_docs

    root = Path(__file__).resolve().parents[3]
    schema = config_docs.load_schema(config_docs.STUDY_SCHEMA, own_models=False)
    assert config_docs.undescribed(schema) == []
    assert (root / config_docs.STUDY_README).read_text() == config_docs.render(schema, config_docs.STUDY_HEADER), \
        "studies/README.md is stale: run python -m chainchaos.workflow.config_docs"


def test_edge_energy_counts_each_end_once_and_marks_a_packet_at_the_walls_invalid():
    h = np.zeros((3, 20))
    h[0, [0, 10]] = 0.5  # half at the left end
    h[1, 19] = 1.0  # all at the right end
    h[2, 5:15] = 0.1  # none within 5 sites of an end
    assert formulas.edge_energy(h).tolist() == [0.5, 1.0, 0.0]
    assert formulas.edge_energy(np.full((1, 6), 1 / 6)).tolist() == pytest.approx([1.0])  # overlapping margins
    # an ordered harmonic chain of 12 beads: the packet reaches the walls, the bound marks it invalid
    study = {"lattice": {"model": "harmonic", "N": 12, "alpha": 1.0}, "excitation": {"energies": [1.0]},
             "integration": {"dt": 0.05, "t_final": 200.0}, "observables": ["participation", "edge_energy"]}
    free = run_study(study)
    bounded = run_study({**study, "criteria": {"max_edge_energy": 0.2}})
    assert float(free["edge_energy"].max()) > 0.2 and (free["valid"] == 1).all()
    assert (bounded["valid"] == 0).all() and np.isnan(bounded["mean_log10_participation"]).all()


def test_a_klein_gordon_study_runs_on_kg_lattices_with_the_energy_of_its_hamiltonian():
    """Models kg and kg_linear run on KG lattices (eps_l from the seed, coupling 1/W); a single-site
    momentum excitation holds the energy asked for exactly, and the run conserves it."""
    from chainchaos.system.chain import kg_chain
    from chainchaos.system.models import get_model, total_energy

    spec = {"lattice": {"model": ["kg", "kg_linear"], "N": 32, "W": 4.0, "realizations": 2, "first_seed": 7},
            "excitation": {"variable": "momentum", "energies": [0.4]},
            "integration": {"dt": 0.1, "t_final": 50.0}, "observables": ["participation", "second_moment"]}
    study = load_study(spec)
    lattice = study.lattices("kg")[1]
    assert lattice.eps.tolist() == kg_chain(8, 4.0, 32).eps.tolist()
    u, p, _ = study.excitation(1).state(get_model("kg"), lattice, 0.4)
    assert float(total_energy(get_model("kg"), lattice, u, p)) == pytest.approx(0.4, rel=1e-14)
    ds = run_study(spec)
    assert (ds["valid"] == 1).all() and float(ds["energy_error_max"].max()) < 1e-6
    with pytest.raises(StudyError, match="a bead model with a chain file"):
        load_study({**spec, "lattice": {"model": "kg", "chain_file": "results/chain/chain.nc"}})


def test_run_study_reads_a_kept_group_with_its_settings_and_computes_the_others(tmp_path, monkeypatch):
    from chainchaos.records.io import write_netcdf
    from chainchaos.studies.study import spec as study_spec
    from chainchaos.studies.study.runs import run_group

    (tmp_path / "studies").mkdir()
    (tmp_path / "studies" / "kept.yaml").write_text(
        "title: kept\nlattice: {model: fput, N: 12, realizations: 2}\nexcitation: {energies: [1.0]}\n"
        "integration: {dt: 0.05, t_final: 20.0}\njobs: {orbits_per_job: 1}\n")
    monkeypatch.setattr(study_spec, "studies_dir", lambda: tmp_path / "studies")
    study = study_spec.load_study("kept")
    group = run_group(study, 0)
    group["participation"] = group["participation"] * 2  # marks the kept file's numbers
    write_netcdf(group, study_spec.kept_group_path("kept", 0), seal=True)
    ds = run_study("kept")
    fresh = run_group(study, 0)["participation"].values[0]
    np.testing.assert_array_equal(ds["participation"].isel(model=0, energy=0, lane=0, realization=0).values, 2 * fresh)
    np.testing.assert_array_equal(ds["participation"].isel(model=0, energy=0, lane=0, realization=1).values,
                                  run_group(study, 1)["participation"].values[0])


def test_run_study_reports_progress_at_every_decade_of_time_not_once_per_batch():
    calls = []
    run_study({"lattice": {"model": "fput", "N": 16, "realizations": 2}, "excitation": {"energies": [0.5]},
               "integration": {"dt": 0.05, "t_final": 1000.0}}, progress=lambda done, total: calls.append((done, total)))
    done = [d for d, _ in calls]
    # one batch of 2 orbits: a report at the first sample, as t passes 10 and 100, and at the end
    assert len(calls) >= 4 and all(t == 2 for _, t in calls)
    assert done == sorted(done) and done[-1] == 2 and 0 < done[-2] < 2
