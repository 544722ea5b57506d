"""The paper's scenes as studies: the ensembles of perturbed orbits on which its statements are judged.

The ensemble verdicts of a model's scenes on the chosen chain (config ``verdicts``, workflow rule
``ensemble_verdicts``) and the realization search's filter runs and scored ensembles on
candidate chains (``studies.search.stages``) are studies (``studies.study``): a model, its scenes'
energies, the bead of the excitation, lanes and settings. Their orbits are integrated and grouped
by the study's mechanism; what is the paper's own is the step after it, which reads a scene's
orbits back (:func:`scene_runs`) and judges the statements on them (``verdicts.evaluate``).
"""

from dataclasses import asdict

import numpy as np
import xarray as xr

from chainchaos.paper import statements
from chainchaos.paper.criteria import Criteria
from chainchaos.run.orbits import OrbitSettings
from chainchaos.studies.study.orbits import StudySettings, settings_blocks
from chainchaos.studies.study.runs import orbit_runs

#: The series a scene's orbit keeps for its statements' verdicts (``orbits.SERIES``, and with
#: ``alignment`` ln GALI_k and SALI), in the order the verdict files hold them.
SCENE_SERIES = ("participation", "log_growth", "eta", "energy_error")
ALIGNMENT_SERIES = ("log_gali", "sali")


def verdict_study_name(model: str) -> str:
    """The name of the study of ``model``'s scenes on the chosen chain (its files: ``results/studies/<name>/``)."""
    return f"verdicts_{model}"


def scenes_study(name: str, model: str, energies, lattice: dict, settings: OrbitSettings, lanes: int, site: int,
                 criteria: Criteria, title: str, realizations_per_job: int | None = None) -> dict:
    """A study (the keys of a study file) of ``model``'s orbits at ``energies`` on ``lattice``.

    Parameters
    ----------
    name : str
        The study's name.
    model : str
        The model of the registry.
    energies : sequence of float
        Total energies H of the scenes, in their order.
    lattice : dict
        The study's ``lattice`` block without ``model``: ``{"chain_file": path}`` or
        ``{"seeds": [...], "N": N, "alpha": alpha}``.
    settings : OrbitSettings
        Integration and sampling; with ``alignment`` the orbits keep ln GALI_k and SALI.
    lanes : int
        Orbits per energy and realization (lane 0 unperturbed).
    site : int
        The excited bead (1-based), displaced alone.
    criteria : Criteria
        The claims' criteria; their ``gali_threshold`` stops an orbit's GALI vectors.
    title : str
        The title its files state.
    realizations_per_job : int, optional
        Chains whose orbits (every energy and lane) one job integrates; default all of them.

    Returns
    -------
    dict
        The study's keys, for ``studies.study.spec.load_study``.
    """
    study_settings = StudySettings.from_config({**asdict(settings), "gali_threshold": float(criteria.gali_threshold)})
    blocks = settings_blocks(study_settings)
    per_job = realizations_per_job or len(lattice.get("seeds") or [None])
    return {
        "name": name, "title": title, "lattice": {"model": model, **lattice},
        "excitation": {"kind": "site", "variable": "displacement", "site": int(site),
                       "energies": [float(e) for e in energies]},
        **blocks, "ensemble": {**blocks["ensemble"], "lanes": int(lanes)},
        "observables": [*scene_series(settings.alignment)],
        "jobs": {"orbits_per_job": int(lanes) * len(energies) * int(per_job)},
        "figures": [],
    }


def scene_series(alignment: bool) -> tuple[str, ...]:
    """The series a scene's orbits keep: :data:`SCENE_SERIES`, with ``alignment`` also :data:`ALIGNMENT_SERIES`."""
    return (*SCENE_SERIES, *(ALIGNMENT_SERIES if alignment else ()))


def verdict_study(model: str, verdicts: dict, claims: dict | None, site: int, chain_file) -> dict:
    """The study of ``model``'s statement scenes on the chosen chain (the file ``chain_file``),
    excited at bead ``site``: ``verdicts["lanes"]`` orbits per scene with the orbit settings
    ``verdicts["settings"]`` (the pipeline's config block ``verdicts``), judged by the criteria
    ``claims`` (its block ``claims``)."""
    scenes = statements.statement_scenes()
    names = statements.statement_scenes_by_model()[model]
    return scenes_study(verdict_study_name(model), model, [scenes[n].energy for n in names],
                        {"chain_file": str(chain_file)}, OrbitSettings.from_config(verdicts["settings"]),
                        int(verdicts["lanes"]), int(site), Criteria.from_config(claims),
                        f"Ensembles of the {model} scenes of the paper's statements on the chosen chain")


def study_runs(groups: list[xr.Dataset]) -> tuple[np.ndarray, dict[tuple[int, int], list[dict]]]:
    """The orbits of a study made by :func:`scenes_study`, as ``orbits.integrate`` returns them.

    Parameters
    ----------
    groups : list of xarray.Dataset
        The study's group files (``studies.study.runs.run_group``), all or some of them.

    Returns
    -------
    times : numpy.ndarray
        The sample times.
    runs : dict
        ``(energy index, realization) -> list`` of the orbits of that scene and chain in lane
        order, each with the :func:`scene_series` the study keeps, ``u0``, ``max_gaps``, ``valid``.
    """
    found: dict[tuple[int, int], list] = {}
    for g in groups:
        series = [name for name in scene_series(True) if name in g]
        where = zip(g["energy_index"].values, g["realization"].values, g["lane"].values)
        for (e, r, lane), run in zip(where, orbit_runs(g, series)):
            found.setdefault((int(e), int(r)), []).append((int(lane), run))
    return groups[0]["time"].values, {key: [run for _, run in sorted(runs, key=lambda item: item[0])]
                                      for key, runs in found.items()}
