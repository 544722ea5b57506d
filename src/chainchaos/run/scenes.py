"""Integrate one scene (model, energy) and return its observables as an xarray Dataset.

Only the requested observables are computed (``chainchaos.observe.registry``, the registry of
what a scene file can hold): the tangent dynamics runs only for those that need it, gap
bookkeeping only for the gap observables, and modal energies only for the modal ones. The
relative energy error is always recorded: it is the guard of every run.
"""

from dataclasses import asdict, dataclass

import numpy as np
import xarray as xr

from chainchaos.engine.integrators import get_scheme
from chainchaos.engine.model_checks import load_model
from chainchaos.errors import require, require_finite_positive
from chainchaos.observe.registry import (
    ALIGNMENT,
    GAPS,
    NORM,
    OBSERVABLES,
    SPECTRUM,
    TANGENT,
    SampledRun,
    model_observables,
    needing,
    variables,
)
from chainchaos.records.provenance import provenance_attrs
from chainchaos.run import driver
from chainchaos.run.settings import RunSettings
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.models import MODELS, get_model


@dataclass(kw_only=True)
class SceneParameters(RunSettings):
    """A scene: a model at an energy, its excited bead (1-based), the observables its file holds
    and its name, integrated and sampled by the ``RunSettings`` it extends (every field of
    ``RunSettings`` is also a keyword here: ``t_final`` and ``dt`` are required).

    Parameters
    ----------
    model : str or Model
        A registered name, a ``Model`` of your own, or ``"module:NAME"`` / ``"file.py:NAME"``
        (``chainchaos.load_model``: checked and added); kept as the model's name.
    energy : float
        Total energy H of the excitation (> 0), in the model's energy unit.
    observables : tuple of str, optional
        Names among ``OBSERVABLES`` the scene's file holds; default the model's own
        (``registry.model_observables``). The relative energy error is always recorded.
    excited_site : int, optional
        The displaced bead or site, 1-based (default 21).
    name : str, optional
        The scene's name (default ``<model>_H<energy>``).
    t_final : float
        Final time, in the model's time unit (> 0).
    dt : float
        Time step, in the model's time unit (> 0, at most ``t_final``).
    integrator : str, optional
        A splitting scheme of ``SCHEMES`` (default ``"SRKN6b"``).
    samples_per_decade : int, optional
        Log-spaced samples per decade of time (default 40).
    t_first_sample : float, optional
        Time of the first sample after t = 0 (default 0.1, or dt if larger).
    check_every : int, optional
        Steps between finiteness checks and deviation-vector renormalisations (default 1000).
    k4_sign : float, optional
        Sign of the FPUT quartic coefficient: +1 (default) or -1.
    deviation_seed : int, optional
        Seed of the initial deviation vector (default 0).
    max_energy_error : float, optional
        The run stops (SimulationError) when its relative energy error exceeds this (default 1e-2).
    exponents : int, optional
        Lyapunov exponents where an observable needs the spectrum (default 0: all 2N).
    gali_order : int, optional
        k of GALI_k where an observable needs SALI or GALI (default 2).

    Examples
    --------
    >>> from chainchaos import SceneParameters
    >>> params = SceneParameters(model="hertz", energy=1.8, t_final=100.0, dt=0.01)
    >>> params.name, params.integrator, params.excited_site
    ('hertz_H1.8', 'SRKN6b', 21)
    """

    model: str
    energy: float
    observables: tuple | None = None  # None: the model's default ones (registry.model_observables)
    excited_site: int = 21
    name: str = ""

    def __post_init__(self):
        super().__post_init__()
        self.model = load_model(self.model).name
        require(not get_model(self.model).is_split, "model", self.model,
                f"a bond model for a scene, one of {sorted(m for m in MODELS if not MODELS[m].is_split)} (a split "
                "model, DNLS, runs in studies and from Python: Problem, sample)")
        require_finite_positive(self, "energy")
        if self.observables is None:
            self.observables = model_observables(self.model)
        unknown = [o for o in self.observables if o not in OBSERVABLES]
        require(not unknown, "observables", unknown, f"names among {list(OBSERVABLES)}")
        if not get_model(self.model).has_gaps:
            gaps = sorted(needing(GAPS) & set(self.observables))
            require(not gaps, "observables", gaps,
                    f"gap observables only with a model whose bonds open: {[m for m in MODELS if MODELS[m].has_gaps]}")
        if not get_model(self.model).is_split:
            norm = sorted(needing(NORM) & set(self.observables))
            require(not norm, "observables", norm,
                    f"norm observables only with a split model: {[m for m in MODELS if MODELS[m].is_split]}")
        self.observables = tuple(o for o in OBSERVABLES if o in set(self.observables) | {"energy_error"})
        if not self.name:
            self.name = f"{self.model}_H{self.energy:g}"


def scene_parameters(simulation: dict, overrides: dict, scene, name: str, observables) -> SceneParameters:
    """A scene of the paper (``panels.Scene``) as a run integrates it: the settings of every scene
    (the pipeline's config block ``simulation``), the scene's own overrides (``scenes: {name:
    ...}``) and the observables its panels use.

    Parameters
    ----------
    simulation : dict
        The settings of every scene (``SceneParameters`` keywords).
    overrides : dict
        Settings of this scene that replace those of ``simulation`` (empty: none).
    scene : chainchaos.paper.panels.Scene
        The scene's model and energy.
    name : str
        The scene's name (its key in ``scenes``).
    observables : iterable of str
        The observables its file holds.

    Returns
    -------
    SceneParameters
        The scene, validated.
    """
    params = {**simulation, **overrides}
    return SceneParameters(**params, model=scene.model, energy=scene.energy, observables=tuple(observables), name=name)


#: The settings that scenes integrated together in one batch must share: one step, one sampling
#: schedule, one force law. Energies, excited beads, deviation vectors and observables may differ.
BATCH_KEYS = ("model", "integrator", "dt", "t_final", "samples_per_decade", "t_first_sample", "check_every",
              "k4_sign", "exponents", "gali_order")


def batch_key(params: SceneParameters) -> tuple:
    """The values of ``BATCH_KEYS`` of a scene: scenes with equal keys may run in one batch.

    Parameters
    ----------
    params : SceneParameters
        The scene.

    Returns
    -------
    tuple
        Its model, scheme, step, length, sampling schedule, check interval, K4 sign, number of
        exponents and GALI order, in the order of ``BATCH_KEYS``.
    """
    return tuple(getattr(params, key) for key in BATCH_KEYS)


def _disorder_attrs(chain) -> dict:
    """The lattice's disorder strength as the scene file records it: a bead chain's alpha
    (radii ratio), a KG lattice's W."""
    return {"W": float(chain.W)} if hasattr(chain, "W") else {"alpha": float(chain.alpha)}


def simulate(chain, params: SceneParameters, progress=None) -> xr.Dataset:
    """Integrate one scene and return its Dataset (data contract: docs/conventions.md#scene-file).

    Parameters
    ----------
    chain : Chain or KGLattice
        The lattice of the model's kind: a bead chain (``random_chain``, ``chain_from_radii``, a
        chain file) or a KG lattice (``kg_chain``).
    params : SceneParameters
        Model, energy, excited bead, observables, scheme, step, length and sampling.
    progress : callable, optional
        Called as ``progress(t, fraction_done)`` after every sample but the first.

    Returns
    -------
    xarray.Dataset
        The scene's observables on the sample times, with its parameters and provenance as
        attributes.

    Raises
    ------
    SimulationError
        Naming the scene, the time and the value, when the state becomes non-finite or the
        relative energy error exceeds ``params.max_energy_error``.
    ParameterError
        For a lattice of the wrong kind for the model, or a bad parameter (named).

    Examples
    --------
    >>> from chainchaos import SceneParameters, random_chain, simulate
    >>> chain = random_chain(seed=879, alpha=5.0, N=40)
    >>> scene = simulate(chain, SceneParameters(model="hertz", energy=1.8, t_final=10.0, dt=0.01,
    ...                                         observables=("participation", "mlce")))
    >>> sorted(scene.data_vars)
    ['energy_error', 'initial_deviation', 'mlce', 'participation']
    >>> bool(scene.attrs["max_energy_error"] < 1e-6)
    True
    """
    return simulate_scenes(chain, [params], progress)[0]


def simulate_scenes(chain, scenes: list[SceneParameters], progress=None) -> list[xr.Dataset]:
    """Integrate scenes that share ``BATCH_KEYS`` together, one lane each, and return their
    Datasets in order. Several scenes run on the batch engine, a single one on
    ``integrators.advance``; every lane's numbers are those of the scene integrated alone.

    The tangent map runs when any scene needs it and gap counting when any counts gaps (neither
    changes the orbit); each Dataset holds only its own scene's observables.

    Parameters
    ----------
    chain : Chain or KGLattice
        The lattice every scene runs on.
    scenes : list of SceneParameters
        At least one scene; all share ``BATCH_KEYS``.
    progress : callable, optional
        Called as ``progress(t, fraction_done)`` after every sample but the first.

    Returns
    -------
    list of xarray.Dataset
        Each scene's Dataset, in order, as :func:`simulate` returns it.

    Raises
    ------
    SimulationError
        Naming the scene, when a state becomes non-finite or an energy error exceeds that
        scene's ``max_energy_error``.
    ParameterError
        For no scenes, scenes that do not share ``BATCH_KEYS``, or a lattice of the wrong kind.
    """
    scenes = list(scenes)
    require(len(scenes) >= 1, "scenes", len(scenes), "at least one scene")
    keys = {batch_key(s) for s in scenes}
    require(len(keys) == 1, "scenes", [s.name for s in scenes],
            f"scenes that share {list(BATCH_KEYS)}")
    first = scenes[0]
    model = get_model(first.model)
    wanted = set().union(*(set(s.observables) for s in scenes))
    problem = first.problem(model, [chain] * len(scenes), tangent=bool(wanted & needing(TANGENT)),
                            track_gaps=bool(wanted & needing(GAPS)), spectrum=bool(wanted & needing(SPECTRUM)),
                            alignment=bool(wanted & needing(ALIGNMENT)))
    chain = problem.chains[0]
    N, B = chain.N, len(scenes)
    Q0, P0, DQ0, DP0 = (np.zeros((N, B)) for _ in range(4))
    u0, deviation0 = np.zeros(B), np.zeros((B, 2 * N))
    XQ0, XP0 = (np.zeros((problem.extra_vectors, N, B)) for _ in range(2))
    for j, params in enumerate(scenes):
        Q0[:, j], P0[:, j], u0[j] = initial_state(model, chain, params.energy, params.excited_site)
        DQ0[:, j], DP0[:, j] = initial_deviation(N, params.deviation_seed)
        deviation0[j] = np.concatenate([DQ0[:, j], DP0[:, j]])
        XQ0[:, :, j], XP0[:, :, j] = params.extra_deviations(problem)
    if not problem.tangent:
        DQ0[:], DP0[:] = 0.0, 0.0
    monitors = [driver.EnergyGuard([s.name for s in scenes], [s.max_energy_error for s in scenes])]
    if progress is not None:
        monitors.append(driver.progress(progress))
    samples = driver.sample(problem, Q0, P0, DQ0, DP0, first.sample_steps(), monitors, xq0=XQ0, xp0=XP0)
    return [_dataset(chain, params, samples.run(j, deviation0[j]), u0[j], samples.H0[j])
            for j, params in enumerate(scenes)]


def _dataset(chain, params, run: SampledRun, u0, H0) -> xr.Dataset:
    N, times, energy_error = chain.N, run.times, run.energy_error
    data = variables(run, params.observables)
    ds = xr.Dataset(data, coords={"time": times, "site": np.arange(1, N + 1), "bond": np.arange(1, N + 2),
                                  "mode": np.arange(1, N + 1)})
    ds.time.attrs.update(units="1", long_name="time",
                         comment="nondimensional time, unit 1/omega_max of the homogeneous linear chain")
    ds.site.attrs.update(units="1", long_name="bead index n")
    ds.bond.attrs.update(units="1", long_name="bond index (bond n joins beads n-1 and n)")
    ds.mode.attrs.update(units="1", long_name="mode number, by increasing frequency")
    if "exponent" in ds.dims:
        ds = ds.assign_coords(exponent=np.arange(1, ds.sizes["exponent"] + 1))
        ds.exponent.attrs.update(units="1", long_name="index i of the Lyapunov exponent (deviation vector i of the QR)")
    parameters = {k: (list(v) if isinstance(v, tuple) else v) for k, v in asdict(params).items()}
    parameters["chain_seed"] = chain.seed
    ds.attrs.update(provenance_attrs(parameters))
    ds.attrs.update(
        title=f"chainchaos scene {params.name}", scene=params.name, model=params.model,
        energy=float(params.energy), total_energy=H0, u0=float(u0), dt=float(params.dt),
        integrator=params.integrator, integrator_order=get_scheme(params.integrator).order,
        t_final=float(times[-1]), K4_sign=float(params.k4_sign), excited_site=int(params.excited_site),
        seed=-1 if chain.seed is None else int(chain.seed), deviation_seed=int(params.deviation_seed),
        **_disorder_attrs(chain), observables=" ".join(params.observables),
        final_energy_error=float(energy_error[-1]), max_energy_error=float(energy_error.max()),
    )
    return ds
