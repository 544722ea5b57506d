"""Integrate one scene (model, energy) and return its observables as an xarray Dataset.

Only the requested observables are computed: the tangent dynamics runs only for ``mlce``, ``dvd``
and ``dvd_participation``, gap bookkeeping only for the gap observables, and modal energies only
for ``mode_energy``, ``spectral_entropy`` and ``eta``. The relative energy error is always
recorded: it is the guard of every run.
"""

import math
import sys
import time as wallclock
from dataclasses import asdict, dataclass, field

import numpy as np
import xarray as xr

from chainchaos import exactmath
from chainchaos import observables as obs
from chainchaos.errors import SimulationError, require, require_finite_positive
from chainchaos.initial import initial_deviation, initial_state
from chainchaos.integrators import advance, get_scheme
from chainchaos.linear import modal_energies, normal_modes, participation_number
from chainchaos.models import coefficients, energy_density, model_id, open_gaps, total_energy
from chainchaos.provenance import provenance_attrs

OBSERVABLES = ("energy_density", "participation", "energy_centre", "mlce", "dvd", "dvd_participation",
               "gap_open", "gap_fraction", "n_gaps", "mode_energy", "spectral_entropy", "eta",
               "energy_error")
TANGENT = {"mlce", "dvd", "dvd_participation"}
GAPS = {"gap_open", "gap_fraction", "n_gaps"}
MODAL = {"mode_energy", "spectral_entropy", "eta"}


def model_observables(model: str) -> tuple:
    """Every observable ``model`` has: gaps exist only in the Hertz chain (the polynomial bonds of
    FPUT and the harmonic chain never open)."""
    model_id(model)
    return OBSERVABLES if model == "hertz" else tuple(o for o in OBSERVABLES if o not in GAPS)


@dataclass
class SceneParameters:
    """Everything that defines a run besides the chain. Times in units of 1/omega_max."""

    model: str
    energy: float
    t_final: float
    dt: float
    integrator: str = "SRKN6b"
    observables: tuple | None = None  # None: every observable of the model (model_observables)
    excited_site: int = 21
    k4_sign: float = 1.0
    deviation_seed: int = 0
    samples_per_decade: int = 40
    t_first_sample: float = 0.1
    check_every: int = 1000
    max_energy_error: float = 1e-2
    name: str = field(default="")

    def __post_init__(self):
        if self.observables is None:
            self.observables = model_observables(self.model)
        model_id(self.model)
        get_scheme(self.integrator)
        require_finite_positive(self, "energy", "t_final", "dt", "t_first_sample")
        require(self.dt <= self.t_final, "dt", self.dt, f"dt <= t_final = {self.t_final}")
        unknown = [o for o in self.observables if o not in OBSERVABLES]
        require(not unknown, "observables", unknown, f"names among {list(OBSERVABLES)}")
        if self.model != "hertz":
            gaps = sorted(GAPS & set(self.observables))
            require(not gaps, "observables", gaps, "gap observables only with model 'hertz'")
        require(self.k4_sign in (1, -1), "K4_sign", self.k4_sign, "+1 (paper) or -1 (Taylor expansion)")
        require(isinstance(self.samples_per_decade, int) and self.samples_per_decade >= 1,
                "samples_per_decade", self.samples_per_decade, "an integer >= 1")
        require(isinstance(self.check_every, int) and self.check_every >= 1, "check_every",
                self.check_every, "an integer >= 1")
        require(self.max_energy_error > 0, "max_energy_error", self.max_energy_error, "> 0")
        self.observables = tuple(o for o in OBSERVABLES if o in set(self.observables) | {"energy_error"})
        if not self.name:
            self.name = f"{self.model}_H{self.energy:g}"


def sample_steps(t_final: float, dt: float, per_decade: int, t_first: float) -> np.ndarray:
    """Step indices of the samples: 0, then log-spaced times from t_first to t_final with
    ``per_decade`` per decade, which include every power of ten, rounded to the step grid.

    The times are t_j = 10^(e_0 + j / per_decade) with e_0 = floor(log10(max(t_first, dt))), up
    to the first t_j >= t_final, from the C library's scalar log10 and pow (chainchaos.exactmath),
    not NumPy's vectorised ones, whose last bits depend on the CPU."""
    first = math.floor(math.log10(max(t_first, dt)))
    count = math.ceil((math.log10(t_final) - first) * per_decade) + 1
    exponents = first + np.arange(count) / per_decade
    steps = np.rint(exactmath.exp10(exponents) / dt).astype(np.int64)
    n_final = int(np.rint(t_final / dt))
    steps = np.unique(np.concatenate(([0], steps[(steps >= 1) & (steps < n_final)], [n_final])))
    return steps


class ProgressReporter:
    """Prints simulated time, percent done and estimated time left to stderr, every few seconds."""

    def __init__(self, name: str, t_final: float, every: float = 5.0, stream=None):
        # sys.stderr is looked up when printing, so a redirected stderr (the job's log) is honoured
        self.name, self.t_final, self.every, self.stream = name, t_final, every, stream
        self.start = self.last = wallclock.perf_counter()

    def __call__(self, t: float, fraction: float) -> None:
        now = wallclock.perf_counter()
        if now - self.last < self.every and fraction < 1.0:
            return
        self.last = now
        elapsed = now - self.start
        left = elapsed * (1.0 - fraction) / fraction if fraction > 0 else float("nan")
        print(f"[{self.name}] t = {t:.6g} / {self.t_final:g} ({100 * fraction:5.1f}%), "
              f"elapsed {elapsed:.1f} s, left ~{left:.1f} s", file=self.stream or sys.stderr, flush=True)


def simulate(chain, params: SceneParameters, progress=None) -> xr.Dataset:
    """Integrate the scene and return its Dataset (data contract of DESIGN section 7).

    Raises SimulationError naming the scene, the time and the value when the state becomes
    non-finite or the relative energy error exceeds ``params.max_energy_error``.
    """
    chain = chain.with_k4_sign(params.k4_sign)
    model = model_id(params.model)
    scheme = get_scheme(params.integrator)
    wanted = set(params.observables)
    tangent = bool(wanted & TANGENT)
    track_gaps = bool(wanted & GAPS)
    N = chain.N

    q, p, u0 = initial_state(model, chain, params.energy, params.excited_site)
    dq, dp = initial_deviation(N, params.deviation_seed)
    deviation0 = np.concatenate([dq, dp])
    if not tangent:
        dq, dp = np.zeros(N), np.zeros(N)
    H0 = float(total_energy(model, chain, q, p))

    steps = sample_steps(params.t_final, params.dt, params.samples_per_decade, params.t_first_sample)
    times = steps * params.dt
    S = steps.size
    Q, Pm = np.empty((S, N)), np.empty((S, N))
    DQ, DP = np.empty((S, N)), np.empty((S, N))
    log_growth = np.zeros(S)
    gap_steps = np.zeros((S, N + 1), dtype=np.int64)
    max_gaps = np.zeros(S, dtype=np.int64)
    energy_error = np.zeros(S)
    Q[0], Pm[0], DQ[0], DP[0] = q, p, dq, dp

    inv_mass = 1.0 / chain.mass
    K2, K3, K4 = coefficients(model, chain)
    f, k = np.empty(N + 1), np.empty(N + 1)
    diagnostics = np.zeros(2)
    counts = np.zeros(N + 1, dtype=np.int64)
    if track_gaps:
        max_gaps[0] = int(open_gaps(chain, q).sum())

    for i in range(1, S):
        counts[:] = 0
        diagnostics[1] = 0.0
        bad = advance(model, q, p, dq, dp, inv_mass, chain.A, chain.delta, K2, K3, K4,
                      scheme.kicks, scheme.drifts, params.dt, int(steps[i] - steps[i - 1]), tangent,
                      params.check_every, track_gaps, counts, diagnostics, f, k)
        if bad >= 0:
            raise SimulationError(params.name, (steps[i - 1] + bad) * params.dt,
                                  "non-finite state (the orbit escaped to infinity or the step is unstable)",
                                  float("nan"))
        Q[i], Pm[i], DQ[i], DP[i] = q, p, dq, dp
        log_growth[i] = diagnostics[0]
        gap_steps[i] = counts
        max_gaps[i] = int(diagnostics[1])
        energy_error[i] = abs(total_energy(model, chain, q, p) - H0) / abs(H0)
        if not energy_error[i] <= params.max_energy_error:
            raise SimulationError(params.name, times[i], "relative energy error", energy_error[i],
                                  f"{params.max_energy_error:g}")
        if progress is not None:
            progress(times[i], steps[i] / steps[-1])

    return _dataset(chain, params, model, times, steps, Q, Pm, DQ, DP, log_growth, gap_steps, max_gaps,
                    energy_error, u0, H0, deviation0)


def _dataset(chain, params, model, times, steps, Q, Pm, DQ, DP, log_growth, gap_steps, max_gaps,
             energy_error, u0, H0, deviation0) -> xr.Dataset:
    wanted = set(params.observables)
    N = chain.N
    data = {}
    one = {"units": "1"}

    def put(name, dims, values, long_name, always=False, **attrs):
        if name in wanted or always:
            data[name] = (dims, values, {**one, "long_name": long_name, **attrs})

    if wanted & {"energy_density", "participation", "energy_centre"}:
        h = energy_density(model, chain, Q, Pm)
        put("energy_density", ("time", "site"), h, "normalised energy density h_n")
        put("participation", "time", participation_number(h, axis=-1), "participation number P = 1/sum h_n^2")
        put("energy_centre", "time", obs.energy_centre(h), "energy centre X = sum n h_n")
    if wanted & TANGENT:
        w = obs.deviation_vector_density(DQ, DP)
        put("mlce", "time", obs.finite_time_mlce(log_growth, times),
            "finite-time maximum Lyapunov characteristic exponent Lambda(t)")
        put("dvd", ("time", "site"), w, "deviation vector density w_n")
        put("dvd_participation", "time", participation_number(w, axis=-1),
            "participation number of the deviation vector density P_D")
        data["initial_deviation"] = ("component", deviation0, {
            **one, "long_name": "initial deviation vector (du_1..du_N, dp_1..dp_N)"})
    if wanted & GAPS:
        is_open = open_gaps(chain, Q)
        dsteps = np.diff(steps, prepend=0)
        fraction = np.where(dsteps[:, None] > 0, gap_steps / np.maximum(dsteps, 1)[:, None], is_open)
        put("gap_open", ("time", "bond"), is_open.astype(np.int8), "bond open (delta_n + u_{n-1} - u_n < 0)",
            flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="closed open")
        put("gap_fraction", ("time", "bond"), fraction, "fraction of steps the bond was open since the previous sample")
        put("n_gaps", "time", is_open.sum(axis=-1).astype(np.int32), "number of open gaps")
        if "n_gaps" in wanted:
            data["n_gaps_max"] = ("time", max_gaps.astype(np.int32), {
                **one, "long_name": "largest number of simultaneously open gaps since the previous sample"})
    if wanted & MODAL:
        omega, U = normal_modes(chain)
        E = modal_energies(chain, omega, U, Q, Pm)
        S_t = obs.spectral_entropy(E)
        put("mode_energy", ("time", "mode"), E, "harmonic energy E_k of linear mode k")
        put("spectral_entropy", "time", S_t, "spectral entropy S = -sum v_k ln v_k")
        put("eta", "time", obs.normalised_entropy(S_t, S_t[0], N), "normalised spectral entropy eta",
            equipartition_value=obs.equipartition_eta(S_t[0], N))
        data["frequency"] = ("mode", omega, {**one, "long_name": "linear mode frequency omega_k / omega_max"})
    put("energy_error", "time", energy_error, "relative energy error |H(t) - H(0)| / H(0)", always=True)

    ds = xr.Dataset(data, coords={"time": times, "site": np.arange(1, N + 1), "bond": np.arange(1, N + 2),
                                  "mode": np.arange(1, N + 1)})
    ds.time.attrs.update(units="1", long_name="time",
                         comment="nondimensional time, unit 1/omega_max of the homogeneous linear chain")
    ds.site.attrs.update(units="1", long_name="bead index n")
    ds.bond.attrs.update(units="1", long_name="bond index (bond n joins beads n-1 and n)")
    ds.mode.attrs.update(units="1", long_name="mode number, by increasing frequency")
    parameters = {k: (list(v) if isinstance(v, tuple) else v) for k, v in asdict(params).items()}
    parameters["chain_seed"] = chain.seed
    ds.attrs.update(provenance_attrs(parameters))
    ds.attrs.update(
        title=f"chainchaos scene {params.name}", scene=params.name, model=params.model,
        energy=float(params.energy), total_energy=H0, u0=float(u0), dt=float(params.dt),
        integrator=params.integrator, integrator_order=get_scheme(params.integrator).order,
        t_final=float(times[-1]), K4_sign=float(params.k4_sign), excited_site=int(params.excited_site),
        seed=-1 if chain.seed is None else int(chain.seed), deviation_seed=int(params.deviation_seed),
        alpha=float(chain.alpha), observables=" ".join(params.observables),
        final_energy_error=float(energy_error[-1]), max_energy_error=float(energy_error.max()),
    )
    return ds


def warm_up() -> str:
    """Compile (or load from the on-disk cache) every kernel a scene uses; returns the cache dir."""
    import os

    from chainchaos.chain import random_chain

    chain = random_chain(0, 2.0, 4)
    for model in ("hertz", "fput"):
        simulate(chain, SceneParameters(model, 0.01, 1.0, 0.1, excited_site=2))
    return os.environ.get("NUMBA_CACHE_DIR", "")
