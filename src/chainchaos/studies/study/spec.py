"""A study from one file: ``studies/<name>.yaml`` (or a dict), validated, completed and resolved.

A study asks one question of the engines: these chains (a model or several, N beads, a disorder
strength, realizations as seeds, or one chain from a file), this excitation at these energies,
this integration, these observables per orbit, this many perturbed lanes per realization, these
figures. :func:`load_study` reads it against the schema beside this module (every key described
there and in the generated ``studies/README.md``), fills the schema's defaults, resolves ``extends``
and checks what holds between keys (an excited site beyond N, a mode above N, a step longer than
the run), each wrong key named in one line with what is allowed. The :class:`Study` it returns
says which orbits exist, in a fixed order, and how they are cut into jobs; its results do not
depend on that cut.
"""

import copy
import math
from importlib import resources
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from chainchaos.engine.integrators import SCHEMES
from chainchaos.engine.model_checks import load_model
from chainchaos.engine.split_schemes import SPLIT_SCHEMES
from chainchaos.errors import ParameterError, StudyError, require
from chainchaos.observe.own import OWN, is_reference, load_observable
from chainchaos.observe.registry import NORM, REGISTRY, study_observables
from chainchaos.project import project_root
from chainchaos.run.orbits import ALIGNMENT_SERIES, Orbit, map_samples, sample_schedule
from chainchaos.run.window import Window
from chainchaos.studies.study.orbits import (
    StudySettings,
    energy_grid,
    select_excitation,
)
from chainchaos.system.chain import dnls_lattice, kg_lattice, random_chain
from chainchaos.system.geometry import Geometry
from chainchaos.system.initial import Excitation
from chainchaos.system.models import BEAD_MODELS, MODELS

#: The schema of a study file, a file of the package (its keys: ``studies/README.md``).
SCHEMA = Path(str(resources.files("chainchaos.studies.study") / "schema.yaml"))


def kept_group_path(name: str, group: int, root=None) -> Path | None:
    """Where group ``group`` of study ``name`` is kept (``snakemake --cores 2 keep --config
    keep=<name>``): ``<root>/<name>/groups/<group>.nc``, ``root`` by default ``data/studies``
    beside the ``studies/`` of :func:`studies_dir` (the workflow's config ``kept_studies``); None
    outside a project (an installed package: nothing is kept there).

    Parameters
    ----------
    name : str
        The study's name.
    group : int
        The group's index (0-based).
    root : path, optional
        The folder of kept studies (default ``data/studies`` beside :func:`studies_dir`).

    Returns
    -------
    pathlib.Path or None
        The group's file (which need not exist), or None outside a project.
    """
    if root is None:
        try:
            root = studies_dir().parent / "data" / "studies"
        except FileNotFoundError:
            return None
    return Path(root) / name / "groups" / f"{group:04d}.nc"


def studies_dir() -> Path:
    """Where a study named without a path is looked up: ``./studies`` when the working directory
    has one, else the project's (``chainchaos.project.project_root``).

    Returns
    -------
    pathlib.Path
        The folder.

    Raises
    ------
    FileNotFoundError
        Outside a project, when the working directory has no ``studies/`` either.
    """
    here = Path.cwd() / "studies"
    if here.is_dir():
        return here
    return project_root(f"a study named without a path ({Path.cwd()} has no studies/)") / "studies"


#: A study's standard figures (``output.plotting.study``), by name.
FIGURES = ("spreading", "chaos", "fractions", "maps")
#: Series every orbit keeps whatever the study asks: P judges delocalization, ln|v| chaos by Lambda.
JUDGED = ("participation", "log_growth")
#: The observables each figure draws beyond :data:`JUDGED` (``comparison``: beside other studies).
FIGURE_OBSERVABLES = {"spreading": ("second_moment",), "chaos": ("mlce",), "fractions": (), "maps": (),
                      "comparison": ("second_moment", "mlce")}


def _defaults(schema: dict, block: dict) -> dict:
    """``block`` with the schema's defaults filled in, object by object (a copy). An optional
    block (type object or null, no default: ``integration.window``) is filled only where given,
    so that an absent one stays absent from the study's settings."""
    out = dict(block)
    for key, sub in schema.get("properties", {}).items():
        if key not in out and "default" in sub:
            out[key] = copy.deepcopy(sub["default"])
        if sub.get("type") == "object":
            out[key] = _defaults(sub, out.get(key) or {})
        elif "object" in sub.get("type", ()) and isinstance(out.get(key), dict):
            out[key] = _defaults(sub, out[key])
    return out


def _read(source, root: Path | None) -> tuple[str, dict]:
    """(name, raw dict) of a study named, given by path or given as a dict."""
    import yaml

    from chainchaos.records.schema import load_yaml

    if isinstance(source, dict):
        return str(source.get("name", "study")), {k: v for k, v in source.items() if k not in ("name", "directory")}
    path = Path(source)
    if path.suffix not in (".yaml", ".yml"):
        root = studies_dir() if root is None else root
        path = root / f"{source}.yaml"
    if not path.is_file():
        raise StudyError([f"study {str(source)!r}: no file {path}; studies here: {study_names(root)}"])
    try:
        raw = load_yaml(path.read_text())
    except yaml.YAMLError as err:
        raise StudyError([f"study file {path}: not YAML ({str(err).splitlines()[0]})"]) from None
    if not isinstance(raw, dict):
        raise StudyError([f"study file {path}: a mapping of keys is needed, not {type(raw).__name__}"])
    return path.stem, raw


def _merged(raw: dict, root: Path | None, seen: tuple = ()) -> dict:
    """``raw`` over the study it extends: its blocks' keys replace the other's, block by block."""
    parent = raw.get("extends")
    if not parent:
        return raw
    if parent in seen:
        raise StudyError([f"study key extends = {parent!r}: the studies extend each other ({' -> '.join(seen)})"])
    name, base = _read(parent, root)
    base = _merged(base, root, (*seen, name))
    out = {k: v for k, v in base.items() if k != "extends"}
    for key, value in raw.items():
        out[key] = {**out[key], **value} if isinstance(value, dict) and isinstance(out.get(key), dict) else value
    out["extends"] = parent
    return out


def _directory(source, root: Path | None) -> Path:
    """Where a model file named by the study (``lattice.model: morse.py:MORSE``) is looked up
    first: the study file's directory (``root`` for a study named; for a dict, its ``directory``
    or the working directory)."""
    if isinstance(source, dict):
        return Path(source.get("directory") or Path.cwd())
    path = Path(source)
    if path.suffix in (".yaml", ".yml"):
        return path.parent
    return studies_dir() if root is None else root


def _model_list(raw: dict) -> list:
    model = (raw.get("lattice") or {}).get("model") if isinstance(raw.get("lattice"), dict) else None
    return [model] if isinstance(model, str) else list(model) if isinstance(model, list) else []


def _model_errors(raw: dict, directory: str) -> list[str]:
    """The study's own models (``module:NAME`` or ``file.py:NAME``), loaded and checked
    (``engine.model_checks.load_model``): one line per model that cannot be."""
    errors = []
    for model in _model_list(raw):
        if isinstance(model, str) and ":" in model:
            try:
                load_model(model, directory)
            except ParameterError as err:
                errors.append(f"study key lattice.model = {model!r}: allowed is {err.allowed}")
    return errors


def _with_model_names(raw: dict, directory: str) -> dict:
    """``raw`` with the study's own models named by their registered names, for the schema (whose
    allowed models are the registry's)."""
    if not any(isinstance(m, str) and ":" in m for m in _model_list(raw)):
        return raw
    names = [load_model(m, directory).name if isinstance(m, str) and ":" in m else m for m in _model_list(raw)]
    model = raw["lattice"]["model"]
    return {**raw, "lattice": {**raw["lattice"], "model": names[0] if isinstance(model, str) else names}}


def _observable_errors(raw: dict, directory: str) -> list[str]:
    """The study's observables of its own (``file.py:NAME``, ``module:NAME``), loaded, checked
    and registered (``observe.own.load_observable``): one line per observable that cannot be."""
    errors = []
    for name in raw.get("observables") or []:
        if is_reference(name):
            try:
                load_observable(name, directory)
            except ParameterError as err:
                errors.append(f"study key observables = {name!r}: allowed is {err.allowed}")
    return errors


def _with_observable_names(raw: dict) -> dict:
    """``raw`` with its observables of its own named by their registered names, for the schema."""
    if not any(name in OWN.values() for name in raw.get("observables") or []):
        return raw
    names = {reference: name for name, reference in OWN.items()}
    return {**raw, "observables": [names.get(o, o) for o in raw["observables"]]}


def check_observable(observable, model, lattice) -> None:
    """Run an observable of one's own (``observe.own``) on a short orbit of ``model`` on
    ``lattice`` (a few steps from one displaced site) and require a float per sample, not all NaN.

    Parameters
    ----------
    observable : chainchaos.observe.registry.Observable
        The observable.
    model : str or Model
        A model of the study.
    lattice : Chain, KGLattice or DNLSLattice
        A lattice of the study (a realization of it).

    Raises
    ------
    ParameterError
        Naming the observable and what it gave.
    """
    from chainchaos.engine.problem import Problem
    from chainchaos.run.driver import sample, sample_steps

    N = lattice.N
    q, p = np.zeros((N, 1)), np.zeros((N, 1))
    q[N // 2] = 0.3
    dq, dp = np.zeros((N, 1)), np.full((N, 1), 1.0 / np.sqrt(N))
    problem = Problem(model, [lattice], dt=0.01, check_every=10)
    samples = sample(problem, q, p, dq, dp, sample_steps(0.1, 0.01, 2, 0.05))
    run = samples.run(0, np.concatenate([dq[:, 0], dp[:, 0]]))
    try:
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):  # as the study's jobs compute it
            values = np.asarray(observable.compute(run), dtype=float)
    except Exception as err:  # the user's code: whatever it raises is reported as its failure
        raise ParameterError("observable", observable.name, f"a compute(run) that runs ({type(err).__name__}: {err})")
    require(values.shape == run.times.shape and bool(np.any(np.isfinite(values))), "observable", observable.name,
            f"a float per sample (NaN where it is not defined), shape {run.times.shape}, not all NaN "
            f"(got shape {values.shape})")


def load_study(source, root: Path | None = None, *, read_files: bool = True) -> "Study":
    """The ``Study`` of ``source``, checked against the study schema.

    Parameters
    ----------
    source : str, path or dict
        A name (``studies/<name>.yaml``), a path to a YAML file, or a dict of the file's keys
        (with an optional ``name``, and ``directory`` where a model file it names is).
    root : path, optional
        Where a study named without a path is looked up; default ``./studies`` when the working
        directory has one, else the checkout's ``studies/``.
    read_files : bool, optional
        Check the keys against the chain file ``lattice.chain_file`` names (its bead count, when it
        exists); False checks the keys alone, as the workflow does while it plans (the jobs read
        the file).

    Returns
    -------
    Study
        The study's keys, with ``extends`` resolved and the defaults filled in.

    Raises
    ------
    StudyError
        Listing every wrong key, each with its value and what is allowed.

    Examples
    --------
    >>> from chainchaos import load_study
    >>> study = load_study({"name": "small", "lattice": {"model": ["hertz", "fput"], "N": 16, "realizations": 4},
    ...                     "excitation": {"energies": [0.5, 1.0]}, "integration": {"t_final": 100.0, "dt": 0.01}})
    >>> study.models, study.energies.tolist(), study.realizations
    (['hertz', 'fput'], [0.5, 1.0], 4)
    >>> load_study({"lattice": {"model": "morse", "N": 16}, "excitation": {"energies": [0.5]},
    ...             "integration": {"t_final": 100.0, "dt": 0.01}})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    chainchaos.errors.StudyError: invalid study (keys: studies/README.md):
      study key lattice.model = 'morse': allowed is ...
    """
    from chainchaos.records.schema import load_schema, nonfinite_errors, schema_errors

    root = None if root is None else Path(root)  # looked up only for a study named, or one it extends
    name, raw = _read(source, root)
    raw = _merged(raw, root)
    directory = str(_directory(source, root))
    errors = _model_errors(raw, directory) + _observable_errors(raw, directory)
    schema = load_schema(SCHEMA)  # after one's own models and observables are registered: the schema allows them
    errors = errors or schema_errors(_with_observable_names(_with_model_names(raw, directory)), schema,
                                     "study key") or nonfinite_errors(raw, what="study key")
    if errors:
        raise StudyError(errors)
    spec = _defaults(schema, raw)
    if "figures" not in raw:  # by default, the standard figures whose series the study computes
        spec["figures"] = [figure for figure in FIGURES
                           if all(name in spec["observables"] for name in FIGURE_OBSERVABLES[figure])
                           and (figure != "maps" or spec["integration"].get("map_times"))]
    study = Study(name, spec, directory)
    study.check(read_files)
    return study


@dataclass(frozen=True)
class Study:
    """A validated study: ``name`` and ``spec``, the file's keys with every default filled in;
    ``directory``, where a model file it names is looked up first.

    Made by :func:`load_study`, which checks the keys; the properties below read them resolved.

    Parameters
    ----------
    name : str
        The study's name (its file's stem).
    spec : dict
        The study file's keys, ``extends`` resolved and every default filled in
        (``studies/README.md``).
    directory : str, optional
        Where a model file the study names is looked up first (default ``"."``).
    """

    name: str
    spec: dict
    directory: str = "."

    # ---- what the file says, resolved ------------------------------------------------------

    @property
    def title(self) -> str:
        """The study's title (``title``, or ``study <name>``)."""
        return self.spec.get("title") or f"study {self.name}"

    @cached_property
    def models(self) -> list[str]:
        """The names of the study's models in the registry, its own models (``module:NAME``,
        ``file.py:NAME``, looked up from :attr:`directory`) loaded and added."""
        model = self.spec["lattice"]["model"]
        return [load_model(m, self.directory).name for m in ([model] if isinstance(model, str) else model)]

    @cached_property
    def energies(self) -> np.ndarray:
        """The energies: as given, or the grid of ``{min, max, n, spacing}`` (``orbits.energy_grid``)."""
        energies = self.spec["excitation"]["energies"]
        if isinstance(energies, dict):
            return energy_grid({"n_energies": energies["n"], "energy_min": energies["min"],
                                "energy_max": energies["max"], "spacing": energies.get("spacing", "log")})
        return np.atleast_1d(np.asarray(energies, dtype=np.float64))

    @property
    def n_energies(self) -> int:
        """Number of energies, from the keys alone (a grid's is not computed: the workflow plans
        its jobs without the kernels that compute it)."""
        energies = self.spec["excitation"]["energies"]
        return int(energies["n"]) if isinstance(energies, dict) else int(np.size(energies))

    @property
    def seeds(self) -> list[int]:
        """The seed of every realization: ``lattice.seeds``, or ``first_seed`` onwards (-1 for a
        chain file's chain drawn from no seed)."""
        lattice = self.spec["lattice"]
        if lattice["chain_file"]:
            return [self.file_chain.seed if self.file_chain.seed is not None else -1]
        if lattice["seeds"]:
            return [int(s) for s in lattice["seeds"]]
        return [int(lattice["first_seed"]) + r for r in range(int(lattice["realizations"]))]

    @property
    def realizations(self) -> int:
        """Number of realizations (one for a chain file, known before the file exists)."""
        lattice = self.spec["lattice"]
        if lattice["chain_file"]:
            return 1
        return len(lattice["seeds"]) if lattice["seeds"] else int(lattice["realizations"])

    @property
    def lanes(self) -> int:
        """Orbits per realization and energy (``ensemble.lanes``): lane j >= 1 a perturbed copy."""
        return int(self.spec["ensemble"]["lanes"])

    @property
    def observables(self) -> list[str]:
        """The per-orbit series the study keeps (``observables``; one of its own by its registered
        name), each once."""
        names = {reference: name for name, reference in OWN.items()}
        return list(dict.fromkeys(names.get(o, o) for o in self.spec["observables"]))

    @property
    def map_times(self) -> list[float]:
        """The times at which every orbit's density is kept as a map (``integration.map_times``;
        empty: none)."""
        return [float(t) for t in self.spec["integration"].get("map_times") or []]

    @property
    def alignment(self) -> bool:
        """GALI_k's vectors are evolved: ln GALI_k or SALI is kept."""
        return any(name in ALIGNMENT_SERIES for name in self.observables)

    @cached_property
    def window(self) -> Window | None:
        """The growing window of ``integration.window`` (None: the whole chain)."""
        return Window.from_config(self.spec["integration"].get("window"))

    @cached_property
    def settings(self) -> StudySettings:
        """Integration, lanes and criteria of every orbit."""
        spec = self.spec
        return StudySettings.from_config({**spec["integration"], **spec["ensemble"], **spec["criteria"],
                                         "alignment": self.alignment, "engine": "batch"})

    @cached_property
    def file_chain(self):
        """The chain of ``lattice.chain_file``, read (``records.io.read_chain``)."""
        from chainchaos.records.io import read_chain

        return read_chain(self.spec["lattice"]["chain_file"])

    @cached_property
    def chains(self) -> list:
        """One bead chain per realization, in the order of :attr:`seeds`."""
        lattice = self.spec["lattice"]
        if lattice["chain_file"]:
            return [self.file_chain]
        return [random_chain(seed, float(lattice["alpha"]), self.N, float(lattice["wall_radius"]))
                for seed in self.seeds]

    @cached_property
    def kg_lattices(self) -> list:
        """One Klein-Gordon lattice per realization (disorder strength W), in the order of :attr:`seeds`."""
        lattice = self.spec["lattice"]
        return [kg_lattice(seed, float(lattice["W"]), self.geometry.shape, lattice["boundary"]) for seed in self.seeds]

    @cached_property
    def dnls_lattices(self) -> list:
        """One DNLS lattice per realization (disorder strength W, nonlinearity beta), in the order
        of :attr:`seeds`."""
        lattice = self.spec["lattice"]
        return [dnls_lattice(seed, float(lattice["W"]), self.geometry.shape, float(lattice["beta"]),
                             lattice["boundary"]) for seed in self.seeds]

    def lattices(self, model: str) -> list:
        """The realizations ``model`` runs on: KG lattices for a KG model, DNLS lattices for a
        DNLS model, else bead chains.

        Parameters
        ----------
        model : str
            One of the study's models.

        Returns
        -------
        list of Chain, KGLattice or DNLSLattice
            One lattice per realization, in the order of :attr:`seeds`.
        """
        kind = MODELS[model].lattice
        return self.kg_lattices if kind == "kg" else self.dnls_lattices if kind == "dnls" else self.chains

    @property
    def N(self) -> int:
        """Number of sites of every lattice."""
        lattice = self.spec["lattice"]
        return self.file_chain.N if lattice["chain_file"] else self.geometry.N

    @cached_property
    def geometry(self) -> Geometry:
        """The shape of every lattice (``system.geometry``): ``lattice.shape``, or the chain of
        ``lattice.N`` sites, with ``lattice.boundary``."""
        lattice = self.spec["lattice"]
        if lattice["chain_file"]:
            return self.file_chain.geometry
        return Geometry(tuple(lattice["shape"] or [lattice["N"]]), lattice["boundary"])

    @property
    def selected(self) -> bool:
        """Each realization's site is chosen by the paper's excitation rule (site ``selected``)."""
        return self.spec["excitation"]["site"] == "selected"

    @cached_property
    def picks(self) -> list[dict]:
        """Per realization, what ``orbits.select_excitation`` picks (site ``selected``) in the
        lattices of the study's first model."""
        return [select_excitation(chain, **self.spec["excitation"]["selection"])
                for chain in self.lattices(self.models[0])]

    def excitation(self, realization: int = 0) -> Excitation:
        """The excitation of realization ``realization`` (they differ only with site ``selected``).

        Parameters
        ----------
        realization : int, default 0
            The realization's index (0-based).

        Returns
        -------
        chainchaos.system.initial.Excitation
            Its kind, variable, site (1-based), mode and width (``excitation``).
        """
        e = self.spec["excitation"]
        site = e["site"]
        if site == "centre":  # the middle site along each axis
            site = tuple((n + 1) // 2 for n in self.geometry.shape)
        if self.selected:
            site = self.picks[realization]["site"]
        site = tuple(int(v) for v in site) if isinstance(site, (list, tuple)) else int(site)
        return Excitation(kind=e["kind"], variable=e["variable"], site=site, mode=int(e["mode"]),
                          width=int(e["width"]), phases=e["phases"], seed=max(self.seeds[realization], 0))

    @property
    def series(self) -> dict:
        """The per-orbit series (name -> value where the state is not measured, as
        ``orbits.SERIES``): the ones asked for and the ones the verdicts read."""
        fills = {"log_growth": None, "mlce": None, "log_gali": None, "sali": None, "energy_error": np.inf}
        series = {name: fills.get(name, np.nan) for name in dict.fromkeys([*JUDGED, *self.observables])
                  if name not in ALIGNMENT_SERIES}
        return {**series, "density": None} if self.map_times else series

    # ---- checks between keys ----------------------------------------------------------------

    def _check_excitation(self) -> None:
        """ParameterError where the excitation does not fit the lattice."""
        excitation = self.excitation()
        if excitation.kind == "mode" or self.geometry.dimension == 1:
            excitation.check(self.N)
        else:
            excitation.lattice_sites(self.geometry)

    def check(self, read_files: bool = True) -> None:
        """Raise StudyError naming every key that does not fit the others.

        Parameters
        ----------
        read_files : bool, optional
            Also check the keys against the chain file ``lattice.chain_file`` names (its bead
            count), when the file exists.

        Raises
        ------
        StudyError
            Listing every wrong key, each with its value and what is allowed.
        """
        errors = []
        chain_file = self.spec["lattice"]["chain_file"]
        # a chain file absent (a rule of the workflow may make it) or not read: the keys alone
        known_chain = not chain_file or (read_files and Path(chain_file).exists())

        def check(key, test):
            try:
                test()
            except ParameterError as err:
                if key in ("integration", "ensemble", "criteria"):  # the block's key that the error names
                    block = next((b for b in ("integration", "ensemble", "criteria") if err.name in self.spec[b]), key)
                    key = f"{block}.{err.name}"
                elif key == "lattice":
                    key = {"window": "integration.window", "excitation.site": "excitation.site"}.get(
                        err.name, f"lattice.{err.name}")
                errors.append(f"study key {key} = {err.value!r}: allowed is {err.allowed}")

        def models():
            for model in self.models:
                if chain_file and MODELS[model].lattice != "beads":
                    raise ParameterError("model", model, f"a bead model with a chain file: {sorted(BEAD_MODELS)}")
            split = SPLIT_SCHEMES if MODELS[self.models[0]].is_split else SCHEMES
            integrator = self.spec["integration"].get("integrator", "SRKN6b")
            if integrator not in split:
                raise ParameterError("integrator", integrator, f"a scheme of the models' kind: one of {sorted(split)}")
            if len({MODELS[m].is_split for m in self.models}) > 1:
                raise ParameterError("model", self.models, "bond models only or split models only (their files hold "
                                     "different series: a split model's norm error)")

        def observables():
            allowed = study_observables()
            for name in self.observables:
                if name not in allowed:
                    raise ParameterError("observable", name, f"one of {allowed}")
            normed = [name for name in self.observables if NORM in REGISTRY[name].needs]
            unsplit = [m for m in self.models if not MODELS[m].is_split]
            if normed and unsplit:  # a norm is a split model's second conserved quantity
                raise ParameterError("observable", normed[0], f"an observable of the split models (DNLS), not of "
                                     f"{unsplit}")
            if read_files and known_chain:  # one's own, on a short orbit, before anything is integrated
                for name in self.observables:
                    if name in OWN:
                        check_observable(REGISTRY[name], self.models[0], self.lattices(self.models[0])[0])


        def figures():
            drawn = [*self.spec["figures"], *(["comparison"] if self.spec["compare_with"] else [])]
            if "maps" in drawn and not self.map_times:
                raise ParameterError("figures", "maps", "a figure of maps with integration.map_times given")
            for figure in drawn:
                missing = [name for name in FIGURE_OBSERVABLES[figure] if name not in self.observables]
                if missing:
                    raise ParameterError("figures", figure, f"a figure whose series the study computes: {figure} "
                                         f"draws {', '.join(missing)}, absent from observables {self.observables} "
                                         "(add it, or name the figures the study draws)")

        def laws():
            for fit in [*self.spec["laws"]["fits"], *self.spec["laws"]["crossovers"]]:
                needed = "mlce" if fit["series"] == "abs_mlce" else fit["series"]
                if needed not in self.observables:
                    raise ParameterError("series", fit["series"], f"a series of the observables {self.observables}")

        def walls():
            bound = self.spec["laws"]["walls"]["edge_energy"]
            if bound is not None and "edge_energy" not in self.observables:
                raise ParameterError("edge_energy", bound, "a bound only with edge_energy among the observables")

        def maps():
            late = [t for t in self.map_times if t > float(self.spec["integration"]["t_final"])]
            if late:
                raise ParameterError("map_times", late, f"times <= t_final = {self.spec['integration']['t_final']:g}")
            times = sample_schedule(self.settings) * self.settings.dt
            at = map_samples(times, self.map_times)
            if len(set(at)) < len(at):
                raise ParameterError("map_times", self.map_times, "times whose nearest samples differ (samples_per_decade "
                                     f"{self.spec['integration']['samples_per_decade']}: the samples are "
                                     f"{', '.join(f'{t:g}' for t in times[at])})")

        def window():
            if self.window is not None and self.alignment:
                raise ParameterError("window", self.spec["integration"]["window"],
                                     "absent with log_gali or sali among the observables (GALI's vectors do not "
                                     "restrict to a window)")

        def lattice():
            given = self.spec["lattice"]
            if chain_file and known_chain:
                self.file_chain  # noqa: B018 (reads and checks the file)
            elif not chain_file and ("N" in given) == bool(given["shape"]):
                raise ParameterError("N", given.get("N"), "an integer >= 2, or lattice.shape, or lattice.chain_file "
                                     "(one of them)")
            if not chain_file:
                geometry = self.geometry
                flat = [m for m in self.models if MODELS[m].lattice == "beads"]
                if geometry.dimension == 2 and flat:
                    raise ParameterError("shape", list(geometry.shape),
                                         f"[N] with the models {flat} (two axes: the Klein-Gordon and DNLS models)")
                if geometry.dimension == 2 and self.selected:
                    raise ParameterError("excitation.site", "selected", "centre or [i, j] on a square lattice")

        check("lattice.model", models)
        check("observables", observables)
        check("figures", figures)
        check("laws.fits", laws)
        check("laws.walls.edge_energy", walls)
        check("lattice", lattice)
        check("integration", lambda: self.settings)
        check("integration.window", window)
        check("integration.map_times", maps)
        kind = self.spec["excitation"]["kind"]
        # a site picked by the excitation rule is a bead of the chain (no need to pick it here)
        if not errors and known_chain and not (self.selected and kind == "site"):
            check("excitation.mode" if kind == "mode" else "excitation.site", self._check_excitation)
        if errors:
            raise StudyError(errors)

    # ---- orbits and jobs --------------------------------------------------------------------

    def items(self) -> list[tuple[str, int, int]]:
        """Every (model, energy index, realization index), in the fixed order jobs are cut from.

        Returns
        -------
        list of tuple of (str, int, int)
            The items, model by model, then energy, then realization.
        """
        return [(m, e, r) for m in self.models for e in range(self.n_energies) for r in range(self.realizations)]

    @property
    def per_job(self) -> int:
        """Items of one job: orbits_per_job orbits, at least one item (its lanes together)."""
        return max(1, int(self.spec["jobs"]["orbits_per_job"]) // self.lanes)

    @property
    def n_groups(self) -> int:
        """Number of groups (jobs) the items are cut into, :attr:`per_job` each."""
        return max(1, math.ceil(len(self.items()) / self.per_job))

    def group_items(self, group: int) -> list[tuple[str, int, int]]:
        """The items of one group (job).

        Parameters
        ----------
        group : int
            The group's index, 0..n_groups - 1.

        Returns
        -------
        list of tuple of (str, int, int)
            Its slice of :meth:`items`.

        Raises
        ------
        ParameterError
            For a group outside 0..n_groups - 1.
        """
        if not 0 <= group < self.n_groups:
            raise ParameterError("group", group, f"0..{self.n_groups - 1}")
        return self.items()[group * self.per_job:(group + 1) * self.per_job]

    def orbits(self, items) -> list[Orbit]:
        """The orbits of ``items``, every lane of each.

        Parameters
        ----------
        items : iterable of tuple of (str, int, int)
            (model, energy index, realization index), as :meth:`items` gives them.

        Returns
        -------
        list of chainchaos.run.orbits.Orbit
            For each item in order, its :attr:`lanes` orbits.
        """
        energies = self.energies
        excitations = {r: self.excitation(r) for r in sorted({r for *_, r in items})}
        return [Orbit(model=m, energy=float(energies[e]), chain=self.lattices(m)[r], site=excitations[r].site,
                      lane=lane, excitation=excitations[r])
                for m, e, r in items for lane in range(self.lanes)]


def study_names(root: Path | None = None) -> list[str]:
    """The studies in ``root`` (default :func:`studies_dir`): the stems of its YAML files.

    Parameters
    ----------
    root : path, optional
        The folder (default :func:`studies_dir`).

    Returns
    -------
    list of str
        The study names, sorted.
    """
    return sorted(p.stem for p in (studies_dir() if root is None else Path(root)).glob("*.yaml"))
