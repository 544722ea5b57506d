"""The registry of scene observables (chainchaos.observe.registry) and the panel table that reads it."""

import numpy as np

from chainchaos.observe.registry import (ALIGNMENT, GAPS, MODES, NORM, OBSERVABLES, REGISTRY, SPECTRUM, TANGENT,
                                        needing)
from chainchaos.paper import panels
from chainchaos.run.scenes import SceneParameters, simulate
from chainchaos.system.chain import random_chain


def test_every_panel_reads_registered_observables():
    for kind, names in panels.KIND_OBSERVABLES.items():
        assert set(names) <= set(OBSERVABLES), kind


def test_companions_are_registered_and_only_written_along():
    companions = {c for o in REGISTRY.values() for c in o.companions}
    assert companions <= set(REGISTRY)
    assert {n for n, o in REGISTRY.items() if not o.selectable} == companions
    for name in companions:  # a companion needs what the observables that bring it need
        bringers = [o for o in REGISTRY.values() if name in o.companions]
        assert all(REGISTRY[name].needs <= o.needs for o in bringers), name


def test_each_observable_is_written_alone_with_its_dims_and_nothing_it_does_not_need():
    chain = random_chain(879, 5.0)
    for name in (o for o in OBSERVABLES if o not in needing(NORM)):  # the norm's: a split model's
        ds = simulate(chain, SceneParameters(model="hertz", energy=1.8, t_final=20.0, dt=0.01, observables=(name,),
                                             samples_per_decade=4))
        o = REGISTRY[name]
        assert set(ds.data_vars) == {name, "energy_error", *o.companions}, name
        assert ds[name].dims == o.dims and ds[name].attrs["long_name"] == o.long_name
        values = ds[name].values[1:]
        if values.dtype.kind == "f":
            assert np.isfinite(values).all(), name
        else:  # the integer observables are counts (gaps, steps)
            assert values.dtype.kind in "iu" and (values >= 0).all() and values.any(), name


def test_needs_split_the_observables_as_the_engines_run_them():
    assert needing(TANGENT) == {"mlce", "log_growth", "dvd", "dvd_participation", "lyapunov_spectrum", "ks_entropy",
                                "sali", "log_gali"}
    assert needing(GAPS) == {"gap_open", "gap_fraction", "n_gaps"}
    assert needing(MODES) == {"mode_energy", "spectral_entropy", "eta"}
    assert needing(SPECTRUM) == {"lyapunov_spectrum", "ks_entropy"} and needing(ALIGNMENT) == {"sali", "log_gali"}
    assert needing(SPECTRUM) | needing(ALIGNMENT) <= needing(TANGENT)
    assert needing(NORM) == {"norm_density", "norm_error"}
