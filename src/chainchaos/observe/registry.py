"""The observables a scene file can hold: a registry, one entry each.

An :class:`Observable` gives its name (the NetCDF variable), its dimensions, what the run must
provide for it (``needs``: the tangent map, gap counting, the linear modes), how it is computed
from the sampled run (a :class:`SampledRun`, whose shared intermediates are computed once), its CF
attributes and its axis label. ``simulate`` runs only what the requested observables need and
writes each one's variable from here; ``panels.KIND_OBSERVABLES`` (the panel table) says which
panels read which. Adding an observable is an entry here (and a panel kind that reads it).
An indicator's ``reference`` names the paper that defines it, and :data:`NEED_REFERENCES` the
method behind a need (the tangent map): docs/reference/citing.md lists them
(``chainchaos.output.citing``).
Entries with ``selectable=False`` are written along with another (``companions``), never asked
for by name. The orbit sets of the scans, the search and the verdicts (``chainchaos.run.orbits``)
record their per-orbit series from here too. Quantities are dimensionless (docs/conventions.md#observables).
"""

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from chainchaos.observe import formulas as obs
from chainchaos.observe.labels import LABELS
from chainchaos.system.linear import modal_energies, normal_modes, participation_number
from chainchaos.system.models import energy_density, get_model, open_bonds

TANGENT, GAPS, MODES = "tangent", "gaps", "modes"
#: Need of the observables of a split model's second conserved quantity, the norm.
NORM = "norm"
#: Needs of the chaos indicators beyond the mLCE: deviation vectors kept orthonormal (the
#: Lyapunov spectrum) or only normalised (SALI and GALI); both need the tangent map.
SPECTRUM, ALIGNMENT = "spectrum", "alignment"

#: The chaos indicators' papers: the Lyapunov exponents', SALI's and GALI's as docs/conventions.md
#: cites them; the deviation vector distribution's and the tangent map method's (below) with the
#: authors, titles and numbers of their arXiv records (1307.0116, 1006.0154).
LYAPUNOV = ("Benettin, Galgani, Giorgilli & Strelcyn, Meccanica 15, 9 and 21 (1980): the Lyapunov "
            "characteristic exponents and their computation")
SALI_PAPER = "Skokos, J. Phys. A 34, 10029 (2001): the smaller alignment index SALI"
GALI_PAPER = "Skokos, Bountis & Antonopoulos, Physica D 231, 30 (2007): the generalized alignment index GALI_k"
DVD_PAPER = ("Skokos, Gkolias & Flach, \"Nonequilibrium chaos of disordered nonlinear waves\", Phys. Rev. Lett. "
             "111, 064101 (2013): the deviation vector distribution")
#: The method behind each need of an observable that has one: what a user of the observable
#: cites beside the observable's own reference.
NEED_REFERENCES: dict[str, str] = {
    TANGENT: ("Skokos & Gerlach, \"Numerical integration of variational equations\", arXiv:1006.0154 (2010): "
              "the tangent map method"),
}


class SampledRun:
    """One scene's samples, (S, N) arrays over the sample times, and what several observables
    derive from them, each computed once on first use.

    Made by ``Samples.run`` (lane j of a sampled problem). S is the number of samples, N of
    sites; units of docs/conventions.md#units.

    Parameters
    ----------
    model : Model
        The model that ran.
    chain : Chain or KGLattice
        The lane's lattice.
    times : numpy.ndarray of shape (S,)
        Sample times, in the model's time unit.
    steps : numpy.ndarray of shape (S,), dtype int
        Sample steps.
    Q, P : numpy.ndarray of shape (S, N)
        Displacements and momenta.
    DQ, DP : numpy.ndarray of shape (S, N)
        The mLCE deviation vector.
    log_growth : numpy.ndarray of shape (S,)
        ln(|v(t)| / |v(0)|) of the mLCE vector.
    gap_steps : numpy.ndarray of shape (S, N + 1), dtype int
        Steps each bond was open since the previous sample.
    max_gaps : numpy.ndarray of shape (S,), dtype int
        Largest number of simultaneously open bonds since the previous sample.
    energy_error : numpy.ndarray of shape (S,)
        Relative energy error (dimensionless).
    deviation0 : numpy.ndarray of shape (2 N,) or None
        The initial deviation vector (du, dp).
    spectrum_growth : numpy.ndarray of shape (S, spectrum), optional
        Accumulated ln of the norms of the spectrum's vectors, the mLCE vector's first.
    log_gali, sali : numpy.ndarray of shape (S,), optional
        ln GALI_k and SALI (NaN where not computed).
    gali_order : int, default 1
        k of GALI_k.
    norm_error : numpy.ndarray of shape (S,), optional
        Relative norm error of a split model (None for a bond model).
    """

    def __init__(self, model, chain, times, steps, Q, P, DQ, DP, log_growth, gap_steps, max_gaps, energy_error,
                 deviation0, spectrum_growth=None, log_gali=None, sali=None, gali_order=1, norm_error=None):
        self.model, self.chain, self.times, self.steps = model, chain, times, steps
        self.Q, self.P, self.DQ, self.DP = Q, P, DQ, DP
        self.log_growth, self.gap_steps, self.max_gaps = log_growth, gap_steps, max_gaps
        self.energy_error, self.deviation0 = energy_error, deviation0
        self.spectrum_growth, self.log_gali, self.sali, self.gali_order = spectrum_growth, log_gali, sali, gali_order
        self.norm_error = norm_error

    @cached_property
    def spectrum(self) -> np.ndarray:
        """(S, spectrum) finite-time Lyapunov exponents, in units of 1 / the model's time unit."""
        return obs.lyapunov_spectrum(self.spectrum_growth, self.times)

    @cached_property
    def energy_density(self) -> np.ndarray:
        """(S, N) normalised energy density h_n (``models.energy_density``)."""
        return energy_density(self.model, self.chain, self.Q, self.P)

    @cached_property
    def norm_density(self) -> np.ndarray:
        """(S, N) normalised norm density z_n = |psi_n|^2 / S of a split model
        (``obs.norm_density``)."""
        return obs.norm_density(self.Q, self.P)

    @cached_property
    def density(self) -> np.ndarray:
        """(S, N) the distribution whose spreading the packet observables measure: the norm
        density of a split model (its energy density may be negative), the energy density of a
        bond model."""
        return self.norm_density if self.model.is_split else self.energy_density

    @cached_property
    def dvd(self) -> np.ndarray:
        """(S, N) deviation vector density w_n."""
        return obs.deviation_vector_density(self.DQ, self.DP)

    @cached_property
    def is_open(self) -> np.ndarray:
        """(S, N + 1) whether each bond is open at each sample."""
        return open_bonds(self.model, self.chain, self.Q)

    @cached_property
    def modes(self) -> tuple[np.ndarray, np.ndarray]:
        """The lattice's linear modes, (omega, U) of ``linear.normal_modes``."""
        return normal_modes(self.chain)

    @cached_property
    def mode_energy(self) -> np.ndarray:
        """(S, N) harmonic energy E_k of every linear mode, in the model's energy unit."""
        omega, U = self.modes
        return modal_energies(self.chain, omega, U, self.Q, self.P)

    @cached_property
    def spectral_entropy(self) -> np.ndarray:
        """(S,) spectral entropy S = -sum v_k ln v_k of the mode energies."""
        return obs.spectral_entropy(self.mode_energy)


def _density(run: SampledRun) -> dict:
    """The attribute that says a packet observable of a split model is taken on its norm density
    (none for a bond model's, on the energy density its long_name names)."""
    return {"density": "norm density |psi_n|^2 / S"} if run.model.is_split else {}


def _positions(run: SampledRun) -> np.ndarray:
    """The sites' positions on the run's lattice (``formulas.site_positions`` of its geometry)."""
    return obs.site_positions(run.chain.geometry)


def _gap_fraction(run: SampledRun) -> np.ndarray:
    """Fraction of the steps since the previous sample that each bond ended open (at t = 0: open
    or not)."""
    dsteps = np.diff(run.steps, prepend=0)
    return np.where(dsteps[:, None] > 0, run.gap_steps / np.maximum(dsteps, 1)[:, None], run.is_open)


@dataclass(frozen=True, kw_only=True)
class Observable:
    """An observable a scene file can hold: an entry of ``REGISTRY`` (``chainchaos.OBSERVABLES``).

    Parameters
    ----------
    name : str
        The NetCDF variable's name and the registry key.
    dims : tuple of str
        Its dimensions (``"time"``, ``"site"``, ``"bond"``, ``"mode"``, ...).
    long_name : str
        The CF ``long_name`` attribute: what it is.
    label : str
        Its axis label (matplotlib mathtext).
    compute : callable
        ``compute(run)``: its values from a :class:`SampledRun`, dimensionless.
    needs : frozenset of str, optional
        What the run must provide: TANGENT, SPECTRUM, ALIGNMENT, GAPS, MODES (default none).
    attrs : callable, optional
        ``attrs(run)``: further CF attributes (default none).
    dtype : type, optional
        The type it is written as (default: as computed).
    companions : tuple of str, optional
        Observables written whenever this one is.
    selectable : bool, optional
        Whether a scene may ask for it by name (default True; False: only as a companion).
    by_default : bool, optional
        Whether it is among a model's observables when a scene names none (default True).
    reference : str, optional
        The paper that defines it (the chaos indicators), for docs/reference/citing.md.
    """

    name: str
    dims: tuple[str, ...]
    long_name: str
    label: str  # axis label (matplotlib mathtext)
    compute: Callable[[SampledRun], np.ndarray]
    needs: frozenset = frozenset()
    attrs: Callable[[SampledRun], dict] = field(default=lambda run: {})  # further CF attributes
    dtype: type | None = None
    companions: tuple[str, ...] = ()  # written whenever this one is
    selectable: bool = True
    by_default: bool = True  # among a model's observables when a scene names none (costly ones are not)
    reference: str = ""  # the paper that defines it (the chaos indicators), for docs/reference/citing.md

    @property
    def references(self) -> tuple[str, ...]:
        """What a user of this observable cites: its own paper, then the methods of its needs."""
        own = (self.reference,) if self.reference else ()
        return own + tuple(NEED_REFERENCES[need] for need in sorted(self.needs) if need in NEED_REFERENCES)


def _registry(*entries: Observable) -> dict[str, Observable]:
    return {o.name: o for o in entries}


#: Every variable a scene file can hold, in file order.
REGISTRY: dict[str, Observable] = _registry(
    Observable(name="energy_density", dims=("time", "site"), long_name="normalised energy density h_n",
               label=LABELS["energy_density"],
               compute=lambda run: run.energy_density),
    Observable(name="participation", dims=("time",), long_name="participation number P = 1/sum h_n^2",
               label=LABELS["participation"],
               compute=lambda run: participation_number(run.density, axis=-1), attrs=_density),
    Observable(name="energy_centre", dims=("time",), long_name="energy centre X = sum n h_n",
               label=LABELS["energy_centre"],
               compute=lambda run: obs.energy_centre(run.density), attrs=_density),
    Observable(name="second_moment", dims=("time",),
               long_name="second moment m2 = sum_n (n - X)^2 h_n of the energy distribution",
               label=LABELS["second_moment"],
               compute=lambda run: obs.second_moment(run.density, _positions(run)), attrs=_density,
               by_default=False),
    Observable(name="compactness", dims=("time",),
               long_name="compactness index zeta = P^2 / m2 of the energy distribution", label=LABELS["compactness"],
               compute=lambda run: obs.compactness(participation_number(run.density, axis=-1),
                                                   obs.second_moment(run.density, _positions(run))),
               attrs=_density, by_default=False),
    Observable(name="edge_energy", dims=("time",),
               long_name=f"fraction of the energy within {obs.EDGE_MARGIN} sites of an edge",
               label=LABELS["edge_energy"], compute=lambda run: obs.edge_energy(run.density, _positions(run)),
               attrs=_density,
               by_default=False),
    Observable(name="largest_share", dims=("time",),
               long_name="largest share max_n h_n of the distribution on one site (self-trapping above 1/2)",

               label=LABELS["largest_share"], compute=lambda run: run.density.max(axis=-1), attrs=_density, by_default=False),
    Observable(name="mlce", dims=("time",), long_name="finite-time maximum Lyapunov characteristic exponent Lambda(t)",
               label=LABELS["mlce"],
               compute=lambda run: obs.finite_time_mlce(run.log_growth, run.times), needs=frozenset({TANGENT}),
               companions=("initial_deviation",), reference=LYAPUNOV),
    Observable(name="log_growth", dims=("time",),
               long_name="logarithmic growth ln(|v(t)|/|v(0)|) = Lambda(t) t of the deviation vector",
               label=LABELS["log_growth"], compute=lambda run: run.log_growth, needs=frozenset({TANGENT}),
               companions=("initial_deviation",), reference=LYAPUNOV),
    Observable(name="lyapunov_spectrum", dims=("time", "exponent"),
               long_name="finite-time Lyapunov exponents lambda_i(t)", label=LABELS["lyapunov_spectrum"],
               compute=lambda run: run.spectrum, needs=frozenset({TANGENT, SPECTRUM}),
               companions=("initial_deviation",), by_default=False, reference=LYAPUNOV),
    Observable(name="ks_entropy", dims=("time",),
               long_name="Kolmogorov-Sinai entropy estimate: sum of the positive exponents",
               label=LABELS["ks_entropy"], compute=lambda run: obs.ks_entropy(run.spectrum),
               needs=frozenset({TANGENT, SPECTRUM}), companions=("initial_deviation",), by_default=False,
               reference=LYAPUNOV),
    Observable(name="sali", dims=("time",),
               long_name="smaller alignment index SALI of the mLCE vector and a second deviation vector",
               label=LABELS["sali"], compute=lambda run: run.sali, needs=frozenset({TANGENT, ALIGNMENT}),
               companions=("initial_deviation",), by_default=False, reference=SALI_PAPER),
    Observable(name="log_gali", dims=("time",), long_name="natural logarithm of the generalized alignment index GALI_k",
               label=LABELS["log_gali"], compute=lambda run: run.log_gali, needs=frozenset({TANGENT, ALIGNMENT}),
               companions=("initial_deviation",), attrs=lambda run: {"k": np.int32(run.gali_order)}, by_default=False,
               reference=GALI_PAPER),
    Observable(name="dvd", dims=("time", "site"), long_name="deviation vector density w_n", label=LABELS["dvd"],
               compute=lambda run: run.dvd, needs=frozenset({TANGENT}), companions=("initial_deviation",),
               reference=DVD_PAPER),
    Observable(name="dvd_participation", dims=("time",),
               long_name="participation number of the deviation vector density P_D", label=LABELS["dvd_participation"],
               compute=lambda run: participation_number(run.dvd, axis=-1), needs=frozenset({TANGENT}),
               companions=("initial_deviation",), reference=DVD_PAPER),
    Observable(name="initial_deviation", dims=("component",),
               long_name="initial deviation vector (du_1..du_N, dp_1..dp_N)", label=LABELS["initial_deviation"],
               compute=lambda run: run.deviation0, needs=frozenset({TANGENT}), selectable=False),
    Observable(name="gap_open", dims=("time", "bond"), long_name="bond open (delta_n + u_{n-1} - u_n < 0)",
               label=LABELS["gap_open"], compute=lambda run: run.is_open, needs=frozenset({GAPS}), dtype=np.int8,
               attrs=lambda run: {"flag_values": np.array([0, 1], dtype=np.int8), "flag_meanings": "closed open"}),
    Observable(name="gap_fraction", dims=("time", "bond"),
               long_name="fraction of steps the bond was open since the previous sample",
               label=LABELS["gap_fraction"], compute=_gap_fraction, needs=frozenset({GAPS})),
    Observable(name="n_gaps", dims=("time",), long_name="number of open gaps", label=LABELS["n_gaps"],
               compute=lambda run: run.is_open.sum(axis=-1), needs=frozenset({GAPS}), dtype=np.int32,
               companions=("n_gaps_max",)),
    Observable(name="n_gaps_max", dims=("time",),
               long_name="largest number of simultaneously open gaps since the previous sample",
               label=LABELS["n_gaps_max"], compute=lambda run: run.max_gaps, needs=frozenset({GAPS}), dtype=np.int32,
               selectable=False),
    Observable(name="mode_energy", dims=("time", "mode"), long_name="harmonic energy E_k of linear mode k",
               label=LABELS["mode_energy"], compute=lambda run: run.mode_energy, needs=frozenset({MODES}),
               companions=("frequency",)),
    Observable(name="spectral_entropy", dims=("time",), long_name="spectral entropy S = -sum v_k ln v_k",
               label=LABELS["spectral_entropy"],
               compute=lambda run: run.spectral_entropy, needs=frozenset({MODES}), companions=("frequency",)),
    Observable(name="eta", dims=("time",), long_name="normalised spectral entropy eta", label=LABELS["eta"],
               compute=lambda run: obs.normalised_entropy(run.spectral_entropy, run.spectral_entropy[0], run.chain.N),
               needs=frozenset({MODES}), companions=("frequency",),
               attrs=lambda run: {"equipartition_value": obs.equipartition_eta(run.spectral_entropy[0], run.chain.N)}),
    Observable(name="frequency", dims=("mode",), long_name="linear mode frequency omega_k / omega_max",
               label=LABELS["frequency"], compute=lambda run: run.modes[0], needs=frozenset({MODES}),
               selectable=False),
    Observable(name="energy_error", dims=("time",), long_name="relative energy error |H(t) - H(0)| / H(0)",
               label=LABELS["energy_error"], compute=lambda run: run.energy_error),
    Observable(name="norm_density", dims=("time", "site"),
               long_name="normalised norm density z_n = |psi_n|^2 / sum_m |psi_m|^2 (a split model's)",
               label=LABELS["norm_density"], compute=lambda run: run.norm_density, needs=frozenset({NORM})),
    Observable(name="density", dims=("time", "site"),
               long_name="the density P, m2 and zeta are measured on: h_n, or a split model's z_n",
               label=LABELS["density"], compute=lambda run: run.density, by_default=False),
    Observable(name="norm_error", dims=("time",), long_name="relative norm error |S(t) - S(0)| / S(0)",
               label=LABELS["norm_error"], compute=lambda run: run.norm_error, needs=frozenset({NORM})),
)

#: The observables a scene may ask for, in file order.
OBSERVABLES: tuple[str, ...] = tuple(name for name, o in REGISTRY.items() if o.selectable)


def needing(need: str) -> frozenset[str]:
    """The selectable observables that need ``need`` (TANGENT, GAPS or MODES).

    Parameters
    ----------
    need : str
        One of TANGENT, SPECTRUM, ALIGNMENT, GAPS, MODES.

    Returns
    -------
    frozenset of str
        The names of those observables.
    """
    return frozenset(name for name in OBSERVABLES if need in REGISTRY[name].needs)


def variables(run: SampledRun, wanted) -> dict:
    """The Dataset variables of the ``wanted`` observables and their companions, in file order.

    Parameters
    ----------
    run : SampledRun
        The sampled run.
    wanted : iterable of str
        Names of ``REGISTRY``.

    Returns
    -------
    dict
        Name to (dims, values, attributes), the attributes with ``units`` "1" and ``long_name``:
        what ``xarray.Dataset`` takes.
    """
    written = set(wanted) | {c for name in wanted for c in REGISTRY[name].companions}
    data = {}
    for name, o in REGISTRY.items():
        if name in written:
            values = o.compute(run)
            values = values.astype(o.dtype) if o.dtype is not None else values
            data[name] = (o.dims, values, {"units": "1", "long_name": o.long_name, **o.attrs(run)})
    return data


def study_observables() -> list[str]:
    """The observables a study keeps per orbit (``chainchaos.studies.study``): the selectable
    time series that need no Lyapunov spectrum and no gap counting.

    Returns
    -------
    list of str
        Their names, in file order.
    """
    return [name for name, o in REGISTRY.items()  # with the observables of one's own registered (observe.own)
            if o.selectable and o.dims == ("time",) and not o.needs & {SPECTRUM, GAPS}]


def model_observables(model: str) -> tuple:
    """The observables of ``model`` a scene computes when it names none: every one computed by
    default (not the costly chaos indicators beyond the mLCE), the gap observables only where
    bonds open (Hertz).

    Parameters
    ----------
    model : str or Model
        The model.

    Returns
    -------
    tuple of str
        Their names, in file order.
    """
    model = get_model(model)
    if model.is_split:  # the norm density replaces the energy density, which may be negative
        left_out = needing(GAPS) | needing(MODES) | {"energy_density"}
    else:
        left_out = (frozenset() if model.has_gaps else needing(GAPS)) | needing(NORM)
    return tuple(o for o in OBSERVABLES if REGISTRY[o].by_default and o not in left_out)
