"""The paper's scenes as studies (chainchaos.paper.ensembles): a study of a model's scenes holds the
orbits orbits.integrate gives for the same models, energies, chain, bead and lanes (a bit-identity
test between two paths of the package: the study is how every ensemble now runs), and the verdict
studies follow the config's verdicts block."""

import numpy as np
import pytest
import yaml

from chainchaos.paper import statements
from chainchaos.paper.criteria import Criteria
from chainchaos.paper.ensembles import scene_series, scenes_study, study_runs, verdict_study
from chainchaos.run.orbits import Orbit, OrbitSettings, integrate
from chainchaos.studies.study.runs import run_group
from chainchaos.studies.study.spec import load_study
from chainchaos.system.chain import random_chain
from conftest import ROOT

SETTINGS = {"integrator": "SRKN6b", "dt": 0.01, "t_final": 200.0, "samples_per_decade": 10, "t_first_sample": 1.0,
            "final_samples": 20, "check_every": 1000, "perturbation": 1e-9, "max_energy_error": 1e-2,
            "gali_order": 4}


@pytest.mark.parametrize("alignment", [False, True])
def test_a_scene_study_holds_the_orbits_integrate_gives(alignment):
    settings = OrbitSettings.from_config({**SETTINGS, "alignment": alignment})
    criteria = Criteria.from_config({})
    seeds, energies, lanes = [879, 5], [0.5, 1.8], 3
    spec = scenes_study("s", "hertz", energies, {"seeds": seeds, "N": 40, "alpha": 5.0}, settings, lanes, 21,
                        criteria, "test")
    study = load_study(spec)
    assert study.n_groups == 1 and study.lanes == lanes
    times, found = study_runs([run_group(study, 0)])
    orbits = [Orbit(model="hertz", energy=e, chain=random_chain(s, 5.0, 40), site=21, lane=lane)
              for s in seeds for e in energies for lane in range(lanes)]
    t, runs = integrate(orbits, settings, gali_stop=np.log(criteria.gali_threshold))
    assert set(scene_series(alignment)) <= set(runs[0])
    for c, seed in enumerate(seeds):
        for k, energy in enumerate(energies):
            mine = found[k, c]
            assert times.tobytes() == t.tobytes() and len(mine) == lanes
            for lane, run in enumerate(mine):
                theirs = runs[(c * len(energies) + k) * lanes + lane]
                for name in scene_series(alignment):
                    assert run[name].tobytes() == theirs[name].tobytes(), (seed, energy, lane, name)
                assert (run["u0"], run["valid"], run["max_gaps"]) == (theirs["u0"], theirs["valid"], theirs["max_gaps"])


def test_the_verdict_studies_follow_the_verdicts_block():
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    block = config["verdicts"]
    for model, names in statements.statement_scenes_by_model().items():
        study = load_study(verdict_study(model, block, config["claims"], config["simulation"]["excited_site"],
                                         f"{config['results']}/chain/chain.nc"))
        scenes = statements.statement_scenes()
        assert study.models == [model] and study.lanes == block["lanes"] and study.n_groups == 1
        assert study.energies.tolist() == [scenes[name].energy for name in names]
        assert study.spec["lattice"]["chain_file"] == f"{config['results']}/chain/chain.nc"
        assert study.spec["excitation"]["site"] == config["simulation"]["excited_site"]  # (the chain file: made by the run)
        for key in ("integrator", "dt", "t_final", "final_samples", "samples_per_decade", "max_energy_error"):
            assert getattr(study.settings, key) == block["settings"][key], key
        assert study.settings.alignment == block["settings"]["alignment"]
        assert study.settings.gali_threshold == Criteria.from_config(config.get("claims")).gali_threshold
