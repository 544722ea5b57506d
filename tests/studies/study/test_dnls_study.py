"""A study of a split model (the DNLS chain): its lattices, its block excitations, its second
conserved quantity recorded and judged, its packet observables on the norm density; and the
studies kept before these keys existed still usable."""

import numpy as np
import pytest

from chainchaos.errors import StudyError
from chainchaos.records import kept
from chainchaos.studies.study import run_study
from chainchaos.studies.study.runs import DNLS_TIME_COMMENT, STUDY_RESULT_VERSION, group_settings, time_comment
from chainchaos.studies.study.spec import kept_group_path, load_study, study_names
from chainchaos.system.chain import dnls_chain

SPEC = {"lattice": {"model": ["dnls", "dnls_linear"], "N": 32, "W": 4.0, "beta": 0.72, "realizations": 2,
                    "first_seed": 3},
        "excitation": {"kind": "block", "width": 5, "phases": "random", "energies": [5.0]},
        "integration": {"integrator": "s9ABC6", "dt": 0.1, "t_final": 100.0, "samples_per_decade": 5},
        "observables": ["participation", "second_moment", "mlce", "norm_error"], "figures": ["spreading", "chaos"]}


def test_a_dnls_study_runs_on_dnls_lattices_and_keeps_the_norm_error():
    study = load_study(SPEC)
    assert study.lattices("dnls")[1].eps.tolist() == dnls_chain(4, 4.0, 32, 0.72).eps.tolist()
    assert study.lattices("dnls")[0].beta == 0.72 and time_comment(study) == DNLS_TIME_COMMENT
    q, p, _ = study.excitation(1).state("dnls", study.lattices("dnls")[1], 5.0)
    assert np.sum(q**2 + p**2) / 2 == pytest.approx(5.0, rel=1e-15)
    ds = run_study(SPEC)
    assert (ds["valid"] == 1).all()
    error = ds["norm_error"].max(dim="time")  # judged as the energy error: valid orbits stay within the bound
    assert 0 < float(error.min()) and float(error.max()) <= study.settings.max_energy_error
    P = ds["participation"].isel(time=-1)
    assert float(P.min()) >= 1 and float(P.max()) <= 32  # on the norm density, a distribution over 32 sites
    assert float(ds["mlce"].sel(model="dnls").isel(time=-1).min()) > 0


@pytest.mark.parametrize("change, message", [
    ({"lattice": {**SPEC["lattice"], "model": ["dnls", "kg"]}}, "bond models only or split models only"),
    ({"integration": {**SPEC["integration"], "integrator": "SRKN6b"}}, "a scheme of the models' kind"),
])
def test_a_study_mixing_kinds_of_model_or_scheme_is_refused(change, message):
    with pytest.raises(StudyError, match=message):
        load_study({**SPEC, **change})


def test_the_kept_studies_are_keyed_by_todays_settings():
    """Keys added since (lattice.beta, excitation.phases) leave the kept groups usable at their defaults."""
    for name in study_names():
        study = load_study(name)
        for group in range(study.n_groups):
            path = kept_group_path(name, group)
            if path is not None and path.exists():
                assert kept.why_not_usable(path, group_settings(study, group), STUDY_RESULT_VERSION, "remake") is None


def test_the_kernels_of_a_split_model_are_warmed_up_for_the_workflow():
    """compile_kernels (the workflow's warm-up) runs a split model's engines and observables (not
    the numerics' measured runs, which are the bond models')."""
    from chainchaos.run.warmup import warm_up

    warm_up(["dnls"])


def test_a_self_trapped_packet_is_said_so_not_fitted_as_a_spreading_law():
    """beta S = 12 on one site traps most of the norm there (FKS 2009's self-trapping); S = 1 does
    not: the law of m2 records the fraction of realizations self-trapped over its window."""
    from chainchaos.studies.study.laws import laws

    spec = {"lattice": {"model": "dnls", "N": 64, "W": 4.0, "beta": 1.0, "realizations": 4},
            "excitation": {"energies": [1.0, 12.0]},
            "integration": {"integrator": "s9ABC6", "dt": 0.05, "t_final": 1000.0},
            "observables": ["participation", "second_moment", "largest_share", "mlce"],
            "laws": {"t_min": 10.0, "bootstrap": 100,
                     "fits": [{"series": "second_moment", "expected": 1 / 3, "reference": "FKS 2009"},
                              {"series": "mlce", "expected": -0.25, "reference": "Senyange et al. 2018"}]}}
    study = load_study(spec)
    found = laws(run_study(spec), study.spec, study.settings, study.N)["self_trapped"].sel(model="dnls")
    assert found.isel(energy=0, law=0) == 0 and found.isel(energy=1, law=0) == 1
    assert np.isnan(found.isel(law=1)).all()  # Lambda is not a spreading law
